"""Right: both methods from one explicit Runge-Kutta loop over a Butcher tableau."""
import numpy as np

MIDPOINT = ([[], [0.5]], [0.0, 1.0], [0.0, 0.5])
RK4 = ([[], [0.5], [0.0, 0.5], [0.0, 0.0, 1.0]], [1 / 6, 1 / 3, 1 / 3, 1 / 6],
       [0.0, 0.5, 0.5, 1.0])


def explicit_rk(tableau, f, t, y, h):
    a, b, c = tableau
    ks = []
    for i in range(len(b)):
        yi = y + h * sum((aij * k for aij, k in zip(a[i], ks)), np.zeros_like(y))
        ks.append(f(t + c[i] * h, yi))
    return y + h * sum(bi * k for bi, k in zip(b, ks))


def midpoint_step(f, t, y, h):
    return explicit_rk(MIDPOINT, f, t, y, h)


def rk4_step(f, t, y, h):
    return explicit_rk(RK4, f, t, y, h)
