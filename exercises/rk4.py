"""Exercise `rk4`: the midpoint method and classical Runge-Kutta for any ODE dy/dt = f(t, y)
(lecture: "Integrating Equations of State"; Blender's cloth offers Euler, Verlet, Midpoint = "2nd
order Runge-Kutta" and RK4 = "4th order Runge-Kutta").

    midpoint:  k1 = f(t, y)
               k2 = f(t + h/2, y + h/2 k1)             y_new = y + h k2
    RK4:       k1 = f(t, y)
               k2 = f(t + h/2, y + h/2 k1)
               k3 = f(t + h/2, y + h/2 k2)
               k4 = f(t + h,   y + h k3)               y_new = y + h/6 (k1 + 2 k2 + 2 k3 + k4)

Write `midpoint_step` and `rk4_step`: y is a NumPy array (any shape), f(t, y) returns an array
of the same shape. Return the new y; do not change the y you were given.

Check it:   python -m app exercise check rk4
Watch it:   python -m app --scene exercise:rk4           (try --set hertz=2)

What the grader measures: the order of each method on a spring and on a pendulum (the error must
fall 16x per halved step for RK4: order 4, and 4x for midpoint: order 2, +- 0.2); that f is
called at the right times (on dy/dt = t^3 RK4 is exact); and RK4's stability limit on the spring,
omega*h = 2 sqrt 2 = 2.83 (+- 2%); and that neither step changes the y it was given.
Then random linear ODEs (seeded: the seed is printed, --seed N repeats it) with y of any shape:
one step of each method must equal that method's exact value there, within rounding.

Hints:
  * The weights matter: equal weights (k1 + k2 + k3 + k4)/4 give only order 2.
  * The midpoint is half a step away: y + h/2 k1, not y + h k1.
"""

import numpy as np


def midpoint_step(f, t: float, y: np.ndarray, h: float) -> np.ndarray:
    """One explicit midpoint (RK2) step of h: return the new y."""
    raise NotImplementedError("write me: y + h * f(t + h/2, y + h/2 * f(t, y))")


def rk4_step(f, t: float, y: np.ndarray, h: float) -> np.ndarray:
    """One classical Runge-Kutta step of h: return the new y."""
    raise NotImplementedError("write me: y + h/6 * (k1 + 2 k2 + 2 k3 + k4)")
