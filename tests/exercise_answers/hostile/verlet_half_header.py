"""Hostile: writes the first 3 bytes of a frame header on every open descriptor in its step
(once: the grader waited for the rest until killed, 78 s). Each check now fails at once."""
import os


def verlet_step(x, x_prev, a, h, drag):
    for fd in range(3, 64):
        try:
            os.write(fd, b"LAB")
        except OSError:
            pass
    return x + (1 - drag) * (x - x_prev) + a * h * h, x.copy()
