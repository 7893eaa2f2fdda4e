"""Grader of exercises/double_pendulum.py: a pymunk double pendulum against its equations of motion.

Reference: scenes.double_pendulum.build_double_pendulum (the scene's builder); the scene's ghost
is the lab's RK4 solution of Lagrange's equations (app/physics/double_pendulum_ode.py). The
student's builder builds `python -m app --scene exercise:double_pendulum`. Checks:
  built as asked   bob positions at the given angles and lengths (1e-6 px), masses as given,
                   both bodies and both rods (PinJoints) added to the space
  agrees           released low (10 and 10 degrees), the tip stays within 1 px of the ghost for
                   2 s (the largest `reference_divergence` seen)
  energy kept      released high (the scene's 120 and 150 degrees), 20 s: |energy drift| < 1%
  joints hold      the same release, 5 s: the rods' length error stays under 1 px (`pin_error`)
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import pymunk

from app.exercises.base import BadAnswer, Check, Exercise, Result, Student, fmt
from app.exercises.pymunk_checks import run_scene

SOFT_HINT = ("pymunk's joints are soft by default: they correct only part of the length error "
             "each step and that bleeds energy. Set joint.error_bias = 0 on both PinJoints.")


def reference() -> SimpleNamespace:
    from scenes.double_pendulum import build_double_pendulum
    return SimpleNamespace(build_double_pendulum=build_double_pendulum)


def built(m: Student) -> Result:
    space = pymunk.Space()
    anchor, lengths, masses, angles = (480.0, 350.0), (160.0, 120.0), (1.0, 2.0), (0.5, -1.0)
    pair = m.build_double_pendulum(space, anchor, lengths, masses, angles)
    if (not isinstance(pair, (tuple, list)) or len(pair) != 2
            or not all(isinstance(b, pymunk.Body) for b in pair)):
        raise BadAnswer(f"build_double_pendulum returned {pair!r}; expected (body1, body2)")
    p1 = (anchor[0] + lengths[0] * math.sin(angles[0]),
          anchor[1] + lengths[0] * math.cos(angles[0]))
    p2 = (p1[0] + lengths[1] * math.sin(angles[1]), p1[1] + lengths[1] * math.cos(angles[1]))
    err = max(math.dist(pair[0].position, p1), math.dist(pair[1].position, p2))
    mass_err = max(abs(pair[0].mass - masses[0]), abs(pair[1].mass - masses[1]))
    # bodies or joints left out of the space never move: that would pass the energy checks
    missing = [f"body{k + 1} is not in the space" for k, b in enumerate(pair)
               if b.space is not space]
    rods = [{j.a, j.b} for j in space.constraints if isinstance(j, (pymunk.PinJoint,
                                                                    pymunk.SlideJoint))]
    if not any(pair[0] in r and any(b.body_type == pymunk.Body.STATIC for b in r) for r in rods):
        missing.append("no rod (PinJoint) from a static body to body1 in the space")
    if {pair[0], pair[1]} not in rods:
        missing.append("no rod (PinJoint) between body1 and body2 in the space")
    ok = err < 1e-6 and mass_err < 1e-9 and not missing
    hint = ("angles are radians from straight DOWN and y points down: p1 = anchor + l1 "
            "(sin t1, cos t1), p2 = p1 + l2 (sin t2, cos t2); Body(mass, moment).")
    if missing:
        hint = "space.add(...) every body, shape and joint you make. " + hint
    return Result(ok, f"bobs {fmt(err)} px from where asked, masses off by {fmt(mass_err)}"
                  + "".join(f"; {m}" for m in missing),
                  "< 1e-06 px, masses exact, both bodies and rods in the space", hint)


def agrees(m: Student) -> Result:
    worst = [0.0]

    def watch(scene):
        worst[0] = max(worst[0], scene.metrics()["reference_divergence"])
    run_scene("double_pendulum", m, 2.0, {"angle1": 10.0, "angle2": 10.0}, watch)
    return Result(worst[0] < 1.0, f"tip up to {fmt(worst[0])} px from the equations' in 2 s",
                  "< 1 px", "two PinJoints: anchor-bob1 and bob1-bob2, each between the bodies' "
                  "centres; the bobs must not collide with each other. " + SOFT_HINT)


def energy_kept(m: Student) -> Result:
    drift = run_scene("double_pendulum", m, 20.0, {"reference": "off", "trail": "off"}
                      ).metrics()["energy_drift_max"]
    return Result(drift < 0.01, f"largest energy drift {100 * drift:.3f}% in 20 s", "< 1%",
                  SOFT_HINT)


def joints_hold(m: Student) -> Result:
    err = run_scene("double_pendulum", m, 5.0, {"reference": "off", "trail": "off"}
                    ).metrics()["pin_error"]
    return Result(err < 1.0, f"rod length error {fmt(err)} px after 5 s", "< 1 px", SOFT_HINT)


EXERCISE = Exercise(
    name="double_pendulum",
    title="A double pendulum in pymunk",
    slide="Physics in Computer Animations and Games: 'test 10 doublePendulum.py' (the pymunk "
          "exercise after the Newton's cradle classwork)",
    functions=("build_double_pendulum",),
    reference=reference,
    checks=(Check("built as asked", built), Check("agrees with the equations", agrees),
            Check("energy kept", energy_kept), Check("joints hold", joints_hold)),
)
