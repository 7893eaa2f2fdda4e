"""Grader of exercises/pivoting_l.py: the pymunk tutorial's add_L with its pin and slide joints.

Reference: the pivoting-L scene's own add_L (scenes/pivoting_l.py, at its default settings). The
student's add_L builds `python -m app --scene exercise:pivoting_l` (balls keep landing on the L).
Checks:
  the L            one dynamic body at the rotation centre L_ORIGIN with two segments; a pin
                   whose anchors meet there; a slide joint from 0 to SLIDE_MAX
  turns on its pin 10 s of balls: the L turns (more than 2 degrees) and its pin error (the
                   scene's largest `pin_error`) stays under 1 px
  stops at max     the same run: the slide joint's largest distance reaches its max (within 1 px)
                   and goes no further than 2 px past it
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import pymunk

from app.exercises.base import BadAnswer, Check, Exercise, Result, Student, fmt
from app.exercises.pymunk_checks import run_scene

RUN = 10.0


def reference() -> SimpleNamespace:
    from scenes.pivoting_l import PivotingLScene

    def add_L(space: pymunk.Space) -> pymunk.Body:
        # the scene's own builder, with the scene's default settings
        defaults = SimpleNamespace(p=PivotingLScene.resolve({})[0])
        return PivotingLScene.add_L(defaults, space)[0]
    return SimpleNamespace(add_L=add_L)


def the_L(m: Student) -> Result:
    from scenes.falling_balls import L_ORIGIN
    from scenes.pivoting_l import SLIDE_ANCHOR
    space = pymunk.Space()
    body = m.add_L(space)
    if not isinstance(body, pymunk.Body):
        raise BadAnswer(f"add_L returned {body!r}; expected the L's pymunk.Body")
    problems = []
    if body.body_type != pymunk.Body.DYNAMIC:
        problems.append("the L is not a dynamic body")
    if math.dist(body.position, L_ORIGIN) > 1e-6:
        problems.append(f"the L is at {tuple(body.position)}, not {L_ORIGIN}")
    if len([s for s in body.shapes if isinstance(s, pymunk.Segment)]) != 2:
        problems.append("the L needs two segments")
    joints = [j for j in space.constraints if body in (j.a, j.b)]
    pins = [j for j in joints if isinstance(j, (pymunk.PinJoint, pymunk.PivotJoint))]
    slides = [j for j in joints if isinstance(j, pymunk.SlideJoint)]
    if not pins:
        problems.append("no PinJoint on the L")
    elif math.dist(pins[0].a.local_to_world(pins[0].anchor_a),
                   pins[0].b.local_to_world(pins[0].anchor_b)) > 1e-6:
        problems.append("the pin's anchors do not meet")
    if not slides:
        problems.append("no SlideJoint on the L")
    else:
        s = slides[0]
        if s.min != 0 or abs(s.max - 25 * 1.5) > 1e-9:
            problems.append(f"slide joint from {s.min:g} to {s.max:g}, not 0 to 37.5")
        on_l = s.anchor_a if s.a is body else s.anchor_b
        if math.dist(on_l, SLIDE_ANCHOR) > 1e-6:
            problems.append(f"slide joint's anchor on the L at {tuple(on_l)}, not {SLIDE_ANCHOR}")
    return Result(not problems, "; ".join(problems) or "as the tutorial builds it",
                  "the tutorial's L, pin and slide joint",
                  "follow the tutorial's add_L (scaled by 1.5): the L body at the rotation "
                  "centre, a PinJoint (0,0)-(0,0) to a static body there, a SlideJoint from "
                  "(-150, 0) on the L to a second static body, 0 to 37.5 px; add everything "
                  "to the space.")


def _run(m: Student) -> tuple[float, float, float, float]:
    turn = [0.0]

    def watch(scene):
        turn[0] = max(turn[0], abs(scene.metrics()["angle_deg"]))
    scene = run_scene("pivoting_l", m, RUN, None, watch)
    mt = scene.metrics()
    return turn[0], mt["pin_error"], mt["slide_seen_max"], scene.slide.max


def turns(m: Student) -> Result:
    turned, pin_error, _, _ = _run(m)
    ok = turned > 2.0 and pin_error < 1.0
    return Result(ok, f"turned {turned:.1f} deg, pin error up to {fmt(pin_error)} px",
                  "> 2 deg, < 1 px",
                  "the L must be DYNAMIC (mass 10, moment 10000 * 1.5^2) and pinned at its own "
                  "position: PinJoint(body, center, (0, 0), (0, 0)) with the static centre body "
                  "at the L's position.")


def stops(m: Student) -> Result:
    _, _, seen, limit = _run(m)
    ok = limit - 1.0 <= seen <= limit + 2.0
    return Result(ok, f"slide distance up to {seen:.2f} px (max {limit:g})",
                  f"{limit - 1:g} to {limit + 2:g} px",
                  "the SlideJoint(body, limit_body, (-150, 0), (0, 0), 0, 37.5) stops the turn; "
                  "add it to the space with the L.")


EXERCISE = Exercise(
    name="pivoting_l",
    title="The pivoting L: pin and slide joints in pymunk",
    slide="Physics in Computer Animations and Games: pymunk tutorial, 'Joints. Just wait and "
          "the L will tip over' (add_L with a PinJoint and a SlideJoint)",
    functions=("add_L",),
    reference=reference,
    checks=(Check("the L", the_L), Check("turns on its pin", turns),
            Check("stops at the slide max", stops)),
)
