"""Wrong (fails 'random particles and steps'): every particle moved by the mean acceleration: right
whenever all particles share one acceleration (gravity alone), 178 px off in the live scene."""
import numpy as np


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a.mean(axis=0) * h * h, x.copy()
