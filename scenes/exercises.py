"""The exercises' scenes: the student's function drives the lecture's system, the lab's own
answer runs beside or behind it as an orange ghost, and the grader's numbers are live in the HUD.

    python -m app --scene exercise:verlet               runs exercises/verlet.py
    python -m app --scene exercise:mywork/verlet.py     runs a copy elsewhere (the file's name,
                                                        without .py, says which exercise it is)

Every exercise of app/exercises has one (`python -m app exercise list`):
  verlet            springs under gravity stepped by your verlet_step (drag: the `drag` param)
  constraints       a hanging cloth: your satisfy_rods on the left, the lab's on the right
  spring            a rope of damped springs: your spring_forces, symplectic Euler steps
  rk4               pendulums: your RK4 (left) and midpoint (right); turn `hertz` down to 2
                    (omega*h = 1.06) and the midpoint pendulum gains energy, RK4 loses a little
  solver_interface  a hanging chain (gravity, drag, springs) stepped by RK4 on your derivative
  newtons_cradle    the cradle scene built by your build_cradle, the lab's cradle as a ghost
  double_pendulum   the double pendulum scene built by your build_double_pendulum, beside the
                    equations-of-motion ghost
  pivoting_l        the pivoting-L scene with your add_L

The student's file is imported when the scene is built, so R (reset) picks up an edit: change,
save, press R. If their code raises, the scene raises app.scene.SceneError with their message,
file and line: the window pauses and shows it; a headless run prints it and exits 1. A file that
does not import is reported the same way at the first step (a sys.exit() in it too).
The scene runs the student's code in the lab's own process (the grader forks; a window cannot):
an endless loop freezes the window (Ctrl-C in the terminal stops it) and os._exit, or a value
that aborts pymunk, closes it. `python -m app exercise check` first is the safe order.
"""

from __future__ import annotations

import copy

import math
import sys
from contextlib import redirect_stdout
from pathlib import Path
from typing import Any, Iterable

import numpy as np
import pygame
import pymunk

from app.draw.hud import Line, text_box
from app.exercises import get_exercise
from app.exercises.base import BadAnswer, array_of
from app.exercises.grade import (CHECK_TIMEOUT, load_module, run_isolated, shown, starter_path,
                                 student_traceback)
from app.pymunk_scene import PymunkScene
from app.scene import Effect, Param, ParamError, Scene, SceneError, common
from scenes.double_pendulum import DoublePendulumScene
from scenes.newtons_cradle import RADIUS, SLOP, NewtonsCradleScene
from scenes.pivoting_l import PivotingLScene

PREFIX = "exercise:"
MINE = (86, 180, 233)        # the student's system
GHOST = (230, 159, 0)        # the lab's reference
LINK = (220, 220, 230)
FIXED = (150, 150, 160)     # anchors and pivots
ERROR = (240, 110, 90)


# what a student's code may raise into the scene: every exception, and sys.exit() (SystemExit),
# which would otherwise close the lab; Ctrl-C (KeyboardInterrupt) still stops it
STUDENT_ERRORS = (Exception, SystemExit)


