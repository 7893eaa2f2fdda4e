"""Grader of exercises/verlet.py: the velocity-less Verlet step with the slide's drag.

Reference: app.physics.jakobsen.verlet_step. Each check's measure (in the child) runs the
student's verlet_step and sends back the positions it produced; its judge (here, in the grader)
does the physics on them:
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
  terminal speed   a fall with drag 0.01 at 60 Hz settles where the step's travel s satisfies
                   s = (1 - drag) s + g h^2: s = g h^2 / drag, a speed g h / drag = 1500 px/s
                   (+- 0.5). Drag that also scales g h^2 settles at (1 - drag) of it: 1485.
  inputs kept      x and a are not changed; the new x is a new array
  random particles and steps  4 random systems (seeded) x 5 chained steps, each particle its
                   own acceleration, any h and drag: the lab's step within its rounding
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import (BadAnswer, Check, Exercise, Raw, Result, Student, array_of,
                                cases_rng, fmt, order, rounding, within)

G = np.array([0.0, 900.0])            # px/s^2, y down
OMEGA = 2 * math.pi                   # the test spring: one period per second
AMPLITUDE = 100.0


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


def run_spring(m: Student, h: float, seconds: float, drag: float = 0.0) -> np.ndarray:
    """The spring x'' = -omega^2 x from x = AMPLITUDE at rest, started exactly (x_prev = x(-h)):
    the positions x_k (k = 0..N)."""
    n = round(seconds / h)
    x = np.array([[AMPLITUDE, 0.0]])
    x_prev = np.array([[AMPLITUDE * math.cos(OMEGA * h), 0.0]])
    xs = [x[0, 0]]
    for _ in range(n):
        x, x_prev = step(m, x, x_prev, -OMEGA ** 2 * x, h, drag)
        xs.append(x[0, 0])
    return np.array(xs)


def spring_energy(xs: np.ndarray, h: float) -> np.ndarray:
    """Energy per unit mass at steps 1..N-1 (velocity from the central difference)."""
    v = (xs[2:] - xs[:-2]) / (2 * h)
    return 0.5 * v ** 2 + 0.5 * OMEGA ** 2 * xs[1:-1] ** 2


# ----- free fall ---------------------------------------------------------------------------------
FALL_X0 = np.array([[100.0, 100.0], [300.0, 50.0], [500.0, 400.0]])
FALL_V0 = np.array([[0.0, 0.0], [120.0, -300.0], [-50.0, -600.0]])
FALL_H, FALL_N = 1 / 60, 60


def measure_free_fall(m: Student) -> dict:
    x, x_prev = FALL_X0.copy(), FALL_X0 - FALL_V0 * FALL_H + G * FALL_H ** 2 / 2   # x(-h)
    for _ in range(FALL_N):
        x, x_prev = step(m, x, x_prev, np.tile(G, (3, 1)), FALL_H, 0.0)
    return {"x": x}


FALL_MISTAKES = {
    "swapped": "you return (x, x_new): the pair in the wrong order, so the particles step back "
               "and forth. Return (x_new, x): the new positions first, then the old x (the next "
               "x_prev).",
    "old prev": "you return (x_new, x_prev): the second value must be the old x (it becomes the "
                "next step's x_prev, the slide's pointer swap), not x_prev.",
    "reversed": "the travel is backwards: x + (x - x_prev), not x + (x_prev - x).",
    "a h": "a h, not a h^2: the acceleration moves the position by a h^2 in Verlet.",
}


def fall_with(kind: str) -> np.ndarray:
    """Where the free fall ends with one of the usual mistakes (computed here, in the parent)."""
    h = FALL_H
    x, x_prev = FALL_X0.copy(), FALL_X0 - FALL_V0 * h + G * h ** 2 / 2
    with np.errstate(all="ignore"):
        for _ in range(FALL_N):
            travel = (x_prev - x) if kind == "reversed" else (x - x_prev)
            new = x + travel + G * (h if kind == "a h" else h * h)
            x, x_prev = {"swapped": (x, new), "old prev": (new, x_prev)}.get(kind, (new, x))
    return x


def judge_free_fall(raw: Raw) -> Result:
    x = raw.array("x", (3, 2))
    t = FALL_N * FALL_H
    exact = FALL_X0 + FALL_V0 * t + G * t * t / 2
    err = float(np.abs(x - exact).max())
    drop = float((x[:, 1] - FALL_X0[:, 1] - FALL_V0[:, 1] * t).mean()) / (G[1] * t * t / 2)
    hint = "x' = x + (x - x_prev) + a h^2: check each term."
    named = [text for kind, text in FALL_MISTAKES.items()
             if np.allclose(x, fall_with(kind), rtol=1e-9, atol=1e-6)]
    if named:
        hint = named[0]
    elif abs(drop) < 0.05:
        hint = ("the particles do not fall: the acceleration never reaches the positions. Did "
                "you move with the old velocity only (Euler's x + h v) and add a h to a velocity "
                "afterwards? In Verlet a h^2 goes into the position.")
    elif abs(drop - 0.5) < 0.05:
        hint = "they fall half as far: a h^2, not a h^2 / 2 (Verlet has no 1/2)."
    elif drop > 5:
        hint = "they fall far too fast: a h^2 (h squared), not a h."
    return Result(within(err, 0.0, 1e-6), f"{fmt(err)} px off the parabola after 1 s",
                  "< 1e-06 px (exact but for rounding)", hint)


# ----- the spring: order, energy, drag -----------------------------------------------------------
ORDER_STEPS = (40, 80, 160)            # end at 1.25 periods: the phase error shows fully there


def measure_order(m: Student) -> dict:
    return {"ends": [run_spring(m, 1.25 / n, 1.25)[-1] for n in ORDER_STEPS]}


def judge_order(raw: Raw) -> Result:
    ends = raw.array("ends", (len(ORDER_STEPS),))
    errors = [float(abs(e - AMPLITUDE * math.cos(OMEGA * 1.25))) for e in ends]
    p = order(errors)
    hint = "x' = x + (x - x_prev) + a h^2 with a at the current x."
    if within(p, 1.0, 0.3):
        hint = ("error halves when h halves: first order. Did you update the position with the "
                "old velocity (Euler) instead of x + (x - x_prev) + a h^2?")
    elif within(p, 0.0, 0.3):
        hint = "the error does not shrink with h: a term has the wrong power of h (a h^2)."
    return Result(within(p, 2.0, 0.2), f"order {fmt(p)} (errors {', '.join(map(fmt, errors))} px)",
                  "2 +- 0.2", hint)


def measure_energy(m: Student) -> dict:
    return {"xs": run_spring(m, 1 / 60, 20.0)}


def judge_energy(raw: Raw) -> Result:
    e = spring_energy(raw.array("xs", (1201,)), 1 / 60)
    ratio = float(e[-60:].mean() / e[:60].mean())
    hint = ("with drag 0 the energy must not drift: x' = x + (x - x_prev) + a h^2 exactly "
            "(1 - drag multiplies only (x - x_prev)).")
    if ratio > 1.01:
        hint = ("the energy grows: forward Euler's spiral does that, and so does any wrong "
                "term (see 'free fall'). " + hint)
    return Result(within(ratio, 1.0, 0.01), f"energy ratio {fmt(ratio)} after 20 s",
                  "1 +- 0.01", hint)


DRAG_HINT = ("drag takes a fraction of the distance travelled: x' = x + (1 - drag) (x - x_prev) "
             "+ a h^2, i.e. (2 - drag) x - (1 - drag) x_prev + a h^2.")


def measure_drag(m: Student) -> dict:
    return {"xs": run_spring(m, 1 / 60, 2.0, drag=0.01)}


def drag_run_with(kind: str) -> np.ndarray:
    """The drag check's spring run with one of the usual drag mistakes (here, in the parent):
    'drag sign' x + (1 + drag)(x - x_prev), 'slide literal' (2 - drag) x - x_prev, 'drag twice'
    x + (1 - drag)^2 (x - x_prev), 'no drag' x + (x - x_prev)."""
    class Mistake:
        @staticmethod
        def verlet_step(x, x_prev, a, h, drag):
            keep = {"drag sign": 1 + drag, "drag twice": (1 - drag) ** 2,
                    "no drag": 1.0}.get(kind, 1 - drag)
            if kind == "slide literal":
                return (2 - drag) * x - x_prev + a * h * h, x.copy()
            return x + keep * (x - x_prev) + a * h * h, x.copy()
    with np.errstate(all="ignore"):
        return run_spring(Mistake, 1 / 60, 2.0, drag=0.01)


def judge_drag(raw: Raw) -> Result:
    xs = raw.array("xs", (121,))
    e = spring_energy(xs, 1 / 60)
    ratio = float(e[-60:].mean() / e[:60].mean())
    expected = 0.99 ** 60           # the amplitude falls by sqrt(1 - drag) per step
    named = {kind: text for kind, text in (
        ("drag sign", "the energy GROWS: (1 - drag), not (1 + drag)."),
        ("slide literal", "Lowering only the 2 (1.99 x - x_prev) is no drag: it pulls every "
                          "particle towards x = 0."),
        ("no drag", "no energy lost: drag is not used (x + (x - x_prev) + a h^2 whatever "
                    "drag is)."),
        ("drag twice", "twice the loss of (1 - drag): the drag is applied twice ((1 - drag)^2, "
                       "or to both x and x_prev).")) if np.allclose(
            xs, drag_run_with(kind), rtol=1e-9, atol=1e-9)}
    hint = " ".join(named.values()) + (" " if named else "") + DRAG_HINT
    if not named:
        hint = (f"the energy kept over 1 s is {fmt(ratio)}, where (1 - drag) per step keeps "
                f"{expected:.2f}. " + DRAG_HINT)
        if not math.isfinite(ratio) or ratio > 3.0:
            hint = ("the energy grows without bound, with drag or without: fix 'free fall' and "
                    "'energy kept' first. " + DRAG_HINT)
    return Result(within(ratio, expected, 0.05),
                  f"energy ratio {fmt(ratio)} over 1 s at drag 0.01",
                  f"{expected:.2f} +- 0.05 (x (1 - drag) per step)", hint)


TERMINAL_H, TERMINAL_DRAG, TERMINAL_STEPS = 1 / 60, 0.01, 1200
TERMINAL = G[1] * TERMINAL_H / TERMINAL_DRAG        # 1500 px/s


def measure_terminal(m: Student) -> dict:
    x = np.array([[480.0, 0.0]])
    x_prev = x.copy()
    for _ in range(TERMINAL_STEPS):
        x, x_prev = step(m, x, x_prev, G[None, :], TERMINAL_H, TERMINAL_DRAG)
    return {"x": x[0], "x_prev": x_prev[0]}


def judge_terminal(raw: Raw) -> Result:
    x, x_prev = raw.array("x", (2,)), raw.array("x_prev", (2,))
    speed = float(x[1] - x_prev[1]) / TERMINAL_H
    hint = (f"a fall with drag settles where the drag takes as much travel as gravity adds: "
            f"(x - x_prev) drag = g h^2, a speed g h / drag = {TERMINAL:g} px/s. " + DRAG_HINT)
    if within(speed, (1 - TERMINAL_DRAG) * TERMINAL, 0.5):
        hint = ("terminal speed (1 - drag) x 1500: your drag also slows gravity. (1 - drag) "
                "multiplies only (x - x_prev); a h^2 is added in full: x + (1 - drag) (x - x_prev) "
                "+ a h^2, not x + (1 - drag) ((x - x_prev) + a h^2).")
    elif within(speed, 0.0, 1.0):
        hint = "it does not fall: " + hint
    return Result(within(speed, TERMINAL, 0.5),
                  f"speed {speed:.1f} px/s after {TERMINAL_STEPS / 60:g} s of falling",
                  f"{TERMINAL:g} +- 0.5 px/s (g h / drag)", hint)


# ----- inputs kept -------------------------------------------------------------------------------
def inputs() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(1)
    x, x_prev, a = rng.normal(size=(3, 4, 2)) * 10
    return x, x_prev, a


def measure_inputs(m: Student) -> dict:
    x, x_prev, a = inputs()
    x_new, x_old = step(m, x, x_prev, a, 0.01, 0.0)
    return {"x_after": x, "a_after": a, "second": x_old, "same_array": bool(
        np.shares_memory(x_new, x))}


def judge_inputs(raw: Raw) -> Result:
    x0, _, a0 = inputs()
    problems = []
    if not np.array_equal(raw.array("x_after", (4, 2)), x0):
        problems.append("x was changed")
    if not np.array_equal(raw.array("a_after", (4, 2)), a0):
        problems.append("a was changed")
    if raw.flag("same_array"):
        problems.append("x_new is the array x")
    if not np.array_equal(raw.array("second", (4, 2)), x0):
        problems.append("the second value is not the old x")
    return Result(not problems, "; ".join(problems) or "x and a untouched, x_new a new array",
                  "x and a unchanged; return (x_new, x)",
                  "compute x_new into a new array (x + ... makes one; x += ... changes the "
                  "caller's x, which is also the x_prev you return). Reusing x_prev's array for "
                  "x_new is fine: the caller is done with it (the slide's pointer swap).")


# ----- random particles, accelerations, steps and drags (a new seed each run) ---------------------
RANDOM_CASES, RANDOM_STEPS = 4, 5


def random_cases() -> list[tuple[np.ndarray, np.ndarray, np.ndarray, float, float]]:
    """1 to 40 particles anywhere, moving any way, each with its own acceleration (any direction,
    up to 5000 px/s^2), h from 1 ms to 0.1 s, drag 0 (the first case) to 0.5."""
    rng = cases_rng("verlet random")
    cases = []
    for k in range(RANDOM_CASES):
        n = int(rng.integers(1, 41))
        x = rng.uniform(-500.0, 1500.0, (n, 2))
        h = float(10 ** rng.uniform(-3.0, -1.0))
        x_prev = x - rng.normal(0.0, 400.0, (n, 2)) * h
        a = rng.normal(0.0, 1.0, (n, 2)) * 10 ** rng.uniform(1.0, 3.7, (n, 1))
        drag = 0.0 if k == 0 else float(rng.uniform(0.0, 0.5))
        cases.append((x, x_prev, a, h, drag))
    return cases


def measure_random(m: Student) -> dict:
    out = {}
    for k, (x, x_prev, a, h, drag) in enumerate(random_cases()):
        xs = []
        for _ in range(RANDOM_STEPS):       # the same accelerations each step, chained
            x, x_prev = step(m, x.copy(), x_prev.copy(), a.copy(), h, drag)
            xs.append((x, x_prev))
        out[str(k)] = {"x": [p[0] for p in xs], "x_prev": [p[1] for p in xs]}
    return out


def judge_random(raw: Raw) -> Result:
    from app.physics.jakobsen import verlet_step
    worst = 0.0
    for k, (x0, xp0, a, h, drag) in enumerate(random_cases()):
        one = Raw(raw.values.get(str(k)))
        n = len(x0)
        xs, xps = (one.array("x", (RANDOM_STEPS, n, 2)), one.array("x_prev", (RANDOM_STEPS, n, 2)))
        x, x_prev = x0, xp0
        for s in range(RANDOM_STEPS):       # each step from the student's own last state
            want, want_prev = verlet_step(xs[s - 1] if s else x0, xps[s - 1] if s else xp0, a, h,
                                          drag)
            here = xs[s - 1] if s else x0
            scale = float(np.abs(here).max() + np.abs(here - (xps[s - 1] if s else xp0)).max()
                          + np.abs(a).max() * h * h)
            tol = rounding(scale, ops=4)
            err = max(float(np.abs(xs[s] - want).max()), float(np.abs(xps[s] - want_prev).max()))
            worst = max(worst, err / tol) if math.isfinite(err) else math.inf
            if not err <= tol:
                mean = verlet_step(here, xps[s - 1] if s else xp0,
                                   np.broadcast_to(a.mean(axis=0), a.shape), h, drag)[0]
                hint = ("x' = x + (1 - drag) (x - x_prev) + a h^2, each particle with its own "
                        "row of a; return (x', x).")
                if n > 1 and np.allclose(xs[s], mean, rtol=0, atol=tol):
                    hint = ("every particle got the same acceleration, the mean of a: each "
                            "particle has its own row a[k] (a has shape (n, 2)); use a as it is.")
                elif np.allclose(xs[s], want, rtol=0, atol=tol):
                    hint = ("x' is right, the second value is not: return (x', x), the old x as "
                            "the next x_prev.")
                return Result(False, f"case {k + 1} of {RANDOM_CASES} ({n} particles, h = "
                              f"{h:.3g} s, drag {drag:.3g}), step {s + 1}: {fmt(err)} px off the "
                              "lab's step", f"< {tol:.2g} px (the lab's own rounding here)", hint)
    return Result(True, f"{RANDOM_CASES} random systems x {RANDOM_STEPS} steps: within "
                  f"{worst:.2g} of the rounding bound", "each step within the lab's rounding")


EXERCISE = Exercise(
    name="verlet",
    title="Verlet integration: the velocity-less step with drag",
    slide="Physics in Computer Animations and Games: 'Verlet integration' "
          "(x' = 2x - x_prev + a h^2; lowering 2 to 1.99 adds drag)",
    functions=("verlet_step",),
    reference=reference,
    checks=(Check("free fall", measure_free_fall, judge_free_fall),
            Check("order 2 on a spring", measure_order, judge_order),
            Check("energy kept (drag 0)", measure_energy, judge_energy),
            Check("drag loses energy", measure_drag, judge_drag),
            Check("terminal speed with drag", measure_terminal, judge_terminal),
            Check("inputs kept", measure_inputs, judge_inputs),
            Check("random particles and steps", measure_random, judge_random)),
)
