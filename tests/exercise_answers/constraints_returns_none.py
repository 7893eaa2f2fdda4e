"""Wrong (every check: 'returned None'): correct rods in place, but no return statement."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    for _ in range(iterations):
        for k in range(len(a)):
            i, j = a[k], b[k]
            if w[i] + w[j] == 0:
                continue
            d = x[j] - x[i]
            length = max(float(np.hypot(*d)), 1e-9)
            diff = (length - rest[k]) / length
            x[i] += d * diff * w[i] / (w[i] + w[j])
            x[j] -= d * diff * w[j] / (w[i] + w[j])
