"""Wrong (fails 'a particle in no spring'): the force array sized from the largest index in the
springs, so a particle in no spring (with the highest index) has no row."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    n = int(max(a.max(), b.max())) + 1
    f = np.zeros((n, 2))
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / length
    fa = -(ks * (length - rest[:, None]) + kd * np.sum((v[a] - v[b]) * u, axis=1,
                                                       keepdims=True)) * u
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    return f
