"""Grader of exercises/pivoting_l.py: the pymunk tutorial's add_L with its pin and slide joints.

Reference: the pivoting-L scene's own add_L (scenes/pivoting_l.py, at its default settings). The
student's add_L builds `python -m app --scene exercise:pivoting_l` (balls keep landing on the L).
The measures send back the L's geometry and what the scene measured; the judges decide:
  the L            one dynamic body at the rotation centre L_ORIGIN, of mass MASS and moment
                   MOMENT, with the two segments LONG and LIP (long arm to the right, lip up) of
                   radius RADIUS; a pin whose anchors meet there; a slide joint from 0 to
                   SLIDE_MAX anchored at SLIDE_ANCHOR on the L and, at its other end, at
                   ORIGIN + SLIDE_ANCHOR on a static body (the pin's other body static too)
  turns on its pin 10 s of balls: the L turns (more than 2 degrees) and its pin error (the
                   scene's largest `pin_error`) stays under 1 px
  stops at max     the same run: the slide joint's largest distance reaches its max (within 1 px)
                   and goes no further than 2 px past it
No random cases here: add_L(space) takes nothing but the space (the tutorial's numbers are fixed
in the starter), so the whole space of its inputs is the one the checks use.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import BadAnswer, Check, Exercise, Raw, Result, Student, fmt
from app.exercises.pymunk_run import run_scene

RUN = 10.0
S = 1.5
ORIGIN = (400.0, 440.0)
LONG = ((-150 * S, 0.0), (255 * S, 0.0))
LIP = ((-150 * S, 0.0), (-150 * S, -50 * S))
RADIUS, MASS, MOMENT = 5 * S, 10.0, 10000 * S * S
SLIDE_ANCHOR, SLIDE_MAX = (-100 * S, 0.0), 25 * S


def reference() -> SimpleNamespace:
    from scenes.pivoting_l import PivotingLScene

    def add_L(space):
        # the scene's own builder, with the scene's default settings
        defaults = SimpleNamespace(p=PivotingLScene.resolve({})[0])
        return PivotingLScene.add_L(defaults, space)[0]
    return SimpleNamespace(add_L=add_L)


def measure_L(m: Student) -> dict:
    import pymunk
    space = pymunk.Space()
    body = m.add_L(space)
    if not isinstance(body, pymunk.Body):
        raise BadAnswer(f"add_L returned {body!r:.200}; expected the L's pymunk.Body")
    joints = [j for j in space.constraints if body in (j.a, j.b)]
    pins = [j for j in joints if isinstance(j, (pymunk.PinJoint, pymunk.PivotJoint))]
    slides = [j for j in joints if isinstance(j, pymunk.SlideJoint)]
    pin_gap = (math.dist(pins[0].a.local_to_world(pins[0].anchor_a),
                         pins[0].b.local_to_world(pins[0].anchor_b)) if pins else None)
    slide = None
    if slides:
        s = slides[0]
        other, other_anchor = (s.b, s.anchor_b) if s.a is body else (s.a, s.anchor_a)
        slide = {"min": s.min, "max": s.max,
                 "anchor": tuple(s.anchor_a if s.a is body else s.anchor_b),
                 "limit_static": other.body_type == pymunk.Body.STATIC,
                 "limit_at": tuple(other.local_to_world(other_anchor))}
    pin_static = None
    if pins:
        other = pins[0].b if pins[0].a is body else pins[0].a
        pin_static = other.body_type == pymunk.Body.STATIC
    return {"dynamic": body.body_type == pymunk.Body.DYNAMIC, "position": tuple(body.position),
            "mass": body.mass, "moment": body.moment,
            "segments": [[*s.a, *s.b, s.radius] for s in body.shapes
                         if isinstance(s, pymunk.Segment)],
            "pin_gap": pin_gap, "pin_static": pin_static, "slide": slide}


def _same_segment(seg: np.ndarray, want: tuple) -> bool:
    a, b = np.array(want[0]), np.array(want[1])
    p, q = seg[:2], seg[2:4]
    return bool(min(np.abs(p - a).max() + np.abs(q - b).max(),
                    np.abs(p - b).max() + np.abs(q - a).max()) < 1e-6)


def judge_L(raw: Raw) -> Result:
    problems = []
    if not raw.flag("dynamic"):
        problems.append("the L is not a dynamic body")
    pos = raw.array("position", (2,))
    if math.dist(pos, ORIGIN) > 1e-6:
        problems.append(f"the L is at {tuple(np.round(pos, 3))}, not {ORIGIN}")
    mass, moment = raw.number("mass"), raw.number("moment")
    if not abs(mass - MASS) < 1e-9:
        problems.append(f"mass {mass:g}, not {MASS:g}")
    if not abs(moment - MOMENT) < 1e-6:
        problems.append(f"moment {moment:g}, not {MOMENT:g}")
    segs = raw.array("segments", (None, 5))
    if len(segs) != 2:
        problems.append(f"{len(segs)} segments, not 2")
    else:
        long_ok = any(_same_segment(s, LONG) for s in segs)
        lip_ok = any(_same_segment(s, LIP) for s in segs)
        mirrored = any(_same_segment(s, ((-x0, y0), (-x1, y1))) for s in segs
                       for (x0, y0), (x1, y1) in [LONG])
        if not long_ok:
            problems.append("the long arm points LEFT (mirrored): LONG runs from x = -225 to "
                            "+382.5" if mirrored else "the long arm is not LONG")
        if not lip_ok:
            problems.append("the short arm is not LIP (at x = -225, pointing up: -y)")
        if not all(abs(r - RADIUS) < 1e-9 for r in segs[:, 4]):
            problems.append(f"segment radius {', '.join(f'{r:g}' for r in segs[:, 4])}, not "
                            f"{RADIUS:g}")
    gap = raw.optional("pin_gap")
    if gap is None:
        problems.append("no PinJoint on the L")
    elif not gap < 1e-6:
        problems.append("the pin's anchors do not meet")
    elif raw.values.get("pin_static") is False:
        problems.append("the pin holds the L to a body that is not STATIC (the rotation centre "
                        "body: pymunk.Body(body_type=pymunk.Body.STATIC))")
    slide = raw.values.get("slide")
    if slide is None:
        problems.append("no SlideJoint on the L")
    else:
        s = Raw(slide)
        lo, hi = s.number("min"), s.number("max")
        if lo != 0 or not abs(hi - SLIDE_MAX) < 1e-9:
            problems.append(f"slide joint from {lo:g} to {hi:g}, not 0 to {SLIDE_MAX:g}")
        anchor = s.array("anchor", (2,))
        if math.dist(anchor, SLIDE_ANCHOR) > 1e-6:
            problems.append(f"slide joint's anchor on the L at ({anchor[0]:g}, {anchor[1]:g}), "
                            f"not ({SLIDE_ANCHOR[0]:g}, {SLIDE_ANCHOR[1]:g})")
        if not s.flag("limit_static"):
            problems.append("the slide joint's limit body is not STATIC (rotation_limit_body = "
                            "pymunk.Body(body_type=pymunk.Body.STATIC)): it falls away")
        limit_at = s.array("limit_at", (2,))
        want = (ORIGIN[0] + SLIDE_ANCHOR[0], ORIGIN[1] + SLIDE_ANCHOR[1])
        if math.dist(limit_at, want) > 1e-6:
            problems.append(f"the slide joint's other end is at ({limit_at[0]:g}, "
                            f"{limit_at[1]:g}), not ORIGIN + SLIDE_ANCHOR = ({want[0]:g}, "
                            f"{want[1]:g}) (the limit body's position)")
    return Result(not problems, "; ".join(problems) or "as the tutorial builds it",
                  "the tutorial's L, pin and slide joint",
                  "follow the tutorial's add_L (scaled by 1.5): the L body (MASS, MOMENT) at the "
                  "rotation centre, segments LONG and LIP of radius RADIUS, a PinJoint (0,0)-(0,0)"
                  " to a static body there, a SlideJoint from SLIDE_ANCHOR on the L to a second "
                  "static body, 0 to SLIDE_MAX; add everything to the space.")


_RUNS: dict[int, dict] = {}     # one 10 s run serves both checks (in one child)


def measure_run(m: Student) -> dict:
    if id(m) in _RUNS:
        return _RUNS[id(m)]
    turn = [0.0]

    def watch(scene):
        a = abs(scene.metrics()["angle_deg"])
        if turn[0] == turn[0] and not a <= turn[0]:       # the largest, and NaN sticks
            turn[0] = a
    scene = run_scene("pivoting_l", m, RUN, None, watch)
    mt = scene.metrics()
    _RUNS[id(m)] = {"turned": turn[0], "pin_error": mt["pin_error"],
                    "seen": mt["slide_seen_max"], "limit": scene.slide.max}
    return _RUNS[id(m)]


def judge_turns(raw: Raw) -> Result:
    turned, pin_error = raw.number("turned"), raw.number("pin_error")
    ok = turned > 2.0 and pin_error < 1.0
    return Result(bool(ok), f"turned {turned:.1f} deg, pin error up to {fmt(pin_error)} px",
                  "> 2 deg, < 1 px",
                  "the L must be DYNAMIC (mass 10, moment 10000 * 1.5^2) and pinned at its own "
                  "position: PinJoint(body, center, (0, 0), (0, 0)) with the static centre body "
                  "at the L's position.")


def judge_stops(raw: Raw) -> Result:
    seen, limit = raw.number("seen"), raw.number("limit")
    ok = limit - 1.0 <= seen <= limit + 2.0
    return Result(bool(ok), f"slide distance up to {seen:.2f} px (max {limit:g})",
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
    checks=(Check("the L", measure_L, judge_L), Check("turns on its pin", measure_run, judge_turns),
            Check("stops at the slide max", measure_run, judge_stops)),
)
