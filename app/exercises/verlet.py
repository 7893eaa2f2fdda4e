"""Grader of exercises/verlet.py: the velocity-less Verlet step with the slide's drag.

Reference: app.physics.jakobsen.verlet_step. Checks (physics, not code):
  free fall        exact for constant acceleration: Verlet's x' - 2x + x_prev = a h^2 is the
                   central difference, which a parabola satisfies exactly (the error is rounding)
  order            a spring x'' = -omega^2 x over 1.25 s in 40, 80, 160 steps: the error falls
                   4x per halving, measured order 2 +- 0.2 (the slide's "4th order accurate"
                   counts one step's O(h^4) error; over a fixed time Verlet is second order;
                   see tests/test_integrators.py)
  energy kept      drag 0, the spring for 20 s at 60 Hz: the energy of the last second within 1% of
                   the first's (it wobbles within the step, but does not drift)
  drag             drag 0.01 per step: the energy falls by 1 - drag per step (0.99^60 = 0.55 in
                   one second at 60 Hz), +- 0.05
  inputs kept      x and a are not changed; the new x is a new array
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import (BadAnswer, Check, Exercise, Result, Student, array_of, fmt,
                                order, within)

G = np.array([0.0, 900.0])            # px/s^2, y down
OMEGA = 2 * math.pi                   # the test spring: one period per second


def reference() -> SimpleNamespace:
    from app.physics.jakobsen import verlet_step
    return SimpleNamespace(verlet_step=verlet_step)


def step(m: Student, x, x_prev, a, h, drag):
    """Call the student's verlet_step and check the shape of what comes back."""
    out = m.verlet_step(x, x_prev, a, h, drag)
    if not isinstance(out, tuple) or len(out) != 2:
        raise BadAnswer(f"verlet_step returned {type(out).__name__}; expected a pair "
                        "(x_new, x)" + (" (no return statement?)" if out is None else ""))
    return (array_of(out[0], x.shape, "verlet_step's x_new"),
            array_of(out[1], x.shape, "verlet_step's second value (the new x_prev)"))


def run_spring(m: Student, h: float, seconds: float, drag: float = 0.0, amplitude: float = 100.0
               ) -> tuple[np.ndarray, np.ndarray]:
    """The spring x'' = -omega^2 x from x = amplitude at rest, started exactly (x_prev = x(-h)).
    Returns positions x_k (k = 0..N) and the energy per unit mass at steps 1..N-1 (velocity
    from the central difference (x_{k+1} - x_{k-1}) / 2h)."""
    n = round(seconds / h)
    x = np.array([[amplitude, 0.0]])
    x_prev = np.array([[amplitude * math.cos(OMEGA * h), 0.0]])
    xs = [x[0, 0]]
    for _ in range(n):
        x_new, x_prev = step(m, x, x_prev, -OMEGA ** 2 * x, h, drag)
        x = x_new
        xs.append(x[0, 0])
    xs = np.array(xs)
    v = (xs[2:] - xs[:-2]) / (2 * h)
    energy = 0.5 * v ** 2 + 0.5 * OMEGA ** 2 * xs[1:-1] ** 2
    return xs, energy


def free_fall(m: Student) -> Result:
    h, n = 1 / 60, 60
    x0 = np.array([[100.0, 100.0], [300.0, 50.0], [500.0, 400.0]])
    v0 = np.array([[0.0, 0.0], [120.0, -300.0], [-50.0, -600.0]])
    x, x_prev = x0.copy(), x0 - v0 * h + G * h * h / 2      # x(-h) of the exact parabola
    for _ in range(n):
        x, x_prev = step(m, x, x_prev, np.tile(G, (3, 1)), h, 0.0)
    t = n * h
    exact = x0 + v0 * t + G * t * t / 2
    err = float(np.abs(x - exact).max())
    drop = float((x[:, 1] - x0[:, 1] - v0[:, 1] * t).mean()) / (G[1] * t * t / 2)
    hint = "x' = x + (x - x_prev) + a h^2: check each term."
    if abs(drop) < 0.05:
        hint = ("the particles do not fall: the acceleration never reaches the positions. Did "
                "you move with the old velocity only (Euler's x + h v) and add a h to a velocity "
                "afterwards? In Verlet a h^2 goes into the position.")
    elif abs(drop - 0.5) < 0.05:
        hint = "they fall half as far: a h^2, not a h^2 / 2 (Verlet has no 1/2)."
    elif drop > 5:
        hint = "they fall far too fast: a h^2 (h squared), not a h."
    return Result(err < 1e-6, f"{fmt(err)} px off the parabola after 1 s",
                  "< 1e-06 px (exact but for rounding)", hint)


