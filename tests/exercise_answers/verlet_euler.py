"""Wrong (fails 'free fall'): forward Euler: the position moves with the old velocity, the
acceleration only reaches a velocity that is thrown away."""
import numpy as np


def verlet_step(x, x_prev, a, h, drag):
    v = (x - x_prev) / h
    x_new = x + h * v
    v = v + h * a
    return x_new, x.copy()
