"""Wrong (fails 'coincident particles'): divides by a length that can be 0."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = x.copy()
    for _ in range(iterations):
        for i, j, r in zip(a, b, rest):
            if w[i] + w[j] == 0:
                continue
            delta = x[j] - x[i]
            length = np.linalg.norm(delta)
            with np.errstate(divide="ignore", invalid="ignore"):
                diff = (length - r) / length
            x[i] += delta * diff * w[i] / (w[i] + w[j])
            x[j] -= delta * diff * w[j] / (w[i] + w[j])
    return x
