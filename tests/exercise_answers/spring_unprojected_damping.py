"""Wrong (fails 'damping part'): damps the whole relative velocity, not its part along the
spring."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / np.maximum(length, 1e-12)
    fa = -ks * (length - rest[:, None]) * u - kd * (v[a] - v[b])
    f = np.zeros_like(x)
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    return f
