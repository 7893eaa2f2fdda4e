"""Wrong (fails 'dx/dt = v'): gathers [f/m, v] instead of [v, f/m]."""
import numpy as np


def derivative(state, masses, forces):
    n = len(masses)
    x = state[:2 * n].reshape(n, 2)
    v = state[2 * n:].reshape(n, 2)
    f = np.zeros((n, 2))
    for force in forces:
        force(x, v, f)
    return np.concatenate([(f / masses[:, None]).ravel(), v.ravel()])
