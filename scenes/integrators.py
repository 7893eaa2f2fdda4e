"""The integrator lab: one system, six integrators at once, and what accuracy costs.

What it shows: the same problem (a mass on a spring, a pendulum, a two-body orbit, or a ball
bouncing on a floor) run side
by side by forward Euler, symplectic Euler, Verlet, midpoint (RK2), RK4 and implicit Euler, each in
its own colour, with the exact (or reference) solution as a white ghost. At the top: the systems
and the phase portrait (position against velocity; the exact solution is the white loop and its
white ring). Below them: the energy error over time, |E/E0 - 1| on a log axis (a magnitude: a log
axis has no room for signs; the table gives E/E0 itself), and a table with, per integrator, the
derivative evaluations and microseconds per step (measured while it runs), the relative
phase-space error against the exact solution, E/E0, and when it blew up (beside the chart in a
wide window, under it in a narrow one; app/draw/integrator_lab.py lays them out).

The lecture idea: explicit methods are cheap per step but only conditionally stable, implicit
methods cost a linear solve per step and are stable at any step. Turn `hertz` down and watch
omega*h in the HUD (h = dt/substeps, the step each integrator takes): forward Euler spirals out
at every h, implicit Euler spirals in. Verlet and symplectic Euler keep their energy bounded until
omega*h passes 2 and then blow up; bounded, not constant: within each swing symplectic Euler's
energy rises and falls by a factor (1 + omega h/2)/(1 - omega h/2) (2.6 at omega*h 0.9, 19 at
1.8: at hertz 5 the spring reads E/E0 from 0.53 to 10), Verlet's (with the velocity this lab
estimates) by somewhat less (13x at 1.8). RK4 stays bounded until 2.83 but damps: every step
multiplies the energy by 1 - (omega h)^6/72 + (omega h)^8/576, negligible below ~0.5, 0.9934 at
omega*h 0.9 (a quarter of the energy left after 20 s at hertz 10) and 0.338 at 2.25 (hertz 4:
the bob simply stops). These limits are the spring's (a linear oscillator, omega fixed); on the
pendulum and the orbit omega changes along the motion: on the orbit (omega = its mean motion) RK4
blew up at omega*h = 0.785 (hertz 4).
Orders: the error after a fixed time falls like h^order; the benchmark measures 1, 1, 2, 2, 4, 1.
Verlet's position error per step is O(h^4) (the slides call it "4th order accurate", counting
that), but the T/h steps add up to an O(h^2) error at time T: the measured order 2.00
contradicts the slides as a global order.
What a contact does to accuracy (`problem=bounce`): a ball dropped onto a floor that pushes back
with a constant 30 m g while the ball is in it (app/physics/problems.py, Bounce). The force jumps
the instant the ball touches: the step that straddles the touch-down evaluates the wrong force
for part of h, an O(h) error whatever the method, and every order falls to about 1. Measured over
a sweep of h from 18 ms to 1.1 ms (the error averaged over 8 start times within a step):
forward Euler 0.89, symplectic Euler 0.92, Verlet 0.93, midpoint 1.03, RK4 0.87, implicit Euler
0.92 (BOUNCE_ORDERS; tests/test_integrators.py measures them again). RK4 pays four evaluations a
step for the order of forward Euler. Implicit Euler takes exactly symplectic Euler's steps here:
the floor's Jacobian is zero off its surface, so its linear solve sees gravity only.
An integrator that blows up (non-finite, or 1000x the problem's size away) is frozen and marked
"blew up at t = ..."; the others run on.

On the orbit, implicit Euler's numerical damping makes the bodies spiral into each other until a
close encounter (a singular 1/r^2 force that one linearised step cannot follow) flings them
apart: stable is not the same as accurate. At hertz 60 the encounter (t = 0.57 s, 19 px apart)
makes implicit Euler's linear system indefinite: its conjugate gradients break down at once (no
direction along which A is positive), the HUD says so, and that step takes a dense LU solve of
the same system instead, the true linearised step (E/E0 about -6: flung apart, unbound).

Controls: `problem` chooses the system (spring, pendulum, orbit, bounce); `hertz` sets dt = 1/hertz (1..1000); each integrator is an
effect you can switch off (only the ones shown are computed; switching restarts the race);
R restarts. From the command line: --set problem=orbit --set hertz=8 --set euler=off.
"""

from __future__ import annotations

import math
import statistics
import time
from collections import deque
from dataclasses import dataclass, field

import numpy as np
import pygame

