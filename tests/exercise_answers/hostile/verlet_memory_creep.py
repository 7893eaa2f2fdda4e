"""Hostile: allocates and touches 100 MB at a time in the step until something stops it (once,
a machine swapping until the time limit): the child's memory cap makes it a MemoryError."""
import numpy as np

_hoard = []


def verlet_step(x, x_prev, a, h, drag):
    while True:
        _hoard.append(np.ones(12_500_000))
