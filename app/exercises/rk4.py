"""Grader of exercises/rk4.py: classical Runge-Kutta and the midpoint method for any ODE
dy/dt = f(t, y).

Reference: app.physics.integrators.rk4_step and midpoint_step. Checks:
  RK4 order, spring       x'' = -x over 2.5 s in 16, 32, 64 steps: measured order 4 +- 0.2
  RK4 order, pendulum     theta'' = -sin theta from 1 rad: order 4 +- 0.2 (exact: the lab's RK4
                          at 4096 steps)
  RK4 stage times         dy/dt = t^3 from 0 to 1 in 4 steps: RK4 is Simpson's rule here, exact
                          (to 1e-12) if k2, k3 are taken at t + h/2 and k4 at t + h
  midpoint order, spring  order 2 +- 0.2;   midpoint order, pendulum: order 2 +- 0.2
  midpoint stage time     dy/dt = t from 0 to 1 in 4 steps: exact if f is taken at t + h/2
  RK4 stability limit     the largest omega*h at which RK4 keeps the spring bounded:
                          2 sqrt 2 = 2.83 +- 2% (found by bisection on 400-step runs)
  y kept                  neither step changes the y it was given
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import Check, Exercise, Result, Student, array_of, fmt, order, within


def reference() -> SimpleNamespace:
    from app.physics.integrators import midpoint_step, rk4_step
    return SimpleNamespace(rk4_step=rk4_step, midpoint_step=midpoint_step)


def spring(t: float, y: np.ndarray) -> np.ndarray:
    return np.array([y[1], -y[0]])


def pendulum(t: float, y: np.ndarray) -> np.ndarray:
    return np.array([y[1], -math.sin(y[0])])


def integrate(step, f, y0, t_end: float, n: int) -> np.ndarray:
    y, h = np.array(y0, dtype=float), t_end / n
    for k in range(n):
        y = array_of(step(f, k * h, y, h), y.shape, step.__name__)
    return y


def measured_order(m: Student, fname: str, f, target: float) -> Result:
    step = getattr(m, fname)
    t_end, y0 = 2.5, np.array([1.0, 0.0])
    exact = (np.array([math.cos(t_end), -math.sin(t_end)]) if f is spring
             else integrate(reference().rk4_step, f, y0, t_end, 4096))
    errors = [float(np.abs(integrate(step, f, y0, t_end, n) - exact).max()) for n in (16, 32, 64)]
    p = order(errors)
    hint = ""
    if fname == "rk4_step":
        hint = ("y' = y + h/6 (k1 + 2 k2 + 2 k3 + k4) with k2 = f(t + h/2, y + h/2 k1), "
                "k3 = f(t + h/2, y + h/2 k2), k4 = f(t + h, y + h k3).")
        if within(p, 2.0, 0.4):
            hint = "second order: " + hint + " Equal weights (k1 + k2 + k3 + k4)/4 give order 2."
        elif within(p, 1.0, 0.3):
            hint = ("first order: the stages' states are off. " + hint + " k2 and k3 go half a "
                    "step (h/2), k4 a whole one.")
    else:
        hint = "y' = y + h f(t + h/2, y + h/2 f(t, y)): a HALF step to the midpoint."
        if within(p, 1.0, 0.3):
            hint = ("first order: " + hint + " A full step to the 'midpoint' takes the slope at "
                    "the end of an Euler step: first order, like Euler.")
    return Result(within(p, target, 0.2), f"order {fmt(p)} (errors {', '.join(map(fmt, errors))})",
                  f"{target:g} +- 0.2", hint)


def stage_times(m: Student, fname: str, power: int) -> Result:
    step = getattr(m, fname)
    y = integrate(step, lambda t, y: np.array([t ** power]), np.array([0.0]), 1.0, 4)
    err = abs(float(y[0]) - 1.0 / (power + 1))
    where = ("k2 and k3 at t + h/2, k4 at t + h" if fname == "rk4_step" else "f at t + h/2")
    return Result(err < 1e-12, f"error {fmt(err)} on dy/dt = t^{power}", "< 1e-12 (exact)",
                  f"f(t, y) depends on t: evaluate the stages at their own times ({where}).")


def growth(step, z: float, n: int = 400) -> float:
    """|y| after n steps of omega*h = z on x'' = -x, from |y| = 1."""
    y = np.array([1.0, 0.0])
    for k in range(n):
        y = array_of(step(spring, k * z, y, z), (2,), step.__name__)
        if not np.isfinite(y).all() or abs(y).max() > 1e6:
            return math.inf
    return float(np.hypot(*y))


def stability_limit(m: Student) -> Result:
    lo, hi = 0.5, 4.0
    if growth(m.rk4_step, lo) > 2:
        lo = hi = 0.0                           # unstable even at small steps
    else:
        while hi - lo > 1e-3:
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if growth(m.rk4_step, mid) <= 2 else (lo, mid)
    limit, exact = (lo + hi) / 2, 2 * math.sqrt(2)
    hint = "RK4's region reaches omega*h = 2 sqrt 2 on the imaginary axis; check the weights."
    if limit < 0.1:
        hint = ("unstable even at small steps, as the midpoint method and forward Euler are on a "
                "spring (they gain energy at every h; midpoint by 1 + (omega h)^4/4 per step): "
                + hint)
    return Result(within(limit, exact, 0.02 * exact), f"omega*h = {limit:.3f}",
                  f"{exact:.3f} +- 2%", hint)


def y_kept(m: Student) -> Result:
    problems = []
    for fname in ("rk4_step", "midpoint_step"):
        y = np.array([0.3, -0.2])
        array_of(getattr(m, fname)(pendulum, 0.0, y, 0.1), (2,), fname)
        if not np.array_equal(y, [0.3, -0.2]):
            problems.append(f"{fname} changed y")
    return Result(not problems, "; ".join(problems) or "y untouched", "y unchanged",
                  "return y + ... (a new array); y += ... changes the caller's y, which a "
                  "solver may still need (to retry a step, or to measure the error).")


EXERCISE = Exercise(
    name="rk4",
    title="Runge-Kutta: RK4 and the midpoint method for any ODE",
    slide="Physics in Computer Animations and Games: 'Integrating Equations of State' (Euler, "
          "Midpoint = 2nd order Runge-Kutta, RK4 = 4th order Runge-Kutta)",
    functions=("rk4_step", "midpoint_step"),
    reference=reference,
    checks=(Check("RK4 order, spring", lambda m: measured_order(m, "rk4_step", spring, 4)),
            Check("RK4 order, pendulum", lambda m: measured_order(m, "rk4_step", pendulum, 4)),
            Check("RK4 stage times", lambda m: stage_times(m, "rk4_step", 3)),
            Check("RK4 stability limit", stability_limit),
            Check("midpoint order, spring",
                  lambda m: measured_order(m, "midpoint_step", spring, 2)),
            Check("midpoint order, pendulum",
                  lambda m: measured_order(m, "midpoint_step", pendulum, 2)),
            Check("midpoint stage time", lambda m: stage_times(m, "midpoint_step", 1)),
            Check("y kept", y_kept)),
)