class StudentCode:
    """Mixin for an exercise scene: imports the student's module at build, keeps the lab's
    reference answer at hand, and turns the student's exceptions into SceneError. While it holds
    an error, the scene's other hooks do nothing (there may be no world to draw)."""

    exercise = ""                  # the exercise's name (app/exercises)
    student_path = ""              # the file to import
    student: Any = None            # a module given directly (the grader), instead of the file
    error: str | None = None
    error_kind = ""                # the exception's class name, for the HUD
    draws_own_error = True         # draw() shows the traceback (headless screenshots too)
    ghost_note = "orange: the lab's"   # what the HUD says the reference looks like

    @classmethod
    def import_problem(cls, timeout: float = CHECK_TIMEOUT) -> str | None:
        """Why the student's file cannot be imported safely, or None: imported first in a child
        process (as the grader does), a file that calls os._exit, kills its own process or
        loops forever at import would take the lab down with it. An exception at import is
        not a problem here: the scene reports it with the student's file and line."""
        if cls.student is not None:
            return None
        report = run_isolated(get_exercise(cls.exercise), None, cls.student_path, timeout)
        if report.measured.startswith(("the process died", "still running")):
            return f"{cls.student_path}: importing it, {report.measured}: {report.error}"
        return None

    def build(self) -> None:
        self.error = None
        try:
            with redirect_stdout(sys.stderr):   # their prints: stdout carries --json
                self.impl = self.student if self.student is not None else load_module(
                    self.student_path)
                self.reference = get_exercise(self.exercise).reference()
                super().build()
        except STUDENT_ERRORS as e:     # any failure of the student's code
            self.fail(e)

    def fail(self, e: BaseException) -> SceneError:
        self.error_kind = type(e).__name__
        message = student_traceback(e, self.student_path)
        self.error = message if 'File "' in message else f"{self.student_path}: {message}"
        return SceneError(self.error)

    def advance(self) -> None:
        if self.error is not None:
            raise SceneError(self.error)
        try:
            with redirect_stdout(sys.stderr):
                super().advance()
        except STUDENT_ERRORS as e:
            raise self.fail(e) from None

    # ----- the other hooks, safe while an error is held ----------------------------------------
    def metrics(self) -> dict[str, float]:
        return {} if self.error else super().metrics()

    def content_bounds(self) -> tuple[float, float, float, float]:
        if self.error:                 # the world may not exist: the whole world area
            return Scene.content_bounds(self)
        return super().content_bounds()

    def effect_costs(self) -> dict[str, float]:
        return {} if self.error else super().effect_costs()

    def hud_lines(self) -> list[str]:
        if self.error:
            return [f"your code raised {self.error_kind} (below): fix it, save, press R"]
        return [f"yours: {self.student_path}; {self.ghost_note}"] + super().hud_lines()

    def draw(self, surface, view) -> None:
        if self.error:
            x, y, w, _ = self.content_bounds()     # where the layout keeps free of the HUD
            text_box(surface, [Line(t, ERROR) for t in self.error.splitlines()],
                     view.pt((x, y)), max_width=int(view.len(w)))
            return
        super().draw(surface, view)

    def handle_event(self, event) -> None:
        if not self.error:
            super().handle_event(event)

    def state_arrays(self) -> Iterable[np.ndarray]:
        return () if self.error else super().state_arrays()

    def snapshot(self) -> Any:
        return None if self.error else super().snapshot()


