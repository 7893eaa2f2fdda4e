"""The `constraints` exercise's scene: `python -m app --scene exercise:constraints`.

A cloth of rods hanging from its top row in a sideways breeze: the student's satisfy_rods on the
left, the lab's (app/physics/jakobsen.py) on the right, both stepped by the lab's Verlet.
"""

from __future__ import annotations

import math

import numpy as np

from app.exercises.base import array_of
from app.exercises.live import StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import Param, ParamError


class _Cloth:
    """A hanging cloth, top row pinned: the lab's Verlet step, then impl.satisfy_rods."""

    radius = 2.0
    ring = False                # the lab's cloth hangs beside yours

    # 8 x 8 (112 rods): the slide's plain Python loop over the rods, as the starter allows, keeps
    # up with 60 Hz at 10 sweeps; at 12 x 12 it took 22 ms a step and the window fell to 8 fps
    def __init__(self, impl, origin: tuple[float, float], iterations: int, rows: int = 8,
                 spacing: float = 34.0):
        from app.physics.jakobsen import verlet_step
        self.verlet, self.satisfy_rods, self.iterations = verlet_step, impl.satisfy_rods, iterations
        r, c = np.mgrid[0:rows, 0:rows]
        idx = r * rows + c
        self.a = np.concatenate([idx[:, :-1].ravel(), idx[:-1, :].ravel()])
        self.b = np.concatenate([idx[:, 1:].ravel(), idx[1:, :].ravel()])
        self.links = list(zip(self.a.tolist(), self.b.tolist()))
        self.x = np.stack([origin[0] + c.ravel() * spacing, origin[1] + r.ravel() * spacing],
                          axis=1).astype(float)
        self.x0 = self.x.copy()
        self.x_prev = self.x.copy()
        self.rest = np.full(len(self.a), spacing)
        self.w = np.ones(len(self.x))
        self.w[:rows] = 0.0
        self.acc = np.where(self.w[:, None] > 0, np.array([0.0, 900.0]), 0.0)
        self.wind_t = 0.0
        self.fixed = np.empty((0, 2))

    def step(self, h: float) -> None:
        self.wind_t += h       # a gentle sideways gust, so the cloth moves
        acc = self.acc + self.w[:, None] * np.array([300.0 * math.sin(1.3 * self.wind_t), 0.0])
        self.x, self.x_prev = self.verlet(self.x, self.x_prev, acc, h, 0.01)
        out = self.satisfy_rods(self.x.copy(), self.a, self.b, self.rest, self.w,
                                self.iterations)
        self.x = array_of(out, self.x.shape, "satisfy_rods")

    def stretch(self) -> float:
        return float(np.abs(np.linalg.norm(self.x[self.b] - self.x[self.a], axis=1)
                            / self.rest - 1).mean())

    def pinned_drift(self) -> float:
        pinned = self.w == 0
        return float(np.abs(self.x[pinned] - self.x0[pinned]).max())

    def points(self) -> np.ndarray:
        return self.x


class ConstraintsExercise(StudentCode, ParticleExercise):
    """Exercise `constraints`: a cloth of rods hanging from its top row in a sideways breeze.
    Left: YOUR satisfy_rods (blue); right: the lab's (orange). Both use the lab's Verlet step.
    Lower `iterations` and both stretch; more sweeps, stiffer cloth.

    HUD: the mean stretch |length/rest - 1| of each, and how far your pinned particles moved.
    """

    exercise = "constraints"
    title = "Exercise: Jakobsen's rods"
    params = (Param("iterations", 10, int, 1, 50, help="relaxation sweeps per step",
                    rebuild=False),)

    live = ("iterations",)
    # one sweep in one substep costs ~0.35 ms for the two cloths (the lab's answer, measured
    # with other work running): 50 x 50 took ~0.9 s a step; refused over ~0.35 s
    step_budget = 1000

    @classmethod
    def check_combination(cls, values) -> None:
        work = values["iterations"] * values["substeps"]
        if work > cls.step_budget:
            raise ParamError(f"iterations x substeps = {values['iterations']} x "
                             f"{values['substeps']} = {work:,} is too large: a step would take "
                             f"over a third of a second (budget {cls.step_budget:,}); lower "
                             "iterations or substeps")

    def make(self, impl):
        mine = impl is self.impl
        return _Cloth(impl, (170.0 if mine else 570.0, 230.0), self.p["iterations"])

    def measure(self) -> dict[str, float]:
        return {"mean_stretch": self.mine.stretch(), "mean_stretch_lab": self.lab.stretch(),
                "pinned_drift": self.mine.pinned_drift()}

    def live_line(self, m: dict[str, float]) -> str:
        return (f"mean stretch: yours {100 * m['mean_stretch']:.3f}%, the lab's "
                f"{100 * m['mean_stretch_lab']:.3f}%; pinned moved {m['pinned_drift']:.3g} px")


SCENE = ConstraintsExercise
