"""Wrong (fails 'stretch falls'): ignores `iterations`: a single sweep."""
import numpy as np


def satisfy_rods(x: np.ndarray, a: np.ndarray, b: np.ndarray, rest: np.ndarray, w: np.ndarray,
                 iterations: int) -> np.ndarray:
    x = x.copy()
    for _ in range(1):
        for k in range(len(a)):
            i, j = a[k], b[k]
            if w[i] + w[j] == 0:
                continue
            delta = x[j] - x[i]
            d = max(np.linalg.norm(delta), 1e-9)
            diff = (d - rest[k]) / d
            x[i] += delta * diff * w[i] / (w[i] + w[j])
            x[j] -= delta * diff * w[j] / (w[i] + w[j])
    return x
