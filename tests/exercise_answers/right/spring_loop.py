"""Right: one spring at a time in a Python loop, the force array from the positions' shape."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    f = np.zeros(x.shape)
    for k in range(len(a)):
        l = x[a[k]] - x[b[k]]
        length = np.sqrt(l @ l)
        u = l / length
        fa = -(ks * (length - rest[k]) + kd * (v[a[k]] - v[b[k]]) @ u) * u
        f[a[k]] += fa
        f[b[k]] -= fa
    return f
