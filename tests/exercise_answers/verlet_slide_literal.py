"""Wrong (fails 'drag loses energy', hint: lowering only the 2): the slide read literally,
1.99 x - x_prev, which pulls every particle towards x = 0 instead of dragging it."""


def verlet_step(x, x_prev, a, h, drag):
    return (2 - drag) * x - x_prev + a * h * h, x
