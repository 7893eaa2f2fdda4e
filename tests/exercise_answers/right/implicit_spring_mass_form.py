"""Right: the symmetric form Baraff & Witkin solve, (M - h D - h^2 K) dv = h (f0 + h K v), a
pinned particle's rows and columns replaced by the identity's (its dv = 0), with NumPy blocks
instead of a loop (np.add.at on the 2x2 blocks)."""
import numpy as np


def parts(x, v, a, b, ks, kd, rest):
    n = len(x)
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1)
    u = l / length[:, None]
    fa = -(ks * (length - rest) + kd * np.einsum("ij,ij->i", v[a] - v[b], u))[:, None] * u
    f = np.zeros((n, 2))
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    uu = np.einsum("ki,kj->kij", u, u)
    kaa = -ks * (uu + np.maximum(1 - rest / length, 0.0)[:, None, None] * (np.eye(2) - uu))
    daa = -kd * uu
    K = np.zeros((n, 2, n, 2))
    D = np.zeros((n, 2, n, 2))
    for p, q, s in ((a, a, 1), (b, b, 1), (a, b, -1), (b, a, -1)):
        np.add.at(K, (p, slice(None), q), s * kaa)
        np.add.at(D, (p, slice(None), q), s * daa)
    return f, K.reshape(2 * n, 2 * n), D.reshape(2 * n, 2 * n)


def linear_system(x, v, w, a, b, ks, kd, rest, g, h):
    n = len(x)
    w = np.asarray(w, dtype=float)
    free = np.repeat(w > 0, 2)
    m = np.repeat(np.where(w > 0, 1 / np.where(w > 0, w, 1), 1.0), 2)
    f, K, D = parts(x, v, a, b, ks, kd, rest)
    A = np.diag(m) - h * D - h * h * K
    rhs = h * (f.ravel() + m * np.tile(g, n) + h * K @ v.ravel())
    A[~free, :] = 0.0
    A[:, ~free] = 0.0
    A[~free, ~free] = 1.0
    rhs[~free] = 0.0
    return A, rhs


def implicit_euler_step(x, v, w, a, b, ks, kd, rest, g, h):
    A, rhs = linear_system(x, v, w, a, b, ks, kd, rest, g, h)
    v_new = v + np.linalg.solve(A, rhs).reshape(x.shape)
    return x + h * v_new, v_new
