"""The `pivoting_l` exercise's scene: `python -m app --scene exercise:pivoting_l`.

The lecture's pivoting-L scene (scenes/pivoting_l.py), its L, pin and slide joint built by the
student's add_L; balls keep landing on it.
"""

from __future__ import annotations

import pymunk

from app.exercises.live import StudentCode
from app.exercises.newtons_cradle.scene import bodies_of
from scenes.pivoting_l import PivotingLScene


def joint_of(space: pymunk.Space, body: pymunk.Body, kinds: tuple[type, ...], what: str):
    for joint in space.constraints:
        if isinstance(joint, kinds) and body in (joint.a, joint.b):
            return joint
    raise ValueError(f"{what}: no {' or '.join(k.__name__ for k in kinds)} on the body "
                     "(did you add it to the space?)")


class PivotingLExercise(StudentCode, PivotingLScene):
    """Exercise `pivoting_l`: the pivoting-L scene, its L, pin and slide joint built by YOUR
    add_L; balls land on it until it tips and the slide joint stops it. The HUD shows the angle,
    the slide distance against its range and the largest pin error.
    """

    exercise = "pivoting_l"
    title = "Exercise: pivoting L"
    category = "Exercises"
    ghost_note = "graded on the pin error and the slide range below"
    params = tuple(p for p in PivotingLScene.params
                   if p.name not in ("L_mass", "pivot", "slide_max"))   # yours decides these

    def add_L(self, space: pymunk.Space) -> tuple[pymunk.Body, list[pymunk.Segment]]:
        body = bodies_of(self.impl.add_L(space), 1, "add_L")[0]
        self.pin = joint_of(space, body, (pymunk.PinJoint, pymunk.PivotJoint), "the pin")
        self.slide = joint_of(space, body, (pymunk.SlideJoint,), "the slide joint")
        return body, list(body.shapes)


SCENE = PivotingLExercise
