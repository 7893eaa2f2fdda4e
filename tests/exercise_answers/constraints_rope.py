"""Wrong (fails 'a squashed rod pushes'): a rod that only pulls, like a rope: a squashed rod is
skipped and stays squashed."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = np.array(x, dtype=float)
    for _ in range(iterations):
        for i, j, r in zip(a, b, rest):
            if w[i] + w[j] == 0:
                continue
            d = x[j] - x[i]
            length = max(float(np.hypot(*d)), 1e-9)
            if length <= r:
                continue
            move = (length - r) / (length * (w[i] + w[j])) * d
            x[i] += w[i] * move
            x[j] -= w[j] * move
    return x
