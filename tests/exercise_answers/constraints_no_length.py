"""Wrong (fails 'one rod, one pass'): the correction is not divided by the length."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = x.copy()
    for _ in range(iterations):
        for i, j, r in zip(a, b, rest):
            if w[i] + w[j] == 0:
                continue
            delta = x[j] - x[i]
            diff = np.linalg.norm(delta) - r
            x[i] += delta * diff * w[i] / (w[i] + w[j])
            x[j] -= delta * diff * w[j] / (w[i] + w[j])
    return x
