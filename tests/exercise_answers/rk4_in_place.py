"""Wrong (fails 'y kept'): right steps, but y += ... changes the caller's y."""


def midpoint_step(f, t, y, h):
    y += h * f(t + h / 2, y + h / 2 * f(t, y))
    return y


def rk4_step(f, t, y, h):
    k1 = f(t, y)
    k2 = f(t + h / 2, y + h / 2 * k1)
    k3 = f(t + h / 2, y + h / 2 * k2)
    k4 = f(t + h, y + h * k3)
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return y
