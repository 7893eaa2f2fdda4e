"""Hostile: closes every file descriptor above 2 (the channel among them) at import, then gives
a right step."""
import os

os.closerange(3, 4096)


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
