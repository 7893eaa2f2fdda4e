"""The `solver_interface` exercise's scene: `python -m app --scene exercise:solver_interface`.

A chain of particles integrated by the lab's RK4, which only ever calls the student's
derivative(state, masses, forces), beside the lab's particle system (orange rings).
"""

from __future__ import annotations

import numpy as np

from app.exercises.base import array_of
from app.exercises.live import StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import common


class _Chain:
    """A chain of particles (gravity, drag, springs, the top one on a spring to an anchor),
    stepped by the lab's RK4 on impl.derivative."""

    radius = 8.0
    ring = True

    def __init__(self, impl, n: int = 6):
        from app.exercises.solver_interface.grader import drag, gravity, springs
        from app.physics.integrators import rk4_step
        self.derivative, self.rk4 = impl.derivative, rk4_step
        self.n = n
        self.masses = np.linspace(1.0, 2.0, n)
        x = np.stack([480 + 40.0 * np.arange(n), np.full(n, 230.0)], axis=1)
        self.y = np.concatenate([x.ravel(), np.zeros(2 * n)])
        self.anchor = np.array([480.0, 230.0])
        rest = np.full(n - 1, 40.0)

        def hold(x, v, f):                      # the top particle on a stiff spring to the anchor
            f[0] -= 4000.0 * (x[0] - self.anchor)
        self.forces = [gravity(self.masses), drag(0.2),
                       springs(np.arange(n - 1), np.arange(1, n), 800.0, rest), hold]
        self.fixed = self.anchor[None, :]
        self.links = list(zip(range(n - 1), range(1, n))) + [(n, 0)]

    def step(self, h: float) -> None:
        def f(t, y):
            return array_of(self.derivative(y.copy(), self.masses, self.forces), y.shape,
                            "derivative")
        self.y = self.rk4(f, 0.0, self.y, h)

    @property
    def x(self) -> np.ndarray:
        return self.points()

    def points(self) -> np.ndarray:
        return self.y[:2 * self.n].reshape(self.n, 2)


class SolverInterfaceExercise(StudentCode, ParticleExercise):
    """Exercise `solver_interface`: a chain of six particles (gravity, drag, springs; the top one
    held near its anchor by a stiff spring) swinging down, integrated by the lab's RK4 that only
    ever calls YOUR derivative(state, masses, forces) (blue), beside the lab's particle system
    (orange).

    HUD: how far apart yours and the lab's are.
    """

    exercise = "solver_interface"
    title = "Exercise: the solver interface"
    params = (common("substeps", default=4),)

    def make(self, impl):
        return _Chain(impl)


SCENE = SolverInterfaceExercise
