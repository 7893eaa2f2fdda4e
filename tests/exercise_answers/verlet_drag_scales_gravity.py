"""Wrong (fails 'terminal speed with drag'): the drag factor also multiplies a h^2, so gravity is
slowed too: a fall settles at 1485 px/s instead of g h / drag = 1500."""


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev + a * h * h), x
