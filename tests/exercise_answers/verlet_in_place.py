"""Wrong (fails 'inputs kept'): updates x in place and returns it twice."""


def verlet_step(x, x_prev, a, h, drag):
    x += (1 - drag) * (x - x_prev) + a * h * h
    return x, x
