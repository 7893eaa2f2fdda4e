"""Right: the rods relaxed in the caller's own array (the starter allows it) and returned, the
length from math.hypot, the shares computed once per rod."""
import math


def satisfy_rods(x, a, b, rest, w, iterations):
    for _ in range(iterations):
        for k, (i, j) in enumerate(zip(a, b)):
            total = w[i] + w[j]
            if total <= 0.0:
                continue
            dx, dy = x[j, 0] - x[i, 0], x[j, 1] - x[i, 1]
            d = max(math.hypot(dx, dy), 1e-9)
            s = (d - rest[k]) / d / total
            x[i, 0] += dx * s * w[i]
            x[i, 1] += dy * s * w[i]
            x[j, 0] -= dx * s * w[j]
            x[j, 1] -= dy * s * w[j]
    return x
