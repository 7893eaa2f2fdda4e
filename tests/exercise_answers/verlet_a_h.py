"""Wrong (fails 'free fall' and 'order 2 on a spring'): a * h instead of a * h^2."""


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h, x.copy()
