"""Grader of exercises/newtons_cradle.py: the classwork, judged by the cradle scene's own verdict.

Reference: scenes.newtons_cradle.build_cradle (the scene's builder). The student's build_cradle
builds the scene (`python -m app --scene exercise:newtons_cradle`), at its defaults (5 balls,
hertz 120 x 30 substeps). Checks:
  k in, k out      lift k = 1, 2, 3 and release: k balls swing out at the far end (the scene's
                   `balls_out`, counted in the half swing after the first impact)
  middle still     2 lifted, 10 s: the balls between stay within 2 px of rest (`middle_max_drift`)
  energy kept      1 lifted, 10 s: more than 95% of the energy is left (`energy_ratio`)
"""

from __future__ import annotations

from types import SimpleNamespace

from app.exercises.base import Check, Exercise, Result, Student, fmt
from app.exercises.pymunk_checks import run_scene

GRADED = {"reference": "off"}       # the grader reads the scene's verdict; no ghost needed

SPACING_HINT = ("balls pressed together at rest (overlapping) are solved as one lump, and balls "
                "that touch exactly pass only by rounding: leave a hair of space between them "
                "(gap ~0.02 px: pitch = 2 * radius + gap), elasticity 0.9999999 (the slide's "
                "hint), friction 0, strings with error_bias 0.")


def reference() -> SimpleNamespace:
    from scenes.newtons_cradle import build_cradle
    return SimpleNamespace(build_cradle=build_cradle)


def k_out(k: int):
    def check(m: Student) -> Result:
        out = run_scene("newtons_cradle", m, 2.8, {**GRADED, "lifted": k}).metrics()["balls_out"]
        hint = SPACING_HINT
        if out == 0:
            hint = "no ball swings out: is the elasticity near 1? " + SPACING_HINT
        return Result(out == k, f"{k} in, {out} out", f"{k} out", hint)
    return check


def middle_still(m: Student) -> Result:
    scene = run_scene("newtons_cradle", m, 10.0, {**GRADED, "lifted": 2})
    drift = scene.metrics()["middle_max_drift"]
    return Result(drift < 2.0, f"middle balls moved up to {fmt(drift)} px in 10 s", "< 2 px",
                  SPACING_HINT)


def energy_kept(m: Student) -> Result:
    ratio = run_scene("newtons_cradle", m, 10.0, {**GRADED, "lifted": 1}).metrics()["energy_ratio"]
    return Result(ratio > 0.95, f"{100 * ratio:.2f}% of the energy left after 10 s", "> 95%",
                  "every impact keeps e^2 of the approach energy: elasticity 0.9999999 on "
                  "every ball (pymunk multiplies the two shapes' values), friction 0, and "
                  "strings that do not stretch (error_bias 0).")


EXERCISE = Exercise(
    name="newtons_cradle",
    title="Newton's cradle in pymunk",
    slide="Physics in Computer Animations and Games: 'Classwork: Newton's Cradle' "
          "(hint: shape.elasticity = 0.9999999)",
    functions=("build_cradle",),
    reference=reference,
    checks=(Check("1 in, 1 out", k_out(1)), Check("2 in, 2 out", k_out(2)),
            Check("3 in, 3 out", k_out(3)), Check("middle balls still", middle_still),
            Check("energy kept", energy_kept)),
)
