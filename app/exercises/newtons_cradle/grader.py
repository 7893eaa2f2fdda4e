"""Grader of exercises/newtons_cradle.py: the classwork, judged on the cradle scene's own verdict.

Reference: scenes.newtons_cradle.build_cradle (the scene's builder). The student's build_cradle
builds the scene (`python -m app --scene exercise:newtons_cradle`), at its defaults (5 balls,
hertz 120 x 30 substeps). The measures run it in the child and send back what the scene measured
(or, for 'lifted as asked', where the balls and their strings' anchors are); the judges decide:
  lifted as asked  5 balls, 2 lifted: each hangs STRING px from its anchor, the lifted ones at
                   LIFT_ANGLE (30 degrees) to the left, the others straight down (1e-6); the
                   anchors on the bar (y = BAR_Y), evenly spaced and centred on CENTRE_X; every
                   ball of mass 1 (equal masses swap velocities whatever they are, so only this
                   check sees the mass)
  k in, k out      lift k = 1, 2, 3 and release: k balls swing out at the far end (the scene's
                   `balls_out`, counted in the half swing after the first impact)
  middle still     2 lifted, 10 s: the balls between stay within 2 px of rest (`middle_max_drift`)
  energy kept      1 lifted, 10 s: more than 95% of the energy is left (`energy_ratio`)
  random rows      3 random rows (seeded; any balls, radius, lifted) hang as asked, and a random
                   row gives k in, k out
Settings a builder sets on the space that the scene sets itself (gravity, damping, iterations)
are named in 'lifted as asked' and in the live scene's HUD (overridden, never silently).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import BadAnswer, Check, Exercise, Raw, Result, Student, cases_rng, fmt
from app.exercises.pymunk_run import run_scene

GRADED = {"reference": "off"}       # the grader reads the scene's verdict; no ghost needed
LIFT_DEG, STRING_PX, BALLS, LIFTED = 30.0, 280.0, 5, 2
CENTRE_X, BAR_Y = 480.0, 230.0            # the starter's bar: its middle and its height, px

SPACING_HINT = ("balls pressed together at rest (overlapping) are solved as one lump, and balls "
                "that touch exactly pass only by rounding: leave a hair of space between them "
                "(gap ~0.02 px: pitch = 2 * radius + gap), elasticity 0.9999999 (the slide's "
                "hint), friction 0, strings with error_bias 0.")


def reference() -> SimpleNamespace:
    from scenes.newtons_cradle import build_cradle
    return SimpleNamespace(build_cradle=build_cradle)


SPACE_SETTINGS = ("gravity", "damping", "iterations")    # the scene sets these itself


def space_settings(space) -> dict:
    return {"gravity": tuple(space.gravity), "damping": float(space.damping),
            "iterations": int(space.iterations)}


def overridden(before: dict, after: dict) -> list[str]:
    """The space's settings a builder changed, which the cradle scene sets itself (its g,
    damping and iterations parameters): what the student is told was overridden."""
    return [f"space.{k} = {after[k]!r}" for k in SPACE_SETTINGS if after[k] != before[k]]


OVERRIDE_NOTE = ("the scene sets these itself (its parameters g, damping, iterations) and "
                 "overrides yours: leave them to the scene")


def measure_row(m: Student, balls: int, radius: float, lifted: int) -> dict:
    import pymunk
    from scenes.newtons_cradle import string_of
    space = pymunk.Space()
    before = space_settings(space)
    bodies = m.build_cradle(space, balls, radius, lifted)
    if not isinstance(bodies, (list, tuple)) or len(bodies) != balls or not all(
            isinstance(b, pymunk.Body) for b in bodies):
        raise BadAnswer(f"build_cradle returned {bodies!r:.200}; expected a list of {balls} "
                        "pymunk.Body objects")
    anchors = []
    for b in bodies:
        try:
            anchors.append(string_of(space, b)[1])
        except ValueError:
            anchors.append(None)
    radii = [max([float(c.radius) for c in b.shapes if isinstance(c, pymunk.Circle)],
                 default=-1.0) for b in bodies]
    return {"positions": [tuple(b.position) for b in bodies], "anchors": anchors,
            "masses": [float(b.mass) for b in bodies], "radii": radii,
            "overridden": overridden(before, space_settings(space))}


def measure_lifted(m: Student) -> dict:
    from scenes.newtons_cradle import RADIUS
    return measure_row(m, BALLS, RADIUS, LIFTED)


def judge_row(raw: Raw, balls: int, radius: float, lifted: int) -> Result:
    pos = raw.array("positions", (balls, 2))
    anchors = raw.values.get("anchors")
    if not isinstance(anchors, list) or len(anchors) != balls:
        return Result(False, "no strings found", "a string per ball",
                      "hang each ball on a pymunk.PinJoint(space.static_body, ball, anchor, "
                      "(0, 0)) and add it to the space.")
    if any(a is None for a in anchors):
        k = anchors.index(None)
        return Result(False, f"ball {k} hangs on no string", "a string per ball",
                      "each ball needs a PinJoint to the static body (its string), added to the "
                      "space.")
    anchor = Raw({"a": anchors}).array("a", (balls, 2))
    d = pos - anchor
    angles = np.degrees(np.arctan2(d[:, 0], d[:, 1]))        # from straight down, + to the right
    lengths = np.hypot(d[:, 0], d[:, 1])
    want = np.array([-LIFT_DEG if i < lifted else 0.0 for i in range(balls)])
    angle_err = float(np.abs(angles - want).max())
    length_err = float(np.abs(lengths - STRING_PX).max())
    masses = raw.array("masses", (balls,))
    radii = raw.array("radii", (balls,)) if raw.has("radii") else np.full(balls, radius)
    pitch = np.diff(anchor[:, 0])
    bar = {"the anchors are not on the bar (y = BAR_Y)": bool(np.abs(anchor[:, 1] - BAR_Y).max()
                                                              > 1e-6),
           "the anchors are not evenly spaced": bool(np.ptp(pitch) > 1e-6) if balls > 2 else False,
           "the row is not centred on CENTRE_X": bool(abs(anchor[:, 0].mean() - CENTRE_X)
                                                      > 1e-6),
           "a ball's mass is not 1": bool(np.abs(masses - 1.0).max() > 1e-9),
           f"a ball's radius is not the radius asked ({radius:g})":
               bool(np.abs(radii - radius).max() > 1e-9),
           "neighbouring balls overlap at rest (pitch < 2 radius)":
               bool(np.abs(pitch).min() < 2 * radius - 1e-9) if balls > 1 else False}
    wrong = [text for text, bad in bar.items() if bad]
    ok = angle_err < 1e-6 and length_err < 1e-6 and not wrong
    hint = ("ball i = anchor i + STRING (sin th, cos th), th = -LIFT_ANGLE for the first `lifted` "
            "balls (to the left; y is down), 0 for the others. LIFT_ANGLE is already in radians.")
    if wrong and angle_err < 1e-6 and length_err < 1e-6:
        hint = ("anchor i = (CENTRE_X + (i - (balls - 1) / 2) pitch, BAR_Y): the middle of the "
                "row at CENTRE_X, pitch = 2 radius + gap, with the `radius` given; each ball "
                "pymunk.Body(1, moment) (mass 1).")
    first = angles[:lifted]
    if np.all(np.abs(first + math.radians(LIFT_DEG)) < 1e-6):
        hint = ("the lifted balls hang at -0.52 degrees, not -30: LIFT_ANGLE is already in "
                "radians, and math.radians(LIFT_ANGLE) converts it twice. " + hint)
    elif np.all(np.abs(first - LIFT_DEG) < 1e-6):
        hint = "the lifted balls are pulled out to the RIGHT: the first balls go left (-x). " + hint
    elif lifted < balls and np.all(np.abs(angles[-lifted:] + LIFT_DEG) < 1e-6) and \
            np.all(np.abs(angles[:balls - lifted]) < 1e-6):
        hint = ("the LAST balls are lifted: lift the first `lifted` balls (i < lifted, the left "
                "end), the ones the scene releases into the row. " + hint)
    if balls > 1 and np.all(np.diff(anchor[:, 0]) < 0):
        hint = ("the balls come back right to left (their anchors' x fall along the list you "
                "return): return them in order along the row, left to right; the first `lifted` "
                "of that list are the ones lifted.")
    shown = ", ".join(f"{a:.3g}" for a in angles)
    notes = raw.texts("overridden") if raw.has("overridden") else []
    note = (f"; your build_cradle sets {', '.join(notes)}: {OVERRIDE_NOTE}" if notes else "")
    wanted = ", ".join(f"{w:g}" for w in want)
    return Result(ok, f"angles {shown} deg; strings {fmt(length_err)} px off {STRING_PX:g}"
                  + "".join(f"; {w}" for w in wrong) + (f" (their mean x {fmt(anchor[:, 0].mean())}"
                  ")" if "the row is not centred on CENTRE_X" in wrong else "") + note,
                  f"{wanted} deg and {STRING_PX:g} px, +- 1e-06; anchors on the bar, "
                  "centred; masses 1", hint)


def judge_lifted(raw: Raw) -> Result:
    from scenes.newtons_cradle import RADIUS
    return judge_row(raw, BALLS, RADIUS, LIFTED)


# ----- random rows (a new seed each run) ---------------------------------------------------------
def random_rows() -> list[tuple[int, float, int]]:
    """(balls, radius, lifted): 2 to 9 balls (the scene's range) of radius 5 to 40 px, 1 to
    balls - 1 lifted; and a row for the scene's verdict: 3 to 7 balls of the scene's radius."""
    from scenes.newtons_cradle import RADIUS
    rng = cases_rng("newtons_cradle random")
    rows = []
    for _ in range(3):
        n = int(rng.integers(2, 10))
        rows.append((n, float(rng.uniform(5.0, 40.0)), int(rng.integers(1, n))))
    n = int(rng.integers(3, 8))
    rows.append((n, RADIUS, int(rng.integers(1, (n + 1) // 2 + 1))))
    return rows


def measure_random(m: Student) -> dict:
    rows = random_rows()
    out = {str(k): measure_row(m, *row) for k, row in enumerate(rows)}
    n, _, k = rows[-1]
    out["out"] = run_scene("newtons_cradle", m, 2.8, {**GRADED, "balls": n, "lifted": k}
                           ).metrics()["balls_out"]
    return out


def judge_random(raw: Raw) -> Result:
    rows = random_rows()
    for k, (n, radius, lifted) in enumerate(rows):
        r = judge_row(Raw(raw.values.get(str(k))), n, radius, lifted)
        if not r.passed:
            return Result(False, f"{n} balls of radius {radius:.3g}, {lifted} lifted: "
                          f"{r.measured}", r.bound, r.hint)
    n, _, k = rows[-1]
    out = raw.integer("out")
    if out != k:
        return Result(False, f"{n} balls, {k} in, {out} out", f"{k} out",
                      ("no ball swings out: is the elasticity near 1? " if out == 0 else "")
                      + SPACING_HINT)
    return Result(True, f"{len(rows)} random rows hang as asked; {n} balls: {k} in, {k} out",
                  "each row as asked; k in, k out")


def measure_k_out(k: int):
    def measure(m: Student) -> dict:
        return {"out": run_scene("newtons_cradle", m, 2.8, {**GRADED, "lifted": k}
                                 ).metrics()["balls_out"]}
    return measure


def judge_k_out(k: int):
    def judge(raw: Raw) -> Result:
        out = raw.integer("out")
        hint = SPACING_HINT
        if out == 0:
            hint = "no ball swings out: is the elasticity near 1? " + SPACING_HINT
        return Result(out == k, f"{k} in, {out} out", f"{k} out", hint)
    return judge


def measure_middle(m: Student) -> dict:
    scene = run_scene("newtons_cradle", m, 10.0, {**GRADED, "lifted": 2})
    return {"drift": scene.metrics()["middle_max_drift"]}


def judge_middle(raw: Raw) -> Result:
    drift = raw.number("drift")
    return Result(bool(drift < 2.0), f"middle balls moved up to {fmt(drift)} px in 10 s",
                  "< 2 px", SPACING_HINT)


def measure_energy(m: Student) -> dict:
    return {"ratio": run_scene("newtons_cradle", m, 10.0, {**GRADED, "lifted": 1}
                               ).metrics()["energy_ratio"]}


def judge_energy(raw: Raw) -> Result:
    ratio = raw.optional("ratio")
    hint = ("every impact keeps e^2 of the approach energy: elasticity 0.9999999 on every ball "
            "(pymunk multiplies the two shapes' values), friction 0, and strings that do not "
            "stretch (error_bias 0).")
    if ratio is None:
        return Result(False, "no energy at release", "> 95%", "the lifted balls start at rest "
                      "at the height of their lift: do they hang where asked? " + hint)
    return Result(bool(ratio > 0.95), f"{100 * ratio:.2f}% of the energy left after 10 s",
                  "> 95%", hint)


EXERCISE = Exercise(
    name="newtons_cradle",
    title="Newton's cradle in pymunk",
    slide="Physics in Computer Animations and Games: 'Classwork: Newton's Cradle' "
          "(hint: shape.elasticity = 0.9999999)",
    functions=("build_cradle",),
    reference=reference,
    checks=(Check("lifted as asked", measure_lifted, judge_lifted),
            Check("1 in, 1 out", measure_k_out(1), judge_k_out(1)),
            Check("2 in, 2 out", measure_k_out(2), judge_k_out(2)),
            Check("3 in, 3 out", measure_k_out(3), judge_k_out(3)),
            Check("middle balls still", measure_middle, judge_middle),
            Check("energy kept", measure_energy, judge_energy),
            Check("random rows", measure_random, judge_random)),
)