from app.draw import hud
from app.draw.integrator_lab import SHORT
from app.draw.palette import INTEGRATOR_COLORS
from app.draw.ring import Ring
from app.draw.text import font, px
from app.draw.view import View
from app.physics.integrators import INTEGRATORS, Integrator
from app.physics.particles import ParticleSystem
from app.physics.problems import PROBLEMS, Problem, make_problem
from app.scene import Effect, Param, Scene, Try

COLORS = INTEGRATOR_COLORS
BLOWUP_SIZE = 1000.0        # a run farther than this many problem scales away has blown up
SAMPLE_DT = 1.0 / 120.0     # plots keep at most 120 samples per simulated second
PLOT_SECONDS = 10.0         # the energy plot shows the last 10 s
TIMING_WINDOW = 61          # us/step is the median of this many recent steps
# Each integrator's order on `bounce`, measured (problems.measured_orders: the slope over the
# problem's own sweep, omega*h 0.1 to 0.00625); tests/test_integrators.py measures them again.
BOUNCE_ORDERS = {"euler": 0.89, "symplectic_euler": 0.92, "verlet": 0.93, "midpoint": 1.03,
                 "rk4": 0.87, "implicit_euler": 0.92}


@dataclass
class Run:
    """One integrator's copy of the system, with its measurements."""

    name: str
    integrator: Integrator
    ps: ParticleSystem
    color: tuple[int, int, int]
    blew_up_t: float | None = None
    cg_failure_t: float | None = None     # implicit Euler: when its CG last stopped short
    error: float = 0.0
    energy_ratio: float = 1.0
    step_seconds: deque = field(default_factory=lambda: deque(maxlen=TIMING_WINDOW))
    energy: Ring = field(default_factory=lambda: Ring(int(PLOT_SECONDS / SAMPLE_DT)))
    phase: Ring = field(default_factory=lambda: Ring(400, 2))
    trail: Ring = field(default_factory=lambda: Ring(400, 2))

    @property
    def step_us(self) -> float:
        return statistics.median(self.step_seconds) * 1e6 if self.step_seconds else 0.0


