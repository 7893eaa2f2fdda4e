"""Wrong (fails, the hint says NaN came back): the velocity estimated as (x - x_prev) / (h - h)."""
import numpy as np


def verlet_step(x, x_prev, a, h, drag):
    with np.errstate(all="ignore"):
        v = (x - x_prev) / (h - h)
    return x + (1 - drag) * v * h + a * h * h, x.copy()
