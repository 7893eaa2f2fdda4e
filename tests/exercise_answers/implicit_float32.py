"""Wrong (fails 'A and rhs'): A and rhs in float32 (np.float32 matrices)."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / np.maximum(length, 1e-12)
    fa = -(ks * (length - rest[:, None]) + kd * np.sum((v[a] - v[b]) * u, axis=1,
                                                       keepdims=True)) * u
    f = np.zeros_like(x, dtype=float)
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    return f


def linear_system(x: np.ndarray, v: np.ndarray, w: np.ndarray, a: np.ndarray, b: np.ndarray,
                  ks: float, kd: float, rest: np.ndarray, g: np.ndarray,
                  h: float) -> tuple[np.ndarray, np.ndarray]:
    n = len(x)
    K = np.zeros((2 * n, 2 * n))
    D = np.zeros((2 * n, 2 * n))
    for k in range(len(a)):
        i, j = a[k], b[k]
        l = x[i] - x[j]
        L = np.linalg.norm(l)
        u = l / L
        uu = np.outer(u, u)
        Kaa = -ks * (uu + max(1 - rest[k] / L, 0) * (np.eye(2) - uu))
        Daa = -kd * uu
        for p, q, s in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
            K[2*p:2*p+2, 2*q:2*q+2] += s * Kaa
            D[2*p:2*p+2, 2*q:2*q+2] += s * Daa
    f0 = spring_forces(x, v, a, b, ks, kd, rest).ravel()
    W = np.diag(np.repeat(w, 2))
    A = np.eye(2 * n) - h * W @ D - h * h * W @ K
    rhs = h * W @ (f0 + h * K @ v.ravel()) + h * (np.where(w[:, None] > 0, g, 0.0)).ravel()
    return A.astype(np.float32), rhs.astype(np.float32)


def implicit_euler_step(x: np.ndarray, v: np.ndarray, w: np.ndarray, a: np.ndarray,
                        b: np.ndarray, ks: float, kd: float, rest: np.ndarray, g: np.ndarray,
                        h: float) -> tuple[np.ndarray, np.ndarray]:
    A, rhs = linear_system(x, v, w, a, b, ks, kd, rest, g, h)
    dv = np.linalg.solve(A, rhs).reshape(-1, 2)
    v_new = v + dv
    return x + h * v_new, v_new