# ----- the NumPy exercises: two copies of one small system, yours and the lab's ------------------
class ParticleExercise(Scene):
    """Base of the NumPy exercises' scenes (each also mixes in StudentCode): `make(impl)` builds a
    system whose `step(h)` calls impl's functions; the student's and the lab's copies are stepped
    together and compared."""

    category = "Exercises"
    snapshot_skip = ("impl", "reference")
    live: tuple[str, ...] = ()      # params both copies read every step (attributes of theirs)

    def build(self) -> None:
        # the student's copy first: if their code raises while building, no step has run
        self.mine = self.make(self.impl)
        self.lab = self.make(self.reference)
        self._bounds = self.rest_bounds()

    def rest_bounds(self, seconds: float = 3.0) -> tuple[float, float, float, float]:
        """Where the lab's copy goes in its first seconds (run on a copy, at most 2000 steps),
        with a margin, for the layout: fixed once built, so the picture does not jump."""
        sim = copy.deepcopy(self.lab)
        for name in self.live:
            setattr(sim, name, self.p[name])
        h = self.dt / self.p["substeps"]
        n = min(2000, int(seconds / h))
        pts = [np.reshape(sim.fixed, (-1, 2)), np.reshape(self.mine.points(), (-1, 2))]
        for _ in range(n):
            sim.step(h)
            pts.append(np.reshape(sim.points(), (-1, 2)))
        pts = np.concatenate(pts)
        pts = pts[np.isfinite(pts).all(axis=1)]
        (x0, y0), (x1, y1) = pts.min(axis=0), pts.max(axis=0)
        pad = max(40.0, 0.12 * max(x1 - x0, y1 - y0))
        return (float(x0 - pad), float(y0 - pad), float(x1 - x0 + 2 * pad),
                float(y1 - y0 + 2 * pad))

    def content_bounds(self) -> tuple[float, float, float, float]:
        return getattr(self, "_bounds", None) or super().content_bounds()

    def make(self, impl):
        """The system, its step calling impl's functions."""
        raise NotImplementedError

    def step(self, h: float) -> None:
        for sim in (self.mine, self.lab):
            for name in self.live:
                setattr(sim, name, self.p[name])
            sim.step(h)

    def measure(self) -> dict[str, float]:
        """The grader's live numbers (the metrics)."""
        return {"apart_px": self.apart()}

    def live_line(self, m: dict[str, float]) -> str:
        """The HUD line that reads them."""
        return f"yours vs the lab's: {m['apart_px']:.3g} px apart"

    def metrics(self) -> dict[str, float]:
        return self.measure()

    def hud_lines(self) -> list[str]:
        return [self.live_line(self.metrics())]

    def state_arrays(self) -> Iterable[np.ndarray]:
        return (self.mine.x, self.lab.x)

    def apart(self) -> float:
        """Largest distance between a particle of yours and the lab's, px."""
        return float(np.abs(self.mine.x - self.lab.x).max())

    def draw(self, surface, view) -> None:
        """Links and fixed points (grey), your particles (filled), the lab's as orange rings a
        little larger, on top: where yours is right, each blue disc sits inside its ring."""
        for sim, color in ((self.lab, GHOST), (self.mine, LINK)):
            pts = view.pts(np.concatenate([sim.points(), sim.fixed]))
            for i, j in sim.links:
                pygame.draw.aaline(surface, color, pts[i], pts[j])
        for p in view.pts(self.mine.fixed):
            pygame.draw.circle(surface, FIXED, p, max(2.0, view.len(4)))
        r = max(2.0, view.len(self.mine.radius))
        for p in view.pts(self.mine.points()):
            pygame.draw.circle(surface, MINE, p, r)
        for p in view.pts(self.lab.points()):
            if self.lab.ring:
                pygame.draw.circle(surface, GHOST, p, r + max(2.0, view.len(3)), 2)
            else:                       # drawn beside yours, not around it: dots
                pygame.draw.circle(surface, GHOST, p, r)


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
        return {"apart_px": self.apart(),
                "force_sum": float(np.linalg.norm(f.sum(0)) / max(np.abs(f).max(), 1e-300))}

    def live_line(self, m: dict[str, float]) -> str:
        return (f"yours vs the lab's: {m['apart_px']:.3g} px apart; |sum of your forces| = "
                f"{m['force_sum']:.2g} of the largest")


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
        self.y = array_of(self.stepper(self.f, self.t, self.y, h), (2,), self.stepper.__name__)
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


class _Chain:
    """A chain of particles (gravity, drag, springs, the top one on a spring to an anchor),
    stepped by the lab's RK4 on impl.derivative."""

    radius = 8.0
    ring = True

    def __init__(self, impl, n: int = 6):
        from app.exercises.solver_interface import drag, gravity, springs
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


# ----- the pymunk exercises: the lab's scenes, built by the student's function ------------------
def _bodies(value: Any, count: int, what: str) -> list[pymunk.Body]:
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    if len(items) != count or not all(isinstance(b, pymunk.Body) for b in items):
        raise TypeError(f"{what} must return {count} pymunk.Body object(s), got {value!r}")
    return items


def _joint(space: pymunk.Space, body: pymunk.Body, kinds: tuple[type, ...], what: str):
    for joint in space.constraints:
        if isinstance(joint, kinds) and body in (joint.a, joint.b):
            return joint
    raise ValueError(f"{what}: no {' or '.join(k.__name__ for k in kinds)} on the body "
                     "(did you add it to the space?)")


