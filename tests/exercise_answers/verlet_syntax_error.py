"""Wrong (does not import): a syntax error on line 4."""


def verlet_step(x, x_prev, a, h, drag)
    return 2 * x - x_prev + a * h * h, x
