"""Right: gravity as a force m g on the free particles inside h W (f0 + m g + h K v) (the mass of
a pinned one set to 0, never 1/0), K and D built from np.kron blocks, and dv from the inverse
of A rather than np.linalg.solve."""
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


def linear_system(x, v, w, a, b, ks, kd, rest, g, h):
    n = len(x)
    K = np.zeros((2 * n, 2 * n))
    D = np.zeros((2 * n, 2 * n))
    for k in range(len(a)):
        e = np.zeros((n, n))
        e[a[k], a[k]] = e[b[k], b[k]] = 1.0
        e[a[k], b[k]] = e[b[k], a[k]] = -1.0
        l = x[a[k]] - x[b[k]]
        L = np.linalg.norm(l)
        uu = np.outer(l, l) / (L * L)
        K += np.kron(e, -ks * (uu + max(1.0 - rest[k] / L, 0.0) * (np.eye(2) - uu)))
        D += np.kron(e, -kd * uu)
    m = np.divide(1.0, w, out=np.zeros(n), where=w > 0)          # pinned: no weight
    force = spring_forces(x, v, a, b, ks, kd, rest) + m[:, None] * g
    W = np.diag(np.repeat(w, 2))
    A = np.eye(2 * n) - h * W @ D - h * h * W @ K
    return A, h * W @ (force.ravel() + h * K @ v.ravel())


def implicit_euler_step(x, v, w, a, b, ks, kd, rest, g, h):
    A, rhs = linear_system(x, v, w, a, b, ks, kd, rest, g, h)
    v_new = v + (np.linalg.inv(A) @ rhs).reshape(v.shape)
    return x + h * v_new, v_new
