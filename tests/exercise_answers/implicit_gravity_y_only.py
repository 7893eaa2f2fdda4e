"""Wrong (fails 'random systems'): gravity's x component dropped (g taken as (0, g[1])): right\nwhenever gravity points straight down."""
import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    f = np.zeros_like(x, dtype=float)
    for k in range(len(a)):
        i, j = a[k], b[k]
        l = x[i] - x[j]
        length = np.linalg.norm(l)
        u = l / length
        fa = -(ks * (length - rest[k]) + kd * np.dot(v[i] - v[j], u)) * u
        f[i] += fa
        f[j] -= fa
    return f


def jacobians(x, a, b, ks, kd, rest):
    n = len(x)
    K = np.zeros((2 * n, 2 * n))
    D = np.zeros((2 * n, 2 * n))
    for k in range(len(a)):
        i, j = a[k], b[k]
        l = x[i] - x[j]
        length = np.linalg.norm(l)
        u = l / length
        uu = np.outer(u, u)
        kaa = -ks * (uu + max(1 - rest[k] / length, 0.0) * (np.eye(2) - uu))
        daa = -kd * uu
        for p, q, s in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
            K[2 * p:2 * p + 2, 2 * q:2 * q + 2] += s * kaa
            D[2 * p:2 * p + 2, 2 * q:2 * q + 2] += s * daa
    return K, D


def linear_system(x, v, w, a, b, ks, kd, rest, g, h):
    n = len(x)
    K, D = jacobians(x, a, b, ks, kd, rest)
    W = np.diag(np.repeat(w, 2))
    A = np.eye(2 * n) - h * W @ D - h * h * W @ K
    f0 = spring_forces(x, v, a, b, ks, kd, rest).ravel()
    gravity = np.where(np.repeat(w, 2) > 0, np.tile([0.0, g[1]], n), 0.0)
    rhs = h * W @ (f0 + h * K @ v.ravel()) + h * gravity
    return A, rhs


def implicit_euler_step(x, v, w, a, b, ks, kd, rest, g, h):
    A, rhs = linear_system(x, v, w, a, b, ks, kd, rest, g, h)
    dv = np.linalg.solve(A, rhs).reshape(x.shape)
    v_new = v + dv
    return x + h * v_new, v_new
