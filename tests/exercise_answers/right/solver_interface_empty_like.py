"""Right: n from the state's length, the result filled into np.empty_like(state) in place, the
masses broadcast with reshape."""
import numpy as np


def derivative(state, masses, forces):
    n = len(state) // 4
    x = state[:2 * n].reshape(-1, 2)
    v = state[2 * n:].reshape(-1, 2)
    f = np.zeros_like(x)
    for force in forces:
        force(x, v, f)
    out = np.empty_like(state, dtype=float)
    out[:2 * n] = state[2 * n:]
    out[2 * n:] = (f / np.reshape(masses, (-1, 1))).ravel()
    return out
