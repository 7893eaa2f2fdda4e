"""Wrong (every check fails with a RecursionError, shown as one frame and a count, not 1000)."""


def verlet_step(x, x_prev, a, h, drag):
    return verlet_step(x, x_prev, a, h, drag)
