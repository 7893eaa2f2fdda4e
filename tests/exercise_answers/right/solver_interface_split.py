"""Right: n from the state's length, x and v copied out, the gather by np.hstack."""
import numpy as np


def derivative(state, masses, forces):
    n = len(state) // 4
    x = state[:2 * n].reshape(n, 2).copy()
    v = state[2 * n:].reshape(n, 2).copy()
    f = np.zeros((n, 2))
    for force in forces:
        force(x, v, f)
    return np.hstack([v.ravel(), (f / np.asarray(masses)[:, None]).ravel()])
