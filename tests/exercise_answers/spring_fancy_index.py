"""Wrong (fails 'Hooke part'): f[a] += fa keeps one spring per particle when a repeats."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / np.maximum(length, 1e-12)
    mag = ks * (length - rest[:, None]) + kd * np.sum((v[a] - v[b]) * u, axis=1, keepdims=True)
    fa = -mag * u
    f = np.zeros_like(x)
    f[a] += fa
    f[b] -= fa
    return f
