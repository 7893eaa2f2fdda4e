"""Grader of exercises/rk4.py: classical Runge-Kutta and the midpoint method for any ODE
dy/dt = f(t, y).

Reference: app.physics.integrators.rk4_step and midpoint_step. Each measure sends back the y the
student's steps produced (the stability check: the limit its bisection found); each judge:
  RK4 order, spring       x'' = -x over 2.5 s in 16, 32, 64 steps: measured order 4 +- 0.2
  RK4 order, pendulum     theta'' = -sin theta from 1 rad: order 4 +- 0.2 (exact: the lab's RK4
                          at 4096 steps)
  RK4 stage times         dy/dt = t^3 from 0 to 1 in 4 steps: RK4 is Simpson's rule here, exact
                          (to 1e-12) if k2, k3 are taken at t + h/2 and k4 at t + h
  RK4 stability limit     the largest omega*h at which RK4 keeps the spring bounded:
                          2 sqrt 2 = 2.83 +- 2% (found by bisection on 400-step runs)
  midpoint order, spring  order 2 +- 0.2;   midpoint order, pendulum: order 2 +- 0.2
  midpoint, not Heun      dy/dt = t^2 from 0 to 1 in 4 steps: the midpoint method is the
                          midpoint rule here (0.328125, f at t + h/2); Heun's method, also second
                          order, is the trapezoid rule (0.34375), Ralston's is exact (1/3)
  any shape of y          y of shape (3, 2): both steps return shape (3, 2), equal to the lab's
  y kept                  neither step changes the y it was given
  random ODEs      4 random linear ODEs and cubics (seeded): each step's closed form
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import (Check, Exercise, Raw, Result, Student, array_of, cases_rng, fmt,
                                order, rounding, within)

STEPS = (16, 32, 64)
T_END, Y0 = 2.5, (1.0, 0.0)


def reference() -> SimpleNamespace:
    from app.physics.integrators import midpoint_step, rk4_step
    return SimpleNamespace(rk4_step=rk4_step, midpoint_step=midpoint_step)


def spring(t: float, y: np.ndarray) -> np.ndarray:
    return np.array([y[1], -y[0]])


def pendulum(t: float, y: np.ndarray) -> np.ndarray:
    return np.array([y[1], -math.sin(y[0])])


def integrate(step, f, y0, t_end: float, n: int, what: str) -> np.ndarray:
    y, h = np.array(y0, dtype=float), t_end / n
    for k in range(n):
        y = array_of(step(f, k * h, y, h), y.shape, what)
    return y


# ----- one step on a probe, to name the usual mistakes ---------------------------------------
def probe_f(t: float, y: np.ndarray) -> np.ndarray:
    """Depends on t and on y (every mistake in the stages or their times shows)."""
    return np.array([y[1] + t * t, -2.0 * y[0] + t])


PROBE = (0.3, np.array([1.0, -0.5]), 0.1)        # t, y, h

RK4_MISTAKES = {
    "increment": "you return the increment h/6 (k1 + 2 k2 + 2 k3 + k4) without y: y_new = y + "
                 "that.",
    "no h": "the h is missing in y + h/6 (k1 + 2 k2 + 2 k3 + k4).",
    "quarter": "the weights are divided by 4: y + h/6 (k1 + 2 k2 + 2 k3 + k4), 1 + 2 + 2 + 1 = "
               "6.",
    "equal": "equal weights (k1 + k2 + k3 + k4)/4 give order 2: y + h/6 (k1 + 2 k2 + 2 k3 + "
             "k4).",
    "k3 from k1": "k3 starts from k1: k3 = f(t + h/2, y + h/2 k2), from k2.",
    "full h stages": "k2 and k3 go half a step (h/2), not a whole h.",
    "h^2 stage": "h squared in a stage: k4 = f(t + h, y + h k3), one h.",
    "k4 at h/2": "k4 is taken at t + h/2: k4 = f(t + h, y + h k3), at the END of the step.",
    "times fixed": "every stage is taken at time t: k2 and k3 at t + h/2, k4 at t + h.",
}
MIDPOINT_MISTAKES = {
    "increment": "you return the increment h k2 without y: y_new = y + h k2.",
    "half step": "y + h/2 k2 goes only half a step: y_new = y + h k2 (the slope from the "
                 "midpoint, over the whole step).",
    "full to midpoint": "the 'midpoint' is a whole Euler step away: k2 = f(t + h/2, y + h/2 "
                        "k1), half a step.",
    "heun": "that is Heun's method (y + h/2 (k1 + k2), k2 at t + h): the midpoint method takes "
            "one slope, at the midpoint.",
    "time fixed": "the midpoint's slope is taken at time t: k2 = f(t + h/2, y + h/2 k1).",
    "euler": "that is Euler's step, y + h f(t, y): the midpoint method takes the slope at the "
             "midpoint, k2 = f(t + h/2, y + h/2 k1).",
}


def rk4_with(kind: str, f, t, y, h):
    half = h if kind == "full h stages" else h / 2
    t2, t4 = (t, t) if kind == "times fixed" else (t + h / 2, t + (h / 2 if kind == "k4 at h/2"
                                                                    else h))
    k1 = f(t, y)
    k2 = f(t2, y + half * k1)
    k3 = f(t2, y + half * (k1 if kind == "k3 from k1" else k2))
    k4 = f(t4, y + (h * h if kind == "h^2 stage" else h) * k3)
    if kind == "equal":
        return y + h / 4 * (k1 + k2 + k3 + k4)
    step = {"no h": 1.0 / 6, "quarter": h / 4}.get(kind, h / 6) * (k1 + 2 * k2 + 2 * k3 + k4)
    return step if kind == "increment" else y + step


def midpoint_with(kind: str, f, t, y, h):
    k1 = f(t, y)
    if kind == "euler":
        return y + h * k1
    if kind == "heun":
        return y + h / 2 * (k1 + f(t + h, y + h * k1))
    if kind == "full to midpoint":     # a whole Euler step, and its end's slope
        k2 = f(t + h, y + h * k1)
    else:
        k2 = f(t if kind == "time fixed" else t + h / 2, y + h / 2 * k1)
    step = (h / 2 if kind == "half step" else h) * k2
    return step if kind == "increment" else y + step


def measure_probe(m: Student, fname: str) -> list:
    t, y, h = PROBE
    return array_of(getattr(m, fname)(probe_f, t, y.copy(), h), (2,), fname)


def probe_mistake(fname: str, raw: Raw) -> str:
    """The usual mistake that one step on the probe matches ('' if none, or if it is right)."""
    if not raw.has("probe"):
        return ""
    got = raw.array("probe", (2,))
    table, step = ((RK4_MISTAKES, rk4_with) if fname == "rk4_step"
                   else (MIDPOINT_MISTAKES, midpoint_with))
    right = step("", probe_f, *PROBE)
    if np.allclose(got, right, rtol=1e-12, atol=1e-14):
        return ""
    for kind, text in table.items():
        if np.allclose(got, step(kind, probe_f, *PROBE), rtol=1e-12, atol=1e-14):
            return text + " "
    return ""


# ----- orders ------------------------------------------------------------------------------------
def measure_order(fname: str, f):
    def measure(m: Student) -> dict:
        step = getattr(m, fname)
        return {"y": [integrate(step, f, Y0, T_END, n, fname) for n in STEPS],
                "probe": measure_probe(m, fname)}
    return measure


def judge_order(fname: str, f, target: float):
    def judge(raw: Raw) -> Result:
        ys = raw.array("y", (len(STEPS), 2))
        exact = (np.array([math.cos(T_END), -math.sin(T_END)]) if f is spring
                 else integrate(reference().rk4_step, f, Y0, T_END, 4096, "the lab's RK4"))
        errors = [float(np.abs(y - exact).max()) for y in ys]
        p = order(errors)
        if fname == "rk4_step":
            hint = ("y' = y + h/6 (k1 + 2 k2 + 2 k3 + k4) with k2 = f(t + h/2, y + h/2 k1), "
                    "k3 = f(t + h/2, y + h/2 k2), k4 = f(t + h, y + h k3).")
            if within(p, 2.0, 0.4):
                hint = ("second order: " + hint + " Equal weights (k1 + k2 + k3 + k4)/4 give "
                        "order 2.")
            elif within(p, 1.0, 0.3):
                hint = ("first order: the stages' states are off. " + hint + " k2 and k3 go "
                        "half a step (h/2), k4 a whole one.")
        else:
            hint = "y' = y + h f(t + h/2, y + h/2 f(t, y)): a HALF step to the midpoint."
            if within(p, 1.0, 0.3):
                hint = ("first order: " + hint + " A full step to the 'midpoint' takes the slope "
                        "at the end of an Euler step: first order, like Euler.")
        hint = probe_mistake(fname, raw) + hint
        return Result(within(p, target, 0.2), f"order {fmt(p)} (errors "
                      f"{', '.join(map(fmt, errors))})", f"{target:g} +- 0.2", hint)
    return judge


# ----- stage times -------------------------------------------------------------------------------
def measure_quadrature(fname: str, power: int):
    def measure(m: Student) -> dict:
        y = integrate(getattr(m, fname), lambda t, y: np.array([t ** power]), np.array([0.0]),
                      1.0, 4, fname)
        return {"y": float(y[0]), "probe": measure_probe(m, fname)}
    return measure


def judge_rk4_times(raw: Raw) -> Result:
    err = abs(raw.number("y") - 0.25)
    named = probe_mistake("rk4_step", raw)
    return Result(within(err, 0.0, 1e-12), f"error {fmt(err)} on dy/dt = t^3", "< 1e-12 (exact)",
                  named or "f(t, y) depends on t: evaluate the stages at their own times (k2 "
                  "and k3 at t + h/2, k4 at t + h).")


MIDPOINT_RULE = 0.25 * sum((t + 0.125) ** 2 for t in (0.0, 0.25, 0.5, 0.75))     # 0.328125
TRAPEZOID = 0.25 * sum((t * t + (t + 0.25) ** 2) / 2 for t in (0.0, 0.25, 0.5, 0.75))  # .34375


def judge_midpoint_times(raw: Raw) -> Result:
    y = raw.number("y")
    hint = probe_mistake("midpoint_step", raw) + (
        "the midpoint method takes the slope at the midpoint, once: y + h f(t + h/2, "
        "y + h/2 f(t, y)). On dy/dt = t^2 that is the midpoint rule.")
    if within(y, TRAPEZOID, 1e-12):
        hint = ("that is Heun's method (the trapezoid: y + h/2 (k1 + k2) with k2 at t + h): also "
                "second order, but not the midpoint method the slide means (and a different "
                "method in Blender's list). " + hint)
    elif within(y, 1.0 / 3.0, 1e-12):
        hint = ("exact here: that is another second-order Runge-Kutta (Ralston's, k2 at t + 2h/3"
                "), not the midpoint method. " + hint)
    return Result(within(y, MIDPOINT_RULE, 1e-12), f"{y:.6g} on dy/dt = t^2 from 0 to 1 in 4 "
                  "steps", f"{MIDPOINT_RULE:g} (the midpoint rule), +- 1e-12", hint)


# ----- stability ---------------------------------------------------------------------------------
def growth(step, z: float, n: int = 400) -> float:
    """|y| after n steps of omega*h = z on x'' = -x, from |y| = 1."""
    y = np.array([1.0, 0.0])
    for k in range(n):
        y = array_of(step(spring, k * z, y, z), (2,), "rk4_step")
        if not np.isfinite(y).all() or abs(y).max() > 1e6:
            return math.inf
    return float(np.hypot(*y))


def measure_stability(m: Student) -> dict:
    lo, hi = 0.5, 4.0
    if growth(m.rk4_step, lo) > 2:
        lo = hi = 0.0                           # unstable even at small steps
    else:
        while hi - lo > 1e-3:
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if growth(m.rk4_step, mid) <= 2 else (lo, mid)
    return {"limit": (lo + hi) / 2, "probe": measure_probe(m, "rk4_step")}


def judge_stability(raw: Raw) -> Result:
    limit, exact = raw.number("limit"), 2 * math.sqrt(2)
    hint = "RK4's region reaches omega*h = 2 sqrt 2 on the imaginary axis; check the weights."
    if limit < 0.1:
        hint = ("unstable even at small steps, as the midpoint method and forward Euler are on a "
                "spring (they gain energy at every h; midpoint by 1 + (omega h)^4/4 per step): "
                + hint)
    hint = probe_mistake("rk4_step", raw) + hint
    return Result(within(limit, exact, 0.02 * exact), f"omega*h = {limit:.3f}",
                  f"{exact:.3f} +- 2%", hint)


# ----- shapes and inputs -------------------------------------------------------------------------
Y_2D = np.array([[1.0, -0.5], [0.3, 2.0], [-1.2, 0.7]])


def decay(t: float, y: np.ndarray) -> np.ndarray:
    return -y


def measure_shape(m: Student) -> dict:
    out = {}
    for fname in ("rk4_step", "midpoint_step"):
        y = getattr(m, fname)(decay, 0.0, Y_2D.copy(), 0.1)
        shape = list(np.shape(y)) if y is not None else None
        out[fname] = {"shape": shape,
                      "y": array_of(y, Y_2D.shape, fname) if shape == [3, 2] else None,
                "probe": measure_probe(m, fname)}
    return out


def judge_shape(raw: Raw) -> Result:
    ref = reference()
    problems = []
    for fname in ("rk4_step", "midpoint_step"):
        got = Raw(raw.values.get(fname))
        shape = got.values.get("shape")
        if shape != [3, 2]:
            shown = "None" if shape is None else str(tuple(shape)) if isinstance(shape, list) \
                else "?"
            problems.append(f"{fname} returned shape {shown}")
            continue
        err = float(np.abs(got.array("y", (3, 2)) - getattr(ref, fname)(decay, 0.0, Y_2D, 0.1)
                           ).max())
        if not within(err, 0.0, 1e-12):
            problems.append(f"{fname} is {fmt(err)} off the lab's")
            named = probe_mistake(fname, got)
            if named:
                problems[-1] += f" ({named.strip()})"
    return Result(not problems, "; ".join(problems) or "shape (3, 2), as the lab's",
                  "shape (3, 2), within 1e-12 of the lab's",
                  "y may have any shape (here 3 particles x 2 coordinates): work with y and "
                  "f(t, y) as whole arrays (y + h/2 * k1) and return an array of y's shape; "
                  "ravel, flatten and np.concatenate change it.")


def measure_kept(m: Student) -> dict:
    out = {}
    for fname in ("rk4_step", "midpoint_step"):
        y = np.array([0.3, -0.2])
        array_of(getattr(m, fname)(pendulum, 0.0, y, 0.1), (2,), fname)
        out[fname] = y
    return out


def judge_kept(raw: Raw) -> Result:
    problems = [f"{fname} changed y" for fname in ("rk4_step", "midpoint_step")
                if not np.array_equal(raw.array(fname, (2,)), [0.3, -0.2])]
    return Result(not problems, "; ".join(problems) or "y untouched", "y unchanged",
                  "return y + ... (a new array); y += ... changes the caller's y, which a "
                  "solver may still need (to retry a step, or to measure the error).")


# ----- random ODEs (a new seed each run) ---------------------------------------------------------
# One step of ANY explicit fourth-order Runge-Kutta method (classical, Kutta's 3/8 rule, ...) on
# a linear system y' = M y is exactly the Taylor polynomial I + hM + (hM)^2/2 + (hM)^3/6 +
# (hM)^4/24 of exp(hM) times y, and on y' = p(t) with p a cubic it is exact (the integral); one
# midpoint step is I + hM + (hM)^2/2 and h p(t + h/2). So the judge compares a step on the two
# side by side (the last row of y obeys y' = p(t), the others y' = M y), for random M, p, t, h
# and shapes of y, with the closed form, within rounding: not only with the lab's code.
RANDOM_CASES = 4


def random_odes() -> list[tuple]:
    """y of shape (k,) or (k, 2) with k = 2 to 5 (the last row the quadrature), M of any sign
    and size with |h M| up to 2.5, a random cubic p, t from -5 to 5, h from 0.001 to 1."""
    rng = cases_rng("rk4 random")
    cases = []
    for _ in range(RANDOM_CASES):
        k = int(rng.integers(2, 6))
        shape = (k,) if rng.random() < 0.5 else (k, 2)
        h = float(10 ** rng.uniform(-3.0, 0.0))
        d = k - 1
        M = rng.normal(0.0, 1.0, (d, d))
        M *= rng.uniform(0.1, 2.5) / (h * max(float(np.abs(np.linalg.eigvals(M)).max()), 1e-9))
        p = rng.normal(0.0, 1.0, 4)                 # p(t) = p0 + p1 t + p2 t^2 + p3 t^3
        y = rng.normal(0.0, 3.0, shape)
        cases.append((M, p, float(rng.uniform(-5.0, 5.0)), y, h))
    return cases


def ode(M: np.ndarray, p: np.ndarray):
    """f(t, y) for the rows y[:-1] (y' = M y) and y[-1] (y' = p(t))."""
    def f(t: float, y: np.ndarray) -> np.ndarray:
        y = np.asarray(y, dtype=float)
        out = np.empty_like(y)
        out[:-1] = M @ y[:-1]
        out[-1] = p[0] + t * (p[1] + t * (p[2] + t * p[3]))
        return out
    return f


def closed_form(fname: str, M, p, t: float, y: np.ndarray, h: float) -> np.ndarray:
    order = 4 if fname == "rk4_step" else 2
    hm = h * M
    term, total = np.eye(len(M)), np.eye(len(M))
    for j in range(1, order + 1):
        term = term @ hm / j
        total = total + term
    out = np.empty_like(y)
    out[:-1] = total @ y[:-1]
    P = lambda s: p[0] * s + p[1] * s ** 2 / 2 + p[2] * s ** 3 / 3 + p[3] * s ** 4 / 4  # noqa
    mid = t + h / 2
    out[-1] = y[-1] + (P(t + h) - P(t) if order == 4 else
                       h * (p[0] + mid * (p[1] + mid * (p[2] + mid * p[3]))))
    return out


def measure_random(m: Student) -> dict:
    out = {}
    for k, (M, p, t, y, h) in enumerate(random_odes()):
        for fname in ("rk4_step", "midpoint_step"):
            out[f"{fname} {k}"] = array_of(getattr(m, fname)(ode(M, p), t, y.copy(), h), y.shape,
                                           fname)
    out["probe rk4_step"] = measure_probe(m, "rk4_step")
    out["probe midpoint_step"] = measure_probe(m, "midpoint_step")
    return out


def judge_random(raw: Raw) -> Result:
    for k, (M, p, t, y, h) in enumerate(random_odes()):
        for fname in ("rk4_step", "midpoint_step"):
            got = raw.array(f"{fname} {k}", y.shape)
            want = closed_form(fname, M, p, t, y, h)
            tmax = abs(t) + h
            scale = float(np.abs(y).max() * 20 + h * np.abs(p).sum() * (1 + tmax) ** 3)
            tol = rounding(scale, ops=8 * len(M))
            err = float(np.abs(got - want).max())
            if not err <= tol:
                named = probe_mistake(fname, Raw({"probe": raw.values.get(f"probe {fname}")}))
                what = "fourth-order Runge-Kutta step" if fname == "rk4_step" else "midpoint step"
                return Result(False, f"case {k + 1} of {RANDOM_CASES}, {fname} (y of shape "
                              f"{y.shape}, t = {t:.3g}, h = {h:.3g}): {fmt(err)} off a {what}",
                              f"< {tol:.2g} (rounding)", named.strip() or (
                                  f"{fmt(err)} off the exact {what} on y' = M y (its Taylor "
                                  f"polynomial of degree {4 if fname == 'rk4_step' else 2}) and "
                                  "y' = p(t) side by side: the stages, their times (t + h/2, "
                                  "t + h) and the weights are where a step goes wrong."))
    return Result(True, f"{RANDOM_CASES} random linear ODEs and cubics: both steps exact but for "
                  "rounding", "each step's closed form, within rounding")


EXERCISE = Exercise(
    name="rk4",
    title="Runge-Kutta: RK4 and the midpoint method for any ODE",
    slide="Physics in Computer Animations and Games: 'Integrating Equations of State' (Euler, "
          "Midpoint = 2nd order Runge-Kutta, RK4 = 4th order Runge-Kutta)",
    functions=("rk4_step", "midpoint_step"),
    reference=reference,
    checks=(Check("RK4 order, spring", measure_order("rk4_step", spring),
                  judge_order("rk4_step", spring, 4)),
            Check("RK4 order, pendulum", measure_order("rk4_step", pendulum),
                  judge_order("rk4_step", pendulum, 4)),
            Check("RK4 stage times", measure_quadrature("rk4_step", 3), judge_rk4_times),
            Check("RK4 stability limit", measure_stability, judge_stability),
            Check("midpoint order, spring", measure_order("midpoint_step", spring),
                  judge_order("midpoint_step", spring, 2)),
            Check("midpoint order, pendulum", measure_order("midpoint_step", pendulum),
                  judge_order("midpoint_step", pendulum, 2)),
            Check("midpoint, not Heun", measure_quadrature("midpoint_step", 2),
                  judge_midpoint_times),
            Check("any shape of y", measure_shape, judge_shape),
            Check("y kept", measure_kept, judge_kept),
            Check("random ODEs", measure_random, judge_random)),
)
