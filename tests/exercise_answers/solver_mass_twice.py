"""Wrong (fails 'a = f / m'): f / m / m."""
import numpy as np


def derivative(state: np.ndarray, masses: np.ndarray, forces: list) -> np.ndarray:
    n = len(masses)
    x = state[:2 * n].reshape(n, 2)
    v = state[2 * n:].reshape(n, 2)
    f = np.zeros((n, 2))
    for force in forces:
        force(x, v, f)
    return np.concatenate([v.ravel(), (f / masses[:, None] / masses[:, None]).ravel()])