class IntegratorsScene(Scene):
    __doc__ = __doc__
    name = "integrators"
    title = "Integrator lab: what accuracy costs"
    no_energy_words = "its energy chart shows each integrator's |E/E0 - 1| instead"
    category = "Particle systems"
    metrics_box = False          # the scene draws its own table of the metrics
    params = (
        Param("problem", "spring", str, choices=tuple(PROBLEMS),
              help="the system every integrator runs: mass on a spring, pendulum, two-body orbit, "
                   "ball bouncing on a floor (a contact: every order falls to ~1)"),
        Param("hertz", 60, int, 1, 1000, rebuild=False,
              help="steps per simulated second (dt = 1/hertz); the HUD shows omega*h"),
    )
    effects = tuple(Effect(name, True, f"{info.title}: {info.note}", rebuild=True)
                    for name, info in INTEGRATORS.items())
    tries = (
        Try("hertz 4: past Verlet", {"problem": "spring", "hertz": 4},
            "omega*h = 2.25: Verlet and symplectic Euler blow up (limit 2); RK4 stays bounded "
            "(limit 2.83), though it damps the energy away"),
        Try("hertz 3: past RK4", {"problem": "spring", "hertz": 3},
            "omega*h = 3: RK4 blows up as well; only implicit Euler stays bounded (it spirals in)"),
        Try("Orbit at hertz 60", {"problem": "orbit", "hertz": 60},
            "implicit Euler's damping draws the bodies together (E/E0 above 2 by t = 0.5 s) "
            "until, at their close pass at t = 0.57 s, its CG breaks down and the step flings "
            "them apart, unbound (E/E0 below 0): stable on a spring is not stable here"),
        Try("Bounce on a floor", {"problem": "bounce", "hertz": 240},
            "the floor's force jumps at touch-down: RK4's error is as large as Verlet's and "
            "falls only like h (measured order 0.87, 4 on the spring)"),
    )

    # ----- world ---------------------------------------------------------------------------------
    def build(self) -> None:
        self.problem: Problem = make_problem(self.p["problem"])
        self.runs = [Run(name, info, self.problem.make_system(), COLORS[name])
                     for name, info in INTEGRATORS.items() if name in self.on]
        ps0 = self.problem.make_system()
        self.e0 = self.problem.energy(ps0.x, ps0.v)
        self.t = 0.0                                   # simulated time, advanced per substep
        self.turn = 0                                  # which live run is timed first this step
        self.sample_times = Ring(int(PLOT_SECONDS / SAMPLE_DT))
        self.exact_phase = (0.0, 0.0)
        self.last_sample = -math.inf
        self.curve = self.problem.phase_curve()
        self._exact_cache: tuple[float, np.ndarray, np.ndarray] | None = None
        self._sample()

    def live(self) -> list[Run]:
        return [r for r in self.runs if r.blew_up_t is None]

    def exact(self) -> tuple[np.ndarray, np.ndarray]:
        """The exact (or reference) state now, computed once per simulated time."""
        if self._exact_cache is None or self._exact_cache[0] != self.t:
            self._exact_cache = (self.t, *self.problem.exact(self.t))
        return self._exact_cache[1], self._exact_cache[2]

    def step(self, h: float) -> None:
        # Timing: whichever run goes first after the window drew a frame finds the CPU caches
        # and branch predictors full of drawing code (and may pay for a garbage collection the
        # drawing set off): timed first every step, forward Euler looked 2-4x slower than it is.
        # So the order rotates every step and the median over TIMING_WINDOW steps drops those.
        runs = self.live()
        k = self.turn % len(runs) if runs else 0
        self.turn += 1
        for run in runs[k:] + runs[:k]:                # the runs are independent: order is free
            ps = run.ps
            before = ps.x, ps.v           # integrators make new arrays: these stay the last good state
            t0 = time.perf_counter()
            run.integrator.step(ps, h)
            run.step_seconds.append(time.perf_counter() - t0)
            if not run.integrator.explicit and not ps.solve.converged:
                run.cg_failure_t = self.t + h
            if not ps.is_finite() or np.abs(ps.x).max() > BLOWUP_SIZE * self.problem.scale:
                ps.x, ps.v = before       # freeze at the last finite state
                ps.x_prev = None
                run.error = self.problem.error(ps, self.t)
                run.blew_up_t = self.t + h
        self.t += h
        if self.t - self.last_sample >= SAMPLE_DT - 1e-12:
            self._sample()

    def _sample(self) -> None:
        """Record energy, phase point and trail of every live run (and the exact solution)."""
        self.last_sample = self.t
        self.sample_times.append(self.t)
        x, v = self.exact()
        self.exact_phase = self.problem.phase(x, v)
        for run in self.runs:
            if run.blew_up_t is None:
                run.energy_ratio = self.problem.energy(run.ps.x, run.ps.v) / self.e0
                run.phase.append(self.problem.phase(run.ps.x, run.ps.v))
                run.trail.append(self.problem.points(run.ps.x)[-1])
            run.energy.append(run.energy_ratio)

    # ----- contract ------------------------------------------------------------------------------
    @property
    def omega_h(self) -> float:
        return self.problem.omega * self.dt / self.p["substeps"]

    def _refresh(self) -> None:
        """Bring every live run's error and E/E0 up to now (for the metrics and the table)."""
        for run in self.live():
            run.error = self.problem.error(run.ps, self.t)
            run.energy_ratio = self.problem.energy(run.ps.x, run.ps.v) / self.e0

    def metrics(self) -> dict[str, float]:
        self._refresh()
        m: dict[str, float] = {"omega_dt": self.omega_h}
        for run in self.runs:
            m[f"{run.name}_error"] = float(run.error)
            m[f"{run.name}_step_us"] = float(run.step_us)
            m[f"{run.name}_energy_ratio"] = float(run.energy_ratio)
            m[f"{run.name}_blew_up_t"] = run.blew_up_t      # None while it has not
            if not run.integrator.explicit:          # how its linear solves ended
                solve = run.ps.solve
                m[f"{run.name}_cg_converged"] = solve.converged if solve.method else None
                m[f"{run.name}_cg_residual"] = solve.residual if solve.method else None
                m[f"{run.name}_cg_failures"] = run.ps.cg_failures
        return m

    def reference_error(self) -> tuple[str, str, float] | None:
        """The largest error against the exact solution among the integrators run."""
        self._refresh()
        if not self.runs:
            return None
        worst = max(self.runs, key=lambda r: r.error)
        return (f"worst error ({SHORT[worst.name]})", f"{worst.name}_error", float(worst.error))

    def effect_costs(self) -> dict[str, float]:
        return {run.name: run.step_us / 1000.0 for run in self.live()}

    def hud_lines(self) -> list[str]:
        """Two short lines at most: omega*h against the limits, and the first blow-up (the
        table has the rest); a third once implicit Euler's CG stopped short of its tolerance."""
        limits = ("spring's limits: 2, RK4 2.83" if self.problem.name == "spring" else
                  "the spring's limits do not apply")
        lines = [f"omega*h = {self.omega_h:.3f}; {limits}"]
        if self.problem.name == "bounce":       # omega*h says nothing about a contact
            lines = self.bounce_words()
        dead = sorted((r for r in self.runs if r.blew_up_t is not None), key=lambda r: r.blew_up_t)
        if dead:
            more = f"  (+{len(dead) - 1} more)" if len(dead) > 1 else ""
            lines.append(f"{SHORT[dead[0].name]} blew up at t = {dead[0].blew_up_t:.2f} s{more}")
        for run in self.runs:                   # a linear solve that stopped short, in words
            if run.cg_failure_t is not None:
                n = run.ps.cg_failures
                what, _, used = run.ps.last_cg_failure.words().partition("; ")
                short = what.partition(", residual")[0] + (
                    "; " + used.partition(" (residual")[0] if used else "")  # F4: residuals
                lines.append(f"implicit Euler, t = {run.cg_failure_t:.2f} s ({n} step"
                             f"{'s' if n > 1 else ''} so far): {short}")
        return lines

    def bounce_words(self) -> list[str]:
        """The bounce problem in two lines: how many steps a contact lasts, and the orders."""
        h = self.dt / self.p["substeps"]
        orders = ", ".join(f"{SHORT[n]} {o:.2f}" for n, o in BOUNCE_ORDERS.items())
        return [f"contact {self.problem.t_contact * 1000:.0f} ms = {self.problem.t_contact / h:.1f}"
                " steps; the floor's force jumps at touch-down",
                f"orders measured here: {orders} (smooth: 1, 1, 2, 2, 4, 1)"]

    def hud_details(self) -> list[str]:
        if self.problem.name == "bounce":
            return ["bounce: orders measured over a sweep of h from 18 ms to 1.1 ms (error "
                    "averaged over 8 start times within a step); on the smooth problems "
                    "1, 1, 2, 2, 4, 1. The step that straddles a touch-down sees the wrong "
                    "force for part of h: an O(h) error, whatever the method"]
        cg = [f"implicit Euler's linear solve: {r.ps.last_cg_failure.words()}"
              for r in self.runs if r.cg_failure_t is not None]      # with its residuals
        return ["h = dt/substeps: the step each integrator takes; omega: the problem's "
                "angular frequency (on the orbit its mean motion)"] + cg

    def state_arrays(self):
        """The live runs' states only: a run that blew up is frozen and reported, so the scene
        whose point is to show explicit Euler exploding never goes non-finite itself."""
        arrays = []
        for run in self.live():
            arrays += [run.ps.x, run.ps.v]
        return arrays

    def snapshot(self):
        return (self.t, self.time, self.steps,
                [(r.ps.copy_state(), r.blew_up_t, r.error, r.energy_ratio) for r in self.runs])

    def restore(self, snap) -> None:
        self.t, self.time, self.steps, runs = snap
        for run, (state, blew_up_t, error, ratio) in zip(self.runs, runs):
            run.ps.restore_state(state)
            run.blew_up_t, run.error, run.energy_ratio = blew_up_t, error, ratio
        self._exact_cache = None

    # ----- drawing -------------------------------------------------------------------------------
    content_fills = True         # laid out in screen pixels in whatever room the window gives

    def fit_to(self, size: tuple[float, float]) -> None:
        self._room = (max(float(size[0]), 1.0), max(float(size[1]), 1.0))

    def content_bounds(self) -> tuple[float, float, float, float]:
        w, h = getattr(self, "_room", (960.0, 600.0))
        return (0.0, 0.0, w, h)

    @property
    def table_text(self) -> int:
        """The table's glyph height in the last frame drawn (px)."""
        return self.drawing.table_text

    def formula_room(self) -> pygame.Rect | None:
        """Where the F4 page puts the six updates: over the phase portrait, beside the table
        (None before the first frame)."""
        rects = getattr(getattr(self, "drawing", None), "rects", None)
        return rects.phase if rects is not None else None

    def draw(self, surface: pygame.Surface, view: View) -> None:
        from app.draw.integrator_lab import LabDrawing
        self._refresh()
        if not hasattr(self, "drawing"):
            self.drawing = LabDrawing()
        x0, y0 = view.pt((0.0, 0.0))
        x1, y1 = view.pt(self.content_bounds()[2:])
        # the window's scrub bar (app/window/timeline_host.py) lies over the bottom of the
        # scene's room, its "7 s kept" label over it: the table ends above both (they hid
        # implicit Euler's row and note at 1024x768, F2)
        bar = max(8, px(10)) + px(6) + 4 + font(hud.HUD_SIZE * 3 // 4).get_height()
        self.drawing.draw(surface, pygame.Rect(x0, y0, x1 - x0, max(y1 - y0 - bar, 1)), self)
