"""Grader of exercises/double_pendulum.py: a pymunk double pendulum against its equations of motion.

Reference: scenes.double_pendulum.build_double_pendulum (the scene's builder); the scene's ghost
is the lab's RK4 solution of Lagrange's equations (app/physics/double_pendulum_ode.py). The
student's builder builds `python -m app --scene exercise:double_pendulum`. The measures send back
where the bodies are and what the scene measured; the judges decide:
  built as asked   bob positions at the given angles and lengths (1e-6 px), masses as given,
                   both bodies and both rods (PinJoints) added to the space, the bobs' shapes
                   kept from colliding with each other (a rod shorter than two radii would
                   otherwise push the bobs apart)
  agrees           released low (10 and 10 degrees), the tip stays within 1 px of the ghost for
                   2 s (the largest `reference_divergence` seen)
  energy kept      released high (the scene's 120 and 150 degrees), 20 s: |energy drift| < 1%
                   at every step (a NaN bob is no drift of 0: it fails)
  joints hold      the same release, 5 s: the rods' length error stays under 1 px (`pin_error`)
  random pendulums 3 random builds (seeded; any anchor, lengths, masses, angles) as asked, and a
                   small random release within 1 px of the equations for 1.5 s
"""

from __future__ import annotations

import math
from types import SimpleNamespace

from app.exercises.base import (BadAnswer, Check, Exercise, Raw, Result, Student, cases_rng, fmt,
                                within)
from app.exercises.pymunk_run import run_scene

SOFT_HINT = ("pymunk's joints are soft by default: they correct only part of the length error "
             "each step and that bleeds energy. Set joint.error_bias = 0 on both PinJoints.")
ANCHOR, LENGTHS, MASSES, ANGLES = (480.0, 350.0), (160.0, 120.0), (1.0, 2.0), (0.5, -1.0)


def reference() -> SimpleNamespace:
    from scenes.double_pendulum import build_double_pendulum
    return SimpleNamespace(build_double_pendulum=build_double_pendulum)


def measure_built(m: Student, anchor=ANCHOR, lengths=LENGTHS, masses=MASSES,
                  angles=ANGLES) -> dict:
    import pymunk
    space = pymunk.Space()
    pair = m.build_double_pendulum(space, anchor, lengths, masses, angles)
    if (not isinstance(pair, (tuple, list)) or len(pair) != 2
            or not all(isinstance(b, pymunk.Body) for b in pair)):
        raise BadAnswer(f"build_double_pendulum returned {pair!r:.200}; expected (body1, body2)")
    rods = [{j.a, j.b} for j in space.constraints if isinstance(j, (pymunk.PinJoint,
                                                                    pymunk.SlideJoint))]
    return {"p1": tuple(pair[0].position), "p2": tuple(pair[1].position),
            "masses": [pair[0].mass, pair[1].mass],
            "in_space": [b.space is space for b in pair],
            "rod_to_static": any(pair[0] in r and any(b.body_type == pymunk.Body.STATIC
                                                      for b in r) for r in rods),
            "rod_between": {pair[0], pair[1]} in rods,
            "bobs_collide": any(not (sa.sensor or sb.sensor or sa.filter.rejects_collision(
                sb.filter)) for sa in pair[0].shapes for sb in pair[1].shapes)}


def placements(ANCHOR=ANCHOR, LENGTHS=LENGTHS, ANGLES=ANGLES) -> dict[tuple, str]:  # noqa: N803
    """Where the usual slips put the two bobs, and what to say."""
    def bobs(angles, lengths, trig, second_from_anchor=False):
        (a1, a2), (l1, l2) = angles, lengths
        p1 = (ANCHOR[0] + l1 * trig[0](a1), ANCHOR[1] + l1 * trig[1](a1))
        base = ANCHOR if second_from_anchor else p1
        return p1, (base[0] + l2 * trig[0](a2), base[1] + l2 * trig[1](a2))
    down, side = (math.sin, math.cos), (math.cos, math.sin)
    return {
        bobs([math.radians(t) for t in ANGLES], LENGTHS, down):
            "the angles are already in radians: math.radians() converts them a second time "
            "(the bobs hang almost straight down).",
        bobs(ANGLES, LENGTHS, side): "(cos, sin) measures the angle from the horizontal: from "
                                     "straight down it is (sin theta, cos theta).",
        bobs(ANGLES, LENGTHS[::-1], down): "the lengths are swapped: rod 1 (anchor to bob 1) "
                                           "is l1, rod 2 (bob 1 to bob 2) is l2.",
        bobs(ANGLES, LENGTHS, down, True): "bob 2 hangs from the anchor: p2 = p1 + l2 (sin "
                                           "theta2, cos theta2), from bob 1.",
        bobs(ANGLES, LENGTHS, (math.sin, lambda t: -math.cos(t))):
            "the bobs hang UP: y points down here, so below the anchor is + l cos theta.",
    }


