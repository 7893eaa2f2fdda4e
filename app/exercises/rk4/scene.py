"""The `rk4` exercise's scene: `python -m app --scene exercise:rk4`.

Two pendulums, one stepped by the student's rk4_step (left), one by their midpoint_step (right),
each over the lab's same method (orange rings).
"""

from __future__ import annotations

import math

import numpy as np

from app.exercises.base import array_of
from app.exercises.live import StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import Param, common


class _Pendulum:
    """A pendulum theta'' = -(g/L) sin theta stepped by impl's rk4_step or midpoint_step."""

    radius = 12.0
    ring = True
    LENGTH = 200.0

    def __init__(self, step, pivot: tuple[float, float], angle: float):
        self.stepper, self.pivot = step, np.array(pivot)
        self.y = np.array([math.radians(angle), 0.0])
        self.t = 0.0
        self.x = self.points()

    @staticmethod
    def f(t: float, y: np.ndarray) -> np.ndarray:
        return np.array([y[1], -900.0 / _Pendulum.LENGTH * math.sin(y[0])])

    def step(self, h: float) -> None:
        self.y = array_of(self.stepper(self.f, self.t, self.y, h), (2,),
                          getattr(self.stepper, "__name__", "the step"))
        self.t += h
        self.x = self.points()

    def energy(self) -> float:
        return 0.5 * self.y[1] ** 2 + 900.0 / self.LENGTH * (1 - math.cos(self.y[0]))

    def points(self) -> np.ndarray:
        """The bob, shape (1, 2)."""
        th = self.y[0]
        return (self.pivot + self.LENGTH * np.array([math.sin(th), math.cos(th)]))[None, :]


class _Pair:
    """Two pendulums stepped together: RK4 and midpoint."""

    radius = 12.0
    ring = True

    def __init__(self, impl, angle: float):
        self.parts = [_Pendulum(impl.rk4_step, (250.0, 300.0), angle),
                      _Pendulum(impl.midpoint_step, (700.0, 300.0), angle)]
        self.fixed = np.array([p.pivot for p in self.parts])
        self.links = [(0, 2), (1, 3)]         # bob to pivot

    def step(self, h: float) -> None:
        for p in self.parts:
            p.step(h)

    @property
    def x(self) -> np.ndarray:
        return self.points()

    def points(self) -> np.ndarray:
        return np.concatenate([p.points() for p in self.parts])


class Rk4Exercise(StudentCode, ParticleExercise):
    """Exercise `rk4`: a pendulum released at `angle`, stepped by YOUR rk4_step (left) and YOUR
    midpoint_step (right), each over the lab's (orange). Lower `hertz` to make the steps long:
    at hertz 2 (omega*h = 1.06) from 120 degrees, after 6 s the midpoint pendulum has 2.2 times
    its energy and RK4 92% of it (explicit midpoint gains energy at every step size, RK4 loses a
    little below its limit of 2.83). The slide (quoting Blender's manual) calls RK4 "energy
    conservative even if the acceleration is not constant": it is not; on a spring each RK4 step
    keeps 1 - (omega h)^6/72 + (omega h)^8/576 of the energy (0.983 at omega*h = 1.06).

    HUD: each one's angle error against the lab's same method, and its energy / the start's.
    """

    exercise = "rk4"
    title = "Exercise: RK4 and midpoint"
    params = (common("hertz", lo=1), Param("angle", 120.0, float, 1.0, 179.0,
              help="release angle, degrees from straight down"))

    def make(self, impl):
        return _Pair(impl, self.p["angle"])

    def measure(self) -> dict[str, float]:
        out = {}
        e0 = 900.0 / _Pendulum.LENGTH * (1 - math.cos(math.radians(self.p["angle"])))
        for name, mine, lab in zip(("rk4", "midpoint"), self.mine.parts, self.lab.parts):
            out[f"{name}_apart_rad"] = abs(float(mine.y[0] - lab.y[0]))
            out[f"{name}_energy_ratio"] = mine.energy() / e0
        return out

    def live_line(self, m: dict[str, float]) -> str:
        return (f"RK4: {m['rk4_apart_rad']:.2g} rad from the lab's, energy x "
                f"{m['rk4_energy_ratio']:.4f}; midpoint: {m['midpoint_apart_rad']:.2g} rad, "
                f"energy x {m['midpoint_energy_ratio']:.4f}")


SCENE = Rk4Exercise
