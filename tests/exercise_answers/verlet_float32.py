"""Wrong (fails 'free fall', the hint says float32 came back): the right formula in single
precision, 7 digits, too few for a 1e-6 px parabola."""
import numpy as np


def verlet_step(x, x_prev, a, h, drag):
    x32, p32, a32 = (np.asarray(v, dtype=np.float32) for v in (x, x_prev, a))
    return x32 + np.float32(1 - drag) * (x32 - p32) + a32 * np.float32(h * h), x32
