"""Wrong (fails 'RK4 order, spring', hint: half a step): the stages k2, k3 step a whole h from y
(the times are right, the states are not): first order."""


def midpoint_step(f, t, y, h):
    return y + h * f(t + h / 2, y + h / 2 * f(t, y))


def rk4_step(f, t, y, h):
    k1 = f(t, y)
    k2 = f(t + h / 2, y + h * k1)
    k3 = f(t + h / 2, y + h * k2)
    k4 = f(t + h, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