def judge_built(raw: Raw, ANCHOR=ANCHOR, LENGTHS=LENGTHS, MASSES=MASSES,  # noqa: N803
                ANGLES=ANGLES) -> Result:
    p1 = (ANCHOR[0] + LENGTHS[0] * math.sin(ANGLES[0]),
          ANCHOR[1] + LENGTHS[0] * math.cos(ANGLES[0]))
    p2 = (p1[0] + LENGTHS[1] * math.sin(ANGLES[1]), p1[1] + LENGTHS[1] * math.cos(ANGLES[1]))
    err = max(math.dist(raw.array("p1", (2,)), p1), math.dist(raw.array("p2", (2,)), p2))
    masses = raw.array("masses", (2,))
    mass_err = float(max(abs(masses[0] - MASSES[0]), abs(masses[1] - MASSES[1])))
    in_space = raw.array("in_space", (2,), dtype=bool)
    # bodies or joints left out of the space never move: that would pass the energy checks
    missing = [f"body{k + 1} is not in the space" for k in range(2) if not in_space[k]]
    if not raw.flag("rod_to_static"):
        missing.append("no rod (PinJoint) from a static body to body1 in the space")
    if not raw.flag("rod_between"):
        missing.append("no rod (PinJoint) between body1 and body2 in the space")
    if raw.flag("bobs_collide"):
        missing.append("the two bobs' shapes can collide (shape.filter = "
                       "pymunk.ShapeFilter(group=1) on both)")
    ok = err < 1e-6 and mass_err < 1e-9 and not missing
    hint = ("angles are radians from straight DOWN and y points down: p1 = anchor + l1 "
            "(sin t1, cos t1), p2 = p1 + l2 (sin t2, cos t2); Body(mass, moment).")
    swapped = within(masses[0], MASSES[1], 1e-9) and within(masses[1], MASSES[0], 1e-9)
    if missing and raw.flag("bobs_collide") and len(missing) == 1:
        hint = ("keep the bobs from colliding with each other: the same ShapeFilter group on "
                "both shapes, shape.filter = pymunk.ShapeFilter(group=1). " + hint)
    elif missing:
        hint = "space.add(...) every body, shape and joint you make. " + hint
    elif swapped:
        hint = "the masses are swapped: body1 has masses[0], body2 masses[1]. " + hint
    else:                               # where the usual slips put the bobs
        got = (raw.array("p1", (2,)), raw.array("p2", (2,)))
        for (c1, c2), text in placements(ANCHOR, LENGTHS, ANGLES).items():
            if max(math.dist(got[0], c1), math.dist(got[1], c2)) < 1e-6:
                hint = text + " " + hint
                break
    return Result(ok, f"bobs {fmt(err)} px from where asked, masses off by {fmt(mass_err)}"
                  + "".join(f"; {m}" for m in missing),
                  "< 1e-06 px, masses exact, both bodies and rods in the space", hint)


def measure_agrees(m: Student) -> dict:
    worst = [0.0]

    def watch(scene):
        d = scene.metrics()["reference_divergence"]
        d = math.inf if d is None else d          # no ghost to compare with: no agreement
        if worst[0] == worst[0] and not d <= worst[0]:      # the largest, and NaN sticks
            worst[0] = d
    scene = run_scene("double_pendulum", m, 2.0, {"angle1": 10.0, "angle2": 10.0}, watch)
    return {"worst": worst[0], "finite": scene.is_finite()}


def judge_agrees(raw: Raw) -> Result:
    worst = raw.number("worst")
    ok = raw.flag("finite") and worst < 1.0
    return Result(bool(ok), f"tip up to {fmt(worst)} px from the equations' in 2 s", "< 1 px",
                  "two PinJoints: anchor-bob1 and bob1-bob2, each between the bodies' centres; "
                  "the bobs must not collide with each other. " + SOFT_HINT)


def measure_energy(m: Student) -> dict:
    scene = run_scene("double_pendulum", m, 20.0, {"reference": "off", "trail": "off"})
    mt = scene.metrics()
    return {"drift_max": mt["energy_drift_max"], "drift": mt["energy_drift"],
            "finite": scene.is_finite()}


def judge_energy(raw: Raw) -> Result:
    drift, last = raw.number("drift_max"), raw.number("drift")
    worst = max(abs(drift), abs(last)) if drift == drift and last == last else math.nan
    ok = raw.flag("finite") and worst < 0.01
    hint = SOFT_HINT if raw.flag("finite") else (
        "the bobs' positions became NaN: a mass or moment of 0, or an infinite one moving? " +
        SOFT_HINT)
    return Result(bool(ok), f"largest energy drift {100 * worst:.3f}% in 20 s", "< 1%", hint)


