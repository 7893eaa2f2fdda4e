"""The `verlet` exercise's scene: `python -m app --scene exercise:verlet` (exercises/verlet.py).

Eight bobs on springs of rising stiffness, under gravity, stepped by the student's verlet_step
beside the lab's (app/physics/jakobsen.py), drawn as orange rings around theirs.
"""

from __future__ import annotations

import math

import numpy as np

from app.exercises.base import BadAnswer, array_of
from app.exercises.live import StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import Param


class _Springs:
    """Bobs on springs to fixed anchors, under gravity, stepped by impl.verlet_step."""

    radius = 9.0
    ring = True                 # the lab's copy is drawn as rings around yours

    def __init__(self, impl, drag: float):
        self.verlet_step, self.drag = impl.verlet_step, drag   # the function: snapshots copy
        n = 8                                                   # sims, and a module cannot be
        self.anchor = np.stack([120 + 100.0 * np.arange(n), np.full(n, 260.0)], axis=1)
        self.omega2 = (2 * math.pi * (0.5 + 0.2 * np.arange(n)))[:, None] ** 2
        self.x = self.anchor + (60.0, 0.0)
        self.x_prev = self.x.copy()
        self.h = 0.0
        self.fixed = self.anchor
        self.links = [(n + i, i) for i in range(n)]

    def accel(self) -> np.ndarray:
        return np.array([0.0, 900.0]) - self.omega2 * (self.x - self.anchor)

    def step(self, h: float) -> None:
        self.h = h
        out = self.verlet_step(self.x, self.x_prev, self.accel(), h, self.drag)
        if not isinstance(out, tuple) or len(out) != 2:
            raise BadAnswer(f"verlet_step returned {type(out).__name__}; expected (x_new, x)")
        self.x = array_of(out[0], self.anchor.shape, "verlet_step")
        self.x_prev = array_of(out[1], self.anchor.shape, "verlet_step")

    def energy(self) -> float:
        v = (self.x - self.x_prev) / self.h if self.h else np.zeros_like(self.x)
        d = self.x - self.anchor
        return float((0.5 * v * v + 0.5 * self.omega2 * d * d - np.array([0.0, 900.0]) * d).sum())

    def points(self) -> np.ndarray:
        return self.x


class VerletExercise(StudentCode, ParticleExercise):
    """Exercise `verlet`: eight bobs on springs of rising stiffness, under gravity, stepped by
    YOUR verlet_step (filled) beside the lab's (orange rings). With drag 0 the bobs swing for ever;
    raise drag and they settle. If yours is right the two overlap exactly.

    HUD: the largest distance between yours and the lab's, and your energy / the lab's.
    """

    exercise = "verlet"
    title = "Exercise: Verlet integration"
    params = (Param("drag", 0.0, float, 0.0, 0.2, help="the slide's 2 -> 1.99 is drag 0.01 "
                    "(fraction of the last step's travel lost per step)"),)

    live = ("drag",)

    def make(self, impl):
        return _Springs(impl, self.p["drag"])

    def measure(self) -> dict[str, float]:
        lab = self.lab.energy()
        return {"apart_px": self.apart(),
                "energy_vs_lab": self.mine.energy() / lab if lab else 1.0}

    def live_line(self, m: dict[str, float]) -> str:
        return (f"yours vs the lab's: {m['apart_px']:.3g} px apart; energy x "
                f"{m['energy_vs_lab']:.4f}")


SCENE = VerletExercise
