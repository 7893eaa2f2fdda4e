"""Right: the slide's form with the drag in both terms, (2 - drag) x - (1 - drag) x_prev + a h^2."""


def verlet_step(x, x_prev, a, h, drag):
    return (2 - drag) * x - (1 - drag) * x_prev + a * h ** 2, x.copy()
