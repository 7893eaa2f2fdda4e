"""Hostile: points every fd above 2 at its own stdout (os.dup2(1, fd)), so the grader's frames go
into the output pipe, then gives a right step."""
import os

for fd in range(3, 64):
    try:
        os.fstat(fd)
        os.dup2(1, fd)
    except OSError:
        pass


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
