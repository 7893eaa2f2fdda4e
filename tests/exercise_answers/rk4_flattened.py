"""Wrong (fails 'any shape of y'): right for 1-D states, but a state of shape (3, 2) comes back
flattened."""
import numpy as np


def midpoint_step(f, t, y, h):
    y = np.ravel(y)
    k1 = np.ravel(f(t, y))
    return y + h * np.ravel(f(t + h / 2, y + h / 2 * k1))


def rk4_step(f, t, y, h):
    y = np.ravel(y)
    k1 = np.ravel(f(t, y))
    k2 = np.ravel(f(t + h / 2, y + h / 2 * k1))
    k3 = np.ravel(f(t + h / 2, y + h / 2 * k2))
    k4 = np.ravel(f(t + h, y + h * k3))
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
