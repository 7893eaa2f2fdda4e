"""Wrong (fails 'drag loses energy' with this file's line; the other checks pass): raises when
drag > 0."""


def verlet_step(x, x_prev, a, h, drag):
    if drag > 0:
        raise ValueError("drag is not supported yet")
    return 2 * x - x_prev + a * h * h, x.copy()
