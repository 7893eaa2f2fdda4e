"""Wrong (fails 'one rod, one pass', hint: divide by w_a + w_b): the ends move by w times the
correction, not by their shares w / (w_a + w_b), so they overshoot."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = x.copy()
    for _ in range(iterations):
        for k in range(len(a)):
            i, j = a[k], b[k]
            d = x[j] - x[i]
            length = max(float(np.hypot(*d)), 1e-9)
            diff = (length - rest[k]) / length
            x[i] += d * diff * w[i]
            x[j] -= d * diff * w[j]
    return x
