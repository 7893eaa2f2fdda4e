"""Wrong (every check is stopped by the time limit): an endless loop."""


def verlet_step(x, x_prev, a, h, drag):
    n = 0
    while n >= 0:
        n += 1
    return x, x
