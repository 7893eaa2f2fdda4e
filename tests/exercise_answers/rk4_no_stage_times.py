"""Wrong (fails 'RK4 stage times'): every stage evaluated at time t."""


def midpoint_step(f, t, y, h):
    return y + h * f(t + h / 2, y + h / 2 * f(t, y))


def rk4_step(f, t, y, h):
    k1 = f(t, y)
    k2 = f(t, y + h / 2 * k1)
    k3 = f(t, y + h / 2 * k2)
    k4 = f(t, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
