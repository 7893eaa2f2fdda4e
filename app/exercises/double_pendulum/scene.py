"""The `double_pendulum` exercise's scene: `python -m app --scene exercise:double_pendulum`.

The lecture's double pendulum scene (scenes/double_pendulum.py), its bobs and rods built by the
student's build_double_pendulum, beside the ghost integrated from the equations of motion.
"""

from __future__ import annotations

import pymunk

from app.exercises.live import StudentCode
from app.exercises.newtons_cradle.scene import bodies_of
from app.pymunk_scene import PymunkScene
from scenes.double_pendulum import PIVOT, DoublePendulumScene


class DoublePendulumExercise(StudentCode, DoublePendulumScene):
    """Exercise `double_pendulum`: the double pendulum scene, its bobs and rods built by YOUR
    build_double_pendulum, beside the ghost integrated from the equations of motion (orange).
    Released low (angle1 = angle2 = 10) the two must stay together; the HUD shows the energy
    drift and when they part. Your joints are used as you built them (their error_bias too).
    """

    exercise = "double_pendulum"
    title = "Exercise: double pendulum"
    category = "Exercises"
    ghost_note = "orange: the equations of motion (the lab's RK4)"
    params = tuple(p for p in DoublePendulumScene.params if p.name != "error_bias")

    def add_bobs(self, space, lengths, angles) -> tuple[pymunk.Body, pymunk.Body]:
        pair = bodies_of(self.impl.build_double_pendulum(
            space, PIVOT, lengths, (self.p["mass1"], self.p["mass2"]), angles), 2,
            "build_double_pendulum")
        return pair[0], pair[1]

    def apply_settings(self) -> None:
        PymunkScene.apply_settings(self)   # the scene would set every joint's error_bias: keep yours


SCENE = DoublePendulumExercise
