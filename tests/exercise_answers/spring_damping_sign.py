"""Wrong (fails 'damping removes energy'): the damping term has the wrong sign."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / np.maximum(length, 1e-12)
    mag = ks * (length - rest[:, None]) - kd * np.sum((v[a] - v[b]) * u, axis=1, keepdims=True)
    f = np.zeros_like(x)
    np.add.at(f, a, -mag * u)
    np.add.at(f, b, mag * u)
    return f
