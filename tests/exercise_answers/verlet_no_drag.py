"""Wrong (fails 'drag loses energy'): ignores drag."""


def verlet_step(x, x_prev, a, h, drag):
    return 2 * x - x_prev + a * h * h, x.copy()
