"""Right: Kutta's 3/8-rule (also fourth order, other weights) for rk4_step, and the midpoint
method written with the midpoint state named (the slide's form, in other words)."""


def midpoint_step(f, t, y, h):
    y_mid = y + 0.5 * h * f(t, y)
    return y + h * f(t + 0.5 * h, y_mid)


def rk4_step(f, t, y, h):
    k1 = f(t, y)
    k2 = f(t + h / 3, y + h * k1 / 3)
    k3 = f(t + 2 * h / 3, y + h * (-k1 / 3 + k2))
    k4 = f(t + h, y + h * (k1 - k2 + k3))
    return y + h / 8 * (k1 + 3 * k2 + 3 * k3 + k4)
