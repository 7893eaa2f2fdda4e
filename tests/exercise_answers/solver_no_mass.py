"""Wrong (fails 'a = f / m'): gathers the force, not the acceleration."""
import numpy as np


def derivative(state, masses, forces):
    n = len(masses)
    x = state[:2 * n].reshape(n, 2)
    v = state[2 * n:].reshape(n, 2)
    f = np.zeros((n, 2))
    for force in forces:
        force(x, v, f)
    return np.concatenate([v.ravel(), f.ravel()])