class CradleExercise(StudentCode, NewtonsCradleScene):
    """Exercise `newtons_cradle`: the cradle scene, its balls and strings built by YOUR
    build_cradle; the lab's cradle swings behind it as orange rings (effect `reference`). The
    HUD gives the scene's
    verdict (k in, k out; middle drift; energy left), the grader's numbers.

    Mouse: drag a ball. Parameters: balls, lifted, damping, substeps, iterations, g.
    """

    exercise = "newtons_cradle"
    title = "Exercise: Newton's cradle"
    category = "Exercises"
    params = tuple(p for p in NewtonsCradleScene.params
                   if p.name not in ("gap", "angle", "elasticity"))   # yours decides these
    effects = NewtonsCradleScene.effects + (
        Effect("reference", True, "the lab's cradle, built by the lab's build_cradle, as orange "
               "rings", rebuild=True),)
    world_keys = NewtonsCradleScene.world_keys + ("ghost", "ghost_bodies")

    def add_balls(self, space: pymunk.Space) -> list[pymunk.Body]:
        n, k = self.p["balls"], self.p["lifted"]
        bodies = _bodies(self.impl.build_cradle(space, n, RADIUS, k), n, "build_cradle")
        xs = [b.position.x for b in bodies]
        if any(left >= right for left, right in zip(xs, xs[1:])):
            # the verdict counts the LAST k balls as the far end: another order miscounts it
            raise ValueError("build_cradle must return the balls in order along the row, left "
                             f"to right; their x: {', '.join(f'{x:.1f}' for x in xs)}")
        self.ghost, self.ghost_bodies = None, []
        if "reference" not in self.on:          # off: not built, not stepped
            return bodies
        self.ghost = pymunk.Space()
        self.ghost.collision_slop = SLOP
        self.ghost.iterations = self.p["iterations"]
        self.ghost.gravity = (0.0, self.gravity())
        self.ghost_bodies = self.reference.build_cradle(self.ghost, n, RADIUS, k)
        return bodies

    def step(self, h: float) -> None:
        super().step(h)
        if self.ghost is None:
            return
        self.ghost.damping = self.space.damping
        self.ghost.gravity = self.space.gravity
        self.ghost.step(h)

    def draw(self, surface, view) -> None:
        super().draw(surface, view)
        if not self.error:             # rings just outside the balls: yours sit inside them
            for body in self.ghost_bodies:
                pygame.draw.circle(surface, GHOST, view.pt(body.position),
                                   max(2.0, view.len(RADIUS + 3)), 2)


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
        from scenes.double_pendulum import PIVOT
        pair = _bodies(self.impl.build_double_pendulum(
            space, PIVOT, lengths, (self.p["mass1"], self.p["mass2"]), angles), 2,
            "build_double_pendulum")
        return pair[0], pair[1]

    def step(self, h: float) -> None:
        PymunkScene.step(self, h)       # the scene would set every joint's error_bias: keep yours


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
        body = _bodies(self.impl.add_L(space), 1, "add_L")[0]
        self.pin = _joint(space, body, (pymunk.PinJoint, pymunk.PivotJoint), "the pin")
        self.slide = _joint(space, body, (pymunk.SlideJoint,), "the slide joint")
        return body, list(body.shapes)


SCENES: dict[str, type[Scene]] = {cls.exercise: cls for cls in (
    VerletExercise, ConstraintsExercise, SpringExercise, Rk4Exercise, SolverInterfaceExercise,
    CradleExercise, DoublePendulumExercise, PivotingLExercise)}


def exercise_scene(spec: str, student: Any = None, path: str | None = None
                   ) -> type[Scene] | None:
    """The scene class for `exercise:SPEC` (SPEC: an exercise's name, or a path to a .py file
    whose name is one), bound to that file, to the file `path` if given, or to `student` (a
    module, or the reference's namespace: the grader) if given; None if SPEC names no
    exercise."""
    name = Path(spec).stem if spec.endswith(".py") else spec
    base = SCENES.get(name)
    if base is None:
        return None
    file = path or (spec if spec.endswith(".py") else shown(starter_path(name)))
    if student is not None:
        file = getattr(student, "__file__", "the lab's reference")
    return type(base.__name__, (base,), {"name": PREFIX + spec, "student_path": file,
                                         "student": student, "__doc__": base.__doc__})
