"""Right: the slide's pointer swap taken literally: x_new is written into x_prev's array (the
caller is done with it), with np.multiply/np.add and out=, and the pair returned."""
import numpy as np


def verlet_step(x, x_prev, a, h, drag):
    out = x_prev                               # reuse the old array: no allocation
    np.subtract(x, x_prev, out=out)            # the travel
    np.multiply(out, 1.0 - drag, out=out)
    out += x
    out += a * (h * h)
    return out, x