def spring_order(m: Student) -> Result:
    errors = []
    for n in (40, 80, 160):         # end at 1.25 periods: the phase error shows fully there
        xs, _ = run_spring(m, 1.25 / n, 1.25)
        errors.append(abs(xs[-1] - 100.0 * math.cos(OMEGA * 1.25)))
    p = order(errors)
    hint = "x' = x + (x - x_prev) + a h^2 with a at the current x."
    if within(p, 1.0, 0.3):
        hint = ("error halves when h halves: first order. Did you update the position with the "
                "old velocity (Euler) instead of x + (x - x_prev) + a h^2?")
    elif within(p, 0.0, 0.3):
        hint = "the error does not shrink with h: a term has the wrong power of h (a h^2)."
    return Result(within(p, 2.0, 0.2), f"order {fmt(p)} (errors {', '.join(map(fmt, errors))} px)",
                  "2 +- 0.2", hint)


def energy_kept(m: Student) -> Result:
    _, e = run_spring(m, 1 / 60, 20.0)
    ratio = float(e[-60:].mean() / e[:60].mean())
    hint = ("with drag 0 the energy must not drift: x' = x + (x - x_prev) + a h^2 exactly "
            "(1 - drag multiplies only (x - x_prev)).")
    if ratio > 1.01:
        hint = "the energy grows: that is forward Euler's spiral, not Verlet."
    return Result(within(ratio, 1.0, 0.01), f"energy ratio {ratio:.4f} after 20 s",
                  "1 +- 0.01", hint)


def drag_loses(m: Student) -> Result:
    _, e = run_spring(m, 1 / 60, 2.0, drag=0.01)
    ratio = float(e[-60:].mean() / e[:60].mean())
    expected = 0.99 ** 60           # the amplitude falls by sqrt(1 - drag) per step
    hint = ("drag takes a fraction of the distance travelled: x' = x + (1 - drag) (x - x_prev) "
            "+ a h^2, i.e. (2 - drag) x - (1 - drag) x_prev. Lowering only the 2 "
            "(1.99 x - x_prev) is no drag: it pulls every particle towards x = 0.")
    if ratio > 1.05:
        hint = "the energy GROWS: (1 - drag), not (1 + drag). " + hint
    elif ratio > 0.99:
        hint = "almost no energy lost: did you ignore drag? " + hint
    return Result(within(ratio, expected, 0.05), f"energy ratio {ratio:.3f} over 1 s at drag 0.01",
                  f"{expected:.2f} +- 0.05 (x (1 - drag) per step)", hint)


def inputs_kept(m: Student) -> Result:
    rng = np.random.default_rng(1)
    x, x_prev, a = rng.normal(size=(3, 4, 2)) * 10
    x0, a0 = x.copy(), a.copy()
    x_new, x_old = step(m, x, x_prev, a, 0.01, 0.0)
    problems = []
    if not np.array_equal(x, x0):
        problems.append("x was changed")
    if not np.array_equal(a, a0):
        problems.append("a was changed")
    if np.shares_memory(x_new, x):
        problems.append("x_new is the array x")
    if not np.array_equal(x_old, x0):
        problems.append("the second value is not the old x")
    return Result(not problems, "; ".join(problems) or "x and a untouched, x_new a new array",
                  "x and a unchanged; return (x_new, x)",
                  "compute x_new into a new array (x + ... makes one; x += ... changes the "
                  "caller's x, which is also the x_prev you return). Reusing x_prev's array for "
                  "x_new is fine: the caller is done with it (the slide's pointer swap).")


EXERCISE = Exercise(
    name="verlet",
    title="Verlet integration: the velocity-less step with drag",
    slide="Physics in Computer Animations and Games: 'Verlet integration' "
          "(x' = 2x - x_prev + a h^2; lowering 2 to 1.99 adds drag)",
    functions=("verlet_step",),
    reference=reference,
    checks=(Check("free fall", free_fall), Check("order 2 on a spring", spring_order),
            Check("energy kept (drag 0)", energy_kept), Check("drag loses energy", drag_loses),
            Check("inputs kept", inputs_kept)),
)
