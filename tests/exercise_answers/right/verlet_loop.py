"""Right: the Verlet step written as a plain loop over the particles, as many students do."""
import numpy as np


def verlet_step(x, x_prev, a, h, drag):
    x_new = np.empty_like(x)
    for i in range(len(x)):
        x_new[i] = x[i] + (1.0 - drag) * (x[i] - x_prev[i]) + a[i] * h * h
    return x_new, x.copy()
