"""Wrong (fails 'Hooke part'): the force along l, not along the unit vector l/|l|."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / np.maximum(length, 1e-12)
    damp = kd * np.sum((v[a] - v[b]) * u, axis=1, keepdims=True)
    fa = -(ks * (length - rest[:, None])) * l - damp * u
    f = np.zeros_like(x)
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    return f
