"""Wrong (fails 'Hooke part', hint: the sign flipped): l = x_b - x_a with the slide's formula,
so a stretched spring pushes its ends apart."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    l = x[b] - x[a]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / length
    fa = -(ks * (length - rest[:, None])
           + kd * np.sum((v[a] - v[b]) * u, axis=1, keepdims=True)) * u
    f = np.zeros_like(x)
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    return f