def measure_joints(m: Student) -> dict:
    scene = run_scene("double_pendulum", m, 5.0, {"reference": "off", "trail": "off"})
    return {"pin_error": scene.metrics()["pin_error"]}


def judge_joints(raw: Raw) -> Result:
    err = raw.number("pin_error")
    return Result(bool(err < 1.0), f"rod length error {fmt(err)} px after 5 s", "< 1 px",
                  SOFT_HINT)


# ----- random pendulums (a new seed each run) ----------------------------------------------------
def random_pendulums() -> list[tuple]:
    """(anchor, lengths, masses, angles): anchors anywhere on the screen, rods 20 to 300 px,
    masses 0.05 to 20, angles from -pi to pi; the last one small (within 12 degrees), of the
    scene's ranges and masses 0.5 to 2 (pymunk's iterative solver parts from the equations at a
    mass ratio of 1:50, whoever builds it), run beside the equations for 1.5 s."""
    rng = cases_rng("double_pendulum random")
    out = []
    for k in range(4):
        small = k == 3
        anchor = (480.0, 350.0) if small else tuple(rng.uniform(0.0, 900.0, 2))
        lengths = tuple(rng.uniform(20.0, 170.0 if small else 300.0, 2))
        masses = (tuple(rng.uniform(0.5, 2.0, 2)) if small else   # pymunk's solver drifts
                  tuple(10 ** rng.uniform(math.log10(0.05), math.log10(20.0), 2)))  # at 1:50
        angles = tuple(rng.uniform(-1.0, 1.0, 2) * (math.radians(12.0) if small else math.pi))
        out.append((anchor, lengths, masses, angles))
    return out


def measure_random(m: Student) -> dict:
    cases = random_pendulums()
    out = {str(k): measure_built(m, *case) for k, case in enumerate(cases)}
    _, lengths, masses, angles = cases[-1]
    worst = [0.0]

    def watch(scene):
        d = scene.metrics()["reference_divergence"]
        d = math.inf if d is None else d
        if worst[0] == worst[0] and not d <= worst[0]:
            worst[0] = d
    settings = {"angle1": math.degrees(angles[0]), "angle2": math.degrees(angles[1]),
                "length1": lengths[0], "length2": lengths[1], "mass1": masses[0],
                "mass2": masses[1]}
    scene = run_scene("double_pendulum", m, 1.5, settings, watch)
    out["worst"], out["finite"] = worst[0], scene.is_finite()
    return out


def judge_random(raw: Raw) -> Result:
    cases = random_pendulums()
    for k, case in enumerate(cases):
        r = judge_built(Raw(raw.values.get(str(k))), *case)
        if not r.passed:
            anchor, lengths, masses, angles = case
            return Result(False, f"anchor ({anchor[0]:.4g}, {anchor[1]:.4g}), lengths "
                          f"{lengths[0]:.4g}, {lengths[1]:.4g}, masses {masses[0]:.3g}, "
                          f"{masses[1]:.3g}, angles {angles[0]:.3g}, {angles[1]:.3g} rad: "
                          f"{r.measured}", r.bound, r.hint)
    worst = raw.number("worst")
    _, lengths, masses, angles = cases[-1]
    if not (raw.flag("finite") and worst < 1.0):
        return Result(False, f"released at {math.degrees(angles[0]):.3g} and "
                      f"{math.degrees(angles[1]):.3g} degrees (lengths {lengths[0]:.4g}, "
                      f"{lengths[1]:.4g}, masses {masses[0]:.3g}, {masses[1]:.3g}): the tip up "
                      f"to {fmt(worst)} px from the equations' in 1.5 s", "< 1 px",
                      "two PinJoints: anchor-bob1 and bob1-bob2, each between the bodies' "
                      "centres, with the lengths and masses given. " + SOFT_HINT)
    return Result(True, f"{len(cases)} random pendulums built as asked; a small release within "
                  f"{fmt(worst)} px of the equations", "as asked; < 1 px")


EXERCISE = Exercise(
    name="double_pendulum",
    title="A double pendulum in pymunk",
    slide="Physics in Computer Animations and Games: 'test 10 doublePendulum.py' (the pymunk "
          "exercise after the Newton's cradle classwork)",
    functions=("build_double_pendulum",),
    reference=reference,
    checks=(Check("built as asked", measure_built, judge_built),
            Check("agrees with the equations", measure_agrees, judge_agrees),
            Check("energy kept", measure_energy, judge_energy),
            Check("joints hold", measure_joints, judge_joints),
            Check("random pendulums", measure_random, judge_random)),
)
