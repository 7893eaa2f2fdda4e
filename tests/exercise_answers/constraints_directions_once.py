"""Wrong (fails 'random rods and sweeps'): every rod's delta taken at the start of the sweep,
then the corrections applied one by one (Jacobi): 20x the right stretch at 1 iteration."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    x = np.array(x, dtype=float)
    for _ in range(iterations):
        start = x.copy()
        for i, j, r in zip(a, b, rest):
            wsum = w[i] + w[j]
            if wsum == 0:
                continue
            d = start[j] - start[i]
            length = float(np.hypot(d[0], d[1]))
            if length == 0:
                continue
            move = (length - r) / (length * wsum) * d
            x[i] += w[i] * move
            x[j] -= w[j] * move
    return x
