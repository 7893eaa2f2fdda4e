"""Wrong (fails 'pinned never move'): no skip when both ends are pinned: 0 / 0."""
import numpy as np


def satisfy_rods(x: np.ndarray, a: np.ndarray, b: np.ndarray, rest: np.ndarray, w: np.ndarray,
                 iterations: int) -> np.ndarray:
    x = x.copy()
    for _ in range(iterations):
        for k in range(len(a)):
            i, j = a[k], b[k]
            delta = x[j] - x[i]
            d = max(np.linalg.norm(delta), 1e-9)
            diff = (d - rest[k]) / d
            x[i] += delta * diff * w[i] / (w[i] + w[j])
            x[j] -= delta * diff * w[j] / (w[i] + w[j])
    return x
