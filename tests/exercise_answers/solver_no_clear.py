"""Wrong (fails 'clears forces'): one accumulator kept between calls and never cleared."""
import numpy as np

accumulator = {}


def derivative(state, masses, forces):
    n = len(masses)
    x = state[:2 * n].reshape(n, 2)
    v = state[2 * n:].reshape(n, 2)
    f = accumulator.setdefault(n, np.zeros((n, 2)))
    for force in forces:
        force(x, v, f)
    return np.concatenate([v.ravel(), (f / masses[:, None]).ravel()])
