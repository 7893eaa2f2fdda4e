"""Wrong (fails 'pinned never move' and 'shares by inverse mass'): splits each correction
50/50, ignoring the inverse masses."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = x.copy()
    for _ in range(iterations):
        for i, j, r in zip(a, b, rest):
            delta = x[j] - x[i]
            length = max(np.linalg.norm(delta), 1e-9)
            diff = (length - r) / length
            x[i] += delta * diff * 0.5
            x[j] -= delta * diff * 0.5
    return x
