"""Wrong (fails 'drag loses energy', hint: the energy GROWS): drag with the wrong sign."""


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 + drag) * (x - x_prev) + a * h * h, x
