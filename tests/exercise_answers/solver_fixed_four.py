"""Wrong (fails 'any number of particles'): written for the four particles of the first test."""
import numpy as np


def derivative(state, masses, forces):
    x = state[:8].reshape(4, 2)
    v = state[8:16].reshape(4, 2)
    f = np.zeros((4, 2))
    for force in forces:
        force(x, v, f)
    return np.concatenate([v.ravel(), (f / masses[:4, None]).ravel()])
