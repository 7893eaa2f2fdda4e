"""Wrong (fails 'random rods and sweeps'): range(iterations + 1): one sweep too many."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = np.array(x, dtype=float)
    for _ in range(iterations + 1):
        for i, j, r in zip(a, b, rest):
            wsum = w[i] + w[j]
            if wsum == 0:
                continue
            d = x[j] - x[i]
            length = float(np.hypot(d[0], d[1]))
            if length == 0:
                continue
            move = (length - r) / (length * wsum) * d
            x[i] += w[i] * move
            x[j] -= w[j] * move
    return x
