"""Wrong (fails 'Hooke part'): only f_a: the force on b is never added."""
import numpy as np


def spring_forces(x: np.ndarray, v: np.ndarray, a: np.ndarray, b: np.ndarray, ks: float,
                  kd: float, rest: np.ndarray) -> np.ndarray:
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / length
    fa = -(ks * (length - rest[:, None]) + kd * np.sum((v[a] - v[b]) * u, axis=1, keepdims=True)) * u
    f = np.zeros_like(x)
    np.add.at(f, a, fa)
    return f
