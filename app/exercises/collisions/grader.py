"""Grader of exercises/collisions.py: Jakobsen's projection out of a circle and Coulomb friction
on the Verlet particles that touch it.

Reference: app.physics.circle_contact (push_out, friction: the lab's `project` and
`verlet_friction`, which its Verlet cloth runs on its obstacles). Each measure (in the child)
calls the student's functions on arrays of its own and sends back what they left in x (both
functions work in place), the depth push_out returned and what else they changed; each judge
(here, in the grader) compares with the answer. The fixed cases, on the circle c = (400, 300),
r = 100:
  inside pushed      (450, 300) -> (500, 300) and (370, 260) -> (340, 220), both 50 px deep (one
                     with w = 0.5: any w > 0 moves), (400, 390) -> (400, 400), 10 px deep
  outside untouched  (600, 300), (400, 150) outside; (460, 380), (400, 200), (300, 300) exactly
                     on the surface (d = r: not inside): none moves, depth 0
  at the centre      (400, 300) leaves through the top: (400, 200), depth 100 (no NaN); beside
                     it (450, 300) -> (500, 300)
  pinned             w = 0 inside and at the centre: not moved, depth 0; a free one beside moves
  slow slide sticks  mu = 0.5: on top, depth 4, travel (1.5, 3): |v_t| = 1.5 <= mu depth = 2, so
                     x goes back to x_prev's x: (398.5, 200); a purely normal travel stays; at
                     (500, 300) a contact only 1e-4 px deep with a slide of 3e-5 px sticks too
  fast slide slows   mu = 0.5: at (500, 300), depth 2, travel (-1, 4): v_t = (0, 4) loses
                     mu depth = 1: (500, 299); at (340, 220), depth 5, |v_t| = 10 loses 2.5
  only touching      depth 0 (outside, on the surface) with any travel: friction moves nothing;
                     mu = 0 moves nothing
  inputs kept        w, center (push_out) and x_prev, center, depth (friction) unchanged
The depth push_out reports is checked against how far the grader sees each particle move: the
grader believes no number the student's code states about its own work.
  random circles and particles  RANDOM_CASES circles (seeded) anywhere, radius 0.1 to 1000
                     px, 1 to 60 particles inside, on, outside, at the centre, some pinned: x
                     and depth within the lab's float64 rounding
  random travels and mu  on the same circles, about 70% of the particles on the surface with a
                     depth of up to r (as push_out leaves them), the others anywhere with depth
                     0; any travel (mostly 0.01 to 1000 px a step), mu from 0 to 2 (one case 2 to 20):
                     x within the lab's rounding
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import (Check, Exercise, Raw, Result, Student, array_of, cases_rng, fmt,
                                rounding)
from app.exercises.collisions.hints import (depth_hint, friction_hint, friction_with, push_hint,
                                            push_with)

C, R = np.array([400.0, 300.0]), 100.0
TOL = 1e-9                  # px: the fixed cases' answers are exact but for rounding


def reference() -> SimpleNamespace:
    from app.physics.circle_contact import friction, push_out
    # the mistakes' models hold the answer too (their 'right' case): named here, the sandbox's
    # harness stubs them like the reference (app/exercises/harness.py); the judges, in the
    # grader's own process, use them
    from app.exercises.collisions.hints import friction_with, push_with  # noqa: F401
    return SimpleNamespace(push_out=push_out, friction=friction)


# ----- calling the student's functions (in the child) -------------------------------------------
def call_push(m: Student, x, w, c, r) -> dict:
    """push_out on copies; what it left in x and w, center and the depth it returned."""
    x, w, c = np.array(x, dtype=float), np.array(w, dtype=float), np.array(c, dtype=float)
    depth = array_of(m.push_out(x, w, c, float(r)), (len(x),), "push_out's depth")
    return {"x": x, "depth": depth, "w": w, "center": c}


def call_friction(m: Student, x, x_prev, c, depth, mu) -> dict:
    """friction on copies; what it left in x, x_prev, center and depth (and an array it
    returned, for the hint: the contract is in place)."""
    x, x_prev = np.array(x, dtype=float), np.array(x_prev, dtype=float)
    c, depth = np.array(c, dtype=float), np.array(depth, dtype=float)
    out = m.friction(x, x_prev, c, depth, float(mu))
    returned = None
    if isinstance(out, np.ndarray) and out.shape == x.shape:
        try:
            returned = np.array(out, dtype=float)
        except (TypeError, ValueError):     # an array of something else: no hint from it
            returned = None
    return {"x": x, "x_prev": x_prev, "center": c, "depth": depth, "returned": returned}


# ----- projection: the fixed cases ---------------------------------------------------------------
# (particles, w, where they belong, their depth)
INSIDE = (np.array([[450.0, 300.0], [370.0, 260.0], [400.0, 390.0]]), np.array([1.0, 0.5, 1.0]),
          np.array([[500.0, 300.0], [340.0, 220.0], [400.0, 400.0]]), np.array([50.0, 50.0, 10.0]))
OUTSIDE = (np.array([[600.0, 300.0], [400.0, 150.0], [460.0, 380.0], [400.0, 200.0],
                     [300.0, 300.0]]), np.ones(5), None, np.zeros(5))
CENTRE = (np.array([[400.0, 300.0], [450.0, 300.0]]), np.ones(2),
          np.array([[400.0, 200.0], [500.0, 300.0]]), np.array([100.0, 50.0]))
PINNED = (np.array([[450.0, 300.0], [400.0, 300.0], [370.0, 260.0]]), np.array([0.0, 0.0, 1.0]),
          np.array([[450.0, 300.0], [400.0, 300.0], [340.0, 220.0]]), np.array([0.0, 0.0, 50.0]))

PUSH_KINDS = ("only first", "new array", "half", "twice", "inward", "to depth", "outside too",
              "pins ignored", "w is 1", "centre NaN", "centre kept", "centre down")


def push_measure(case):
    return lambda m: call_push(m, case[0], case[1], C, R)


def where(p) -> str:
    return "(" + ", ".join("NaN" if v != v else f"{v:.6g}" for v in p) + ")"


def farthest(off: np.ndarray) -> int:
    """The particle farthest off (a NaN or an infinity counts as the farthest)."""
    return int(np.nanargmax(np.where(np.isfinite(off), off, np.inf)))


def judge_push(case, what: str):
    x0, w, want, want_depth = case
    want = x0 if want is None else want

    def judge(raw: Raw) -> Result:
        n = len(x0)
        x, depth = raw.array("x", (n, 2)), raw.array("depth", (n,))
        off = np.hypot(*(x - want).T)
        moved = np.hypot(*(x - x0).T)
        err = float(np.max(off)) if np.isfinite(off).all() else math.nan
        derr = float(np.max(np.abs(depth - want_depth)))
        lies = float(np.max(np.abs(depth - moved)))
        ok = err <= TOL and derr <= TOL and lies <= TOL
        k = farthest(off)
        measured = (f"{fmt(err)} px from where they belong" if not err <= TOL else
                    "every particle where it belongs") + f"; depth {fmt(derr)} px off"
        hint = ""
        if not ok:
            hint = push_hint(x, depth, x0, w, C, R, PUSH_KINDS)
            if not hint and err <= TOL:
                hint = depth_hint(depth, moved, want_depth)
            if not hint:
                hint = (f"particle {k} started at {where(x0[k])} and ended at {where(x[k])}; "
                        f"it belongs at {where(want[k])} ({what}).")
        return Result(ok, measured, f"< {TOL:g} px, and depth = the distance moved", hint)
    return judge


# ----- friction: the fixed cases -----------------------------------------------------------------
MU = 0.5
# (x on the surface, depth, travel v = x - x_prev, where it belongs after friction)
# (the third touched only a little, depth 1e-4 px, as a resting cloth at 1000 Hz does: it sticks)
STICK = (np.array([[400.0, 200.0], [300.0, 300.0], [500.0, 300.0]]), np.array([4.0, 3.0, 1e-4]),
         np.array([[1.5, 3.0], [2.0, 0.0], [-2e-5, 3e-5]]),
         np.array([[398.5, 200.0], [300.0, 300.0], [500.0, 300.0 - 3e-5]]))
SLIDE = (np.array([[500.0, 300.0], [340.0, 220.0]]), np.array([2.0, 5.0]),
         np.array([[-1.0, 4.0], [7.4, -6.8]]), np.array([[500.0, 299.0], [338.0, 221.5]]))
APART = (np.array([[600.0, 300.0], [460.0, 380.0], [500.0, 300.0]]), np.array([0.0, 0.0, 2.0]),
         np.array([[5.0, 5.0], [3.0, -1.0], [-1.0, 4.0]]), None)
APART_MU = np.array([MU, MU, 0.0])          # the touching particle's call has mu = 0

FRICTION_KINDS = ("reverses", "position", "whole travel", "drag everywhere", "fraction",
                  "never slides", "skips shallow")


def friction_measure(case, mus=None):
    def measure(m: Student) -> dict:
        x, depth, v, _ = case
        out = {}
        for mu in sorted(set([MU] if mus is None else mus.tolist())):   # one call per mu
            rows = np.arange(len(x)) if mus is None else np.flatnonzero(mus == mu)
            out[str(mu)] = call_friction(m, x[rows], x[rows] - v[rows], C, depth[rows], mu)
        return out
    return measure


def judge_friction(case, what: str, mus=None):
    x0, depth, v, want = case
    want = x0 if want is None else want

    def judge(raw: Raw) -> Result:
        got = np.empty_like(x0)
        hint = ""
        for mu in sorted(set([MU] if mus is None else mus.tolist())):
            rows = np.arange(len(x0)) if mus is None else np.flatnonzero(mus == mu)
            one = Raw(raw.values.get(str(mu)))
            x = one.array("x", (len(rows), 2))
            got[rows] = x
            returned = one.array("returned", (len(rows), 2)) if one.values.get("returned") \
                is not None else None
            if not hint and not np.allclose(x, want[rows], rtol=0, atol=TOL):
                hint = friction_hint(x, x0[rows], x0[rows] - v[rows], C, depth[rows], mu,
                                     FRICTION_KINDS, one.array("x_prev", (len(rows), 2)),
                                     returned)
        off = np.hypot(*(got - want).T)
        err = float(np.max(off)) if np.isfinite(off).all() else math.nan
        ok = err <= TOL
        if not ok and not hint:
            k = farthest(off)
            travel = got[k] - (x0[k] - v[k])
            hint = (f"particle {k} (depth {depth[k]:g}, travel {where(v[k])}, mu "
                    f"{(MU if mus is None else mus[k]):g}) ended at {where(got[k])}, a travel of "
                    f"{where(travel)}; it belongs at {where(want[k])} ({what}).")
        return Result(ok, f"{fmt(err)} px from where friction leaves them",
                      f"< {TOL:g} px", hint)
    return judge


# ----- inputs kept -------------------------------------------------------------------------------
def measure_inputs(m: Student) -> dict:
    x, depth, v, _ = SLIDE
    return {"push": call_push(m, INSIDE[0], INSIDE[1], C, R),
            "friction": call_friction(m, x, x - v, C, depth, MU)}


def judge_inputs(raw: Raw) -> Result:
    push, fric = Raw(raw.values.get("push")), Raw(raw.values.get("friction"))
    x, depth, v, _ = SLIDE
    problems = [f"{fn} changed {name}" for fn, one, name, before in (
        ("push_out", push, "w", INSIDE[1]), ("push_out", push, "center", C),
        ("friction", fric, "x_prev", x - v), ("friction", fric, "center", C),
        ("friction", fric, "depth", depth))
        if not np.array_equal(one.array(name, np.shape(before)), before)]
    return Result(not problems, "; ".join(problems) or "w, center, x_prev and depth untouched",
                  "only x changes", "change only x (in place); read the other arrays, never "
                  "write into them: the cloth's x_prev and the circle are the caller's.")


# ----- random circles, particles, travels and mu (a new seed each run) ---------------------------
RANDOM_CASES = 6


def random_cases() -> list[tuple[np.ndarray, np.ndarray, np.ndarray, float]]:
    """(x, w, center, radius): a centre anywhere in +-2000 px, a radius of 0.1 to 1000 px (cases
    1 to 4 one decade each, 0.1-1, 1-10, 10-100, 100-1000, so a run never misses one; the
    others any), 1 to 60 particles: inside (any depth), on the surface (up to rounding),
    outside (to 3 r away), exactly at the centre; about a fifth pinned (w = 0), the others any
    w > 0. The first case has one particle, the second every kind at once."""
    rng = cases_rng("collisions random")
    cases = []
    for k in range(RANDOM_CASES):
        n = 1 if k == 0 else int(rng.integers(5 if k == 1 else 2, 61))
        c = rng.uniform(-2000.0, 2000.0, 2)
        r = float(10 ** (rng.uniform(k - 2, k - 1) if 1 <= k <= 4 else rng.uniform(-1.0, 3.0)))
        kind = rng.integers(0, 4, n) if k != 1 else np.arange(n) % 4
        angle = rng.uniform(0.0, 2 * math.pi, n)
        rho = np.select([kind == 0, kind == 1, kind == 2],
                        [r * np.sqrt(rng.uniform(1e-6, 1.0, n)), np.full(n, r),
                         r * rng.uniform(1.0 + 1e-6, 3.0, n)], 0.0)
        x = c + rho[:, None] * np.stack([np.cos(angle), np.sin(angle)], axis=1)
        x[kind == 3] = c                                            # exactly at the centre
        w = np.where(rng.uniform(size=n) < 0.2, 0.0, rng.uniform(0.05, 2.0, n))
        cases.append((x, w, c, r))
    return cases


def measure_random_push(m: Student) -> dict:
    return {str(k): call_push(m, x, w, c, r) for k, (x, w, c, r) in enumerate(random_cases())}


def scale_of(*arrays) -> float:
    return float(sum(np.abs(a).max() for a in arrays if np.size(a)))


def judge_random_push(raw: Raw) -> Result:
    push_out = reference().push_out     # (not imported here: the child's harness leaves it out)
    worst = 0.0
    for k, (x0, w, c, r) in enumerate(random_cases()):
        one = Raw(raw.values.get(str(k)))
        n = len(x0)
        x, depth = one.array("x", (n, 2)), one.array("depth", (n,))
        want = x0.copy()
        want_depth = push_out(want, w, c, r)
        tol = rounding(scale_of(x0, c, r), ops=8)
        moved = np.hypot(*(x - x0).T)
        err = max(float(np.abs(x - want).max()), float(np.abs(depth - want_depth).max()),
                  float(np.abs(depth - moved).max()))
        worst = max(worst, err / tol) if math.isfinite(err) else math.inf
        if not err <= tol:
            off = np.abs(x - want).max(axis=1)
            bad = farthest(off)
            hint = push_hint(x, depth, x0, w, c, r, ("radius 100",) + PUSH_KINDS)
            if not hint and np.allclose(x, want, rtol=0, atol=tol):
                hint = depth_hint(depth, moved, want_depth)
            if not hint:
                d0 = float(np.hypot(*(x0[bad] - c)))
                hint = (f"particle {bad} (w = {w[bad]:.3g}, {d0:.6g} px from the centre) ended "
                        f"at {where(x[bad])}; it belongs at {where(want[bad])}.")
            return Result(False, f"case {k + 1} of {RANDOM_CASES} ({n} particles, centre "
                          f"{where(c)}, radius {r:.4g}): {fmt(err)} px off the lab's answer",
                          f"< {tol:.2g} px (the lab's own rounding here)", hint)
    return Result(True, f"{RANDOM_CASES} random circles: within {worst:.2g} of the rounding "
                  "bound", "x and depth within the lab's rounding")


def friction_cases() -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]]:
    """(x, x_prev, center, depth, mu) on random_cases()' circles: about 70% of the particles
    touch (on the surface, pushed 1e-6 r to r px: depth, every decade alike, so contacts as
    shallow as a resting cloth's come in every run), the others stay where random_cases() put
    them with depth 0 (outside, on, pinned inside); each travels mostly 0.01 to 1000 px in any
    direction; mu 0 (the first case), 2 (the second), else anything between."""
    rng = cases_rng("collisions friction")
    cases = []
    for k, (x, _, c, r) in enumerate(random_cases()):
        n = len(x)
        touching = rng.uniform(size=n) < 0.7
        angle = rng.uniform(0.0, 2 * math.pi, n)
        angle[rng.uniform(size=n) < 0.1] = -math.pi / 2          # the top: from the centre
        surface = c + r * np.stack([np.cos(angle), np.sin(angle)], axis=1)
        x = np.where(touching[:, None], surface, x)
        depth = np.where(touching, r * 10 ** rng.uniform(-6.0, 0.0, n), 0.0)
        v = rng.normal(0.0, 1.0, (n, 2)) * 10 ** rng.uniform(-2.0, 3.0, (n, 1))
        mu = {0: 0.0, 1: 2.0, 2: float(10 ** rng.uniform(0.3, 1.3))}.get(
            k, float(rng.uniform(0.0, 2.0)))
        cases.append((x, x - v, c, depth, mu))
    return cases


def measure_random_friction(m: Student) -> dict:
    return {str(k): call_friction(m, x, xp, c, depth, mu)
            for k, (x, xp, c, depth, mu) in enumerate(friction_cases())}


def judge_random_friction(raw: Raw) -> Result:
    friction = reference().friction
    worst = 0.0
    for k, (x0, xp, c, depth, mu) in enumerate(friction_cases()):
        one = Raw(raw.values.get(str(k)))
        n = len(x0)
        x = one.array("x", (n, 2))
        want = x0.copy()
        friction(want, xp, c, depth, mu)
        tol = rounding(scale_of(x0, xp, mu * depth), ops=16)
        err = float(np.abs(x - want).max())
        worst = max(worst, err / tol) if math.isfinite(err) else math.inf
        if not err <= tol:
            returned = one.array("returned", (n, 2)) if one.values.get("returned") is not None \
                else None
            hint = friction_hint(x, x0, xp, c, depth, mu, ("mu capped",) + FRICTION_KINDS,
                                 one.array("x_prev", (n, 2)), returned)
            if not hint:
                off = np.abs(x - want).max(axis=1)
                bad = farthest(off)
                vt = x0[bad] - xp[bad]
                hint = (f"particle {bad} (depth {depth[bad]:.4g}, travel {where(vt)}) ended at "
                        f"{where(x[bad])}; the lab's friction leaves it at {where(want[bad])}.")
            return Result(False, f"case {k + 1} of {RANDOM_CASES} ({n} particles, mu {mu:.3g}): "
                          f"{fmt(err)} px off the lab's answer",
                          f"< {tol:.2g} px (the lab's own rounding here)", hint)
    return Result(True, f"{RANDOM_CASES} random sets of travels: within {worst:.2g} of the "
                  "rounding bound", "x within the lab's rounding")


EXERCISE = Exercise(
    name="collisions",
    title="Collisions: particles pushed out of a ball, and Coulomb friction",
    slide="Cloth Simulation: 'Verlet cloth' (Jakobsen, Advanced Character Physics: particles "
          "found inside an obstacle are projected to its surface) and the jello cube's "
          "collision detection",
    functions=("push_out", "friction"),
    reference=reference,
    checks=(Check("inside pushed to the surface", push_measure(INSIDE),
                  judge_push(INSIDE, "on the surface, straight out from the centre")),
            Check("outside and on the surface untouched", push_measure(OUTSIDE),
                  judge_push(OUTSIDE, "it was not inside: d >= r")),
            Check("a particle at the centre", push_measure(CENTRE),
                  judge_push(CENTRE, "out through the top, n = (0, -1)")),
            Check("pinned never move", push_measure(PINNED),
                  judge_push(PINNED, "w = 0 never moves")),
            Check("a slow slide sticks", friction_measure(STICK),
                  judge_friction(STICK, "|v_t| <= mu * depth: x - v_t")),
            Check("a fast slide slows", friction_measure(SLIDE),
                  judge_friction(SLIDE, "|v_t| > mu * depth: x - mu * depth * v_t / |v_t|")),
            Check("friction only where touching", friction_measure(APART, APART_MU),
                  judge_friction(APART, "depth 0 or mu 0: friction does nothing", APART_MU)),
            Check("inputs kept", measure_inputs, judge_inputs),
            Check("random circles and particles", measure_random_push, judge_random_push),
            Check("random travels and mu", measure_random_friction, judge_random_friction)),
)

__all__ = ["EXERCISE", "friction_with", "push_with"]
