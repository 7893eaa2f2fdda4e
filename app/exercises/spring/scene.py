"""The `spring` exercise's scene: `python -m app --scene exercise:spring`.

A rope of damped springs (neighbours and skip-one) held at its left end, falling and swinging
under gravity, its forces from the student's spring_forces beside the lab's (orange rings).
"""

from __future__ import annotations

import numpy as np

from app.exercises.base import array_of
from app.exercises.live import StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import Param, common


class _Rope:
    """A rope of damped springs hanging from particle 0 (held), symplectic Euler steps with
    impl.spring_forces + gravity."""

    radius = 6.0
    ring = True

    def __init__(self, impl, kd: float, n: int = 12, spacing: float = 30.0):
        self.spring_forces, self.kd = impl.spring_forces, kd
        self.x = np.stack([300 + spacing * np.arange(n), np.full(n, 240.0)], axis=1)
        self.v = np.zeros_like(self.x)
        self.a = np.concatenate([np.arange(n - 1), np.arange(n - 2)])
        self.b = np.concatenate([np.arange(1, n), np.arange(2, n)])
        self.rest = np.linalg.norm(self.x[self.a] - self.x[self.b], axis=1)
        self.links = list(zip(range(n - 1), range(1, n)))
        self.free = np.ones((n, 1))
        self.free[0] = 0.0
        self.f = np.zeros_like(self.x)
        self.fixed = np.empty((0, 2))

    def step(self, h: float) -> None:
        self.f = array_of(self.spring_forces(self.x, self.v, self.a, self.b, 2000.0, self.kd,
                                             self.rest), self.x.shape, "spring_forces")
        self.v = (self.v + h * (self.f + np.array([0.0, 900.0]))) * self.free
        self.x = self.x + h * self.v

    def points(self) -> np.ndarray:
        return self.x


class SpringExercise(StudentCode, ParticleExercise):
    """Exercise `spring`: a rope of damped springs (neighbours and skip-one) held at its left end,
    falling and swinging under gravity. YOUR spring_forces (blue) beside the lab's (orange).

    HUD: how far apart the two ropes are, and the sum of your spring forces (Newton's third law
    makes it zero).
    """

    exercise = "spring"
    title = "Exercise: damped springs"
    params = (common("substeps", default=8), Param("kd", 2.0, float, 0.0, 20.0,
              help="spring damping kd", rebuild=False))

    live = ("kd",)

    def make(self, impl):
        return _Rope(impl, self.p["kd"])

    def measure(self) -> dict[str, float]:
        f = self.mine.f
        largest = float(np.abs(f).max())
        return {"apart_px": self.apart(),
                "force_sum": float(np.linalg.norm(f.sum(0))) / largest if largest > 0 else 0.0}

    def live_line(self, m: dict[str, float]) -> str:
        return (f"yours vs the lab's: {m['apart_px']:.3g} px apart; |sum of your forces| = "
                f"{m['force_sum']:.2g} of the largest")


SCENE = SpringExercise
