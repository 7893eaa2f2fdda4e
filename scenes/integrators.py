"""The integrator lab: one system, six integrators at once, and what accuracy costs.

What it shows: the same problem (a mass on a spring, a pendulum, or a two-body orbit) run side
by side by forward Euler, symplectic Euler, Verlet, midpoint (RK2), RK4 and implicit Euler, each in
its own colour, with the exact (or reference) solution as a white ghost. Top left: the systems.
Top right: the phase portrait (position against velocity; the exact solution is the white loop
and its white ring). Bottom left: the energy error over time, |E/E0 - 1| on a log axis (a
magnitude: a log axis has no room for signs; the table gives E/E0 itself). Bottom right: per
integrator the derivative evaluations and microseconds per step (measured while it runs), the
relative phase-space error against the exact solution, E/E0, and when it blew up.

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
An integrator that blows up (non-finite, or 1000x the problem's size away) is frozen and marked
"blew up at t = ..."; the others run on.

On the orbit, implicit Euler's numerical damping makes the bodies spiral into each other until a
close encounter (a singular 1/r^2 force that one linearised step cannot follow) flings them
apart: stable is not the same as accurate. At hertz 60 the encounter (t = 0.57 s, 19 px apart)
makes implicit Euler's linear system indefinite: its conjugate gradients break down at once (no
direction along which A is positive), the HUD says so, and that step takes a dense LU solve of
the same system instead, the true linearised step (E/E0 about -6: flung apart, unbound).

Controls: `problem` chooses the system; `hertz` sets dt = 1/hertz (1..1000); each integrator is an
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

from app.draw.palette import INTEGRATOR_COLORS
from app.draw.ring import Ring
from app.draw.text import TEXT, fit_size, font, px
from app.draw.view import View
from app.physics.integrators import INTEGRATORS, Integrator
from app.physics.particles import ParticleSystem
from app.physics.problems import PROBLEMS, Problem, make_problem
from app.scene import Effect, Param, Scene, Try

COLORS = INTEGRATOR_COLORS
SHORT = {"euler": "Euler", "symplectic_euler": "sympl.", "verlet": "Verlet",
         "midpoint": "midpt", "rk4": "RK4", "implicit_euler": "impl."}
GHOST = (235, 235, 235)
LABEL = (200, 200, 210)
BLOWUP_SIZE = 1000.0        # a run farther than this many problem scales away has blown up
SAMPLE_DT = 1.0 / 120.0     # plots keep at most 120 samples per simulated second
PLOT_SECONDS = 10.0         # the energy plot shows the last 10 s
TIMING_WINDOW = 61          # us/step is the median of this many recent steps

# Layout in world pixels (y down): x, y, w, h. The panels fill the content rectangle, which the
# window fits into the space its HUD and panel leave free. With large text (F2) the energy chart
# and the table each take the full width below the two upper panels, so their text can grow.
SYSTEM_RECT = (0, 0, 480, 338)
PHASE_RECT = (490, 0, 470, 338)
LAYOUTS = {   # text size -> (energy chart, table, content)
    "normal": ((0, 346, 380, 200), (390, 346, 570, 200), (0.0, 0.0, 960.0, 546.0)),
    "large": ((0, 346, 960, 180), (0, 534, 960, 250), (0.0, 0.0, 960.0, 784.0)),
}
SPRING_DRAW_SCALE = 0.8     # the spring column is drawn at 80 % so the bobs fit the panel
TABLE_SIZE = 24             # font sizes at zoom 1 (pygame's default font at 24: 16 px glyphs)
TITLE_SIZE = 20
SMALL_SIZE = 18


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
    category = "Particle systems"
    metrics_box = False          # the scene draws its own table of the metrics
    params = (
        Param("problem", "spring", str, choices=tuple(PROBLEMS),
              help="the system every integrator runs: mass on a spring, pendulum, two-body orbit"),
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
            "implicit Euler's damping makes the bodies spiral in: stable is not accurate"),
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
        self._texts: dict = {}                         # rendered labels, reused across frames
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

    def effect_costs(self) -> dict[str, float]:
        return {run.name: run.step_us / 1000.0 for run in self.live()}

    def hud_lines(self) -> list[str]:
        """Two short lines at most: omega*h against the limits, and the first blow-up (the
        table has the rest); a third once implicit Euler's CG stopped short of its tolerance."""
        limits = ("spring's limits: 2, RK4 2.83" if self.problem.name == "spring" else
                  "the spring's limits do not apply")
        lines = [f"omega*h = {self.omega_h:.3f} (h = dt/substeps); {limits}"]
        dead = sorted((r for r in self.runs if r.blew_up_t is not None), key=lambda r: r.blew_up_t)
        if dead:
            more = f"  (+{len(dead) - 1} more)" if len(dead) > 1 else ""
            lines.append(f"{SHORT[dead[0].name]} blew up at t = {dead[0].blew_up_t:.2f} s{more}")
        for run in self.runs:                   # a linear solve that stopped short, in words
            if run.cg_failure_t is not None:
                n = run.ps.cg_failures
                lines.append(f"implicit Euler, t = {run.cg_failure_t:.2f} s ({n} step"
                             f"{'s' if n > 1 else ''} so far): {run.ps.last_cg_failure.words()}")
        return lines

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
    def content_bounds(self) -> tuple[float, float, float, float]:
        return self.panels()[2]

    @staticmethod
    def panels() -> tuple:
        """(energy chart rect, table rect, content rect) for the text size in use."""
        return LAYOUTS["large" if TEXT.scale > 1 else "normal"]

    def draw(self, surface: pygame.Surface, view: View) -> None:
        self._refresh()
        self._draw_systems(surface, view)
        self._draw_table(surface, view)
        self._draw_phase(surface, view)
        self._draw_energy(surface, view)

    def _size(self, view: View, size: int) -> int:
        return max(10, int(round(view.len(size))))

    def _render(self, text: str, color, size: int) -> pygame.Surface:
        """font(size).render, remembered: most labels are the same every frame."""
        key = (text, color, size, TEXT.scale)
        label = self._texts.get(key)
        if label is None:
            if len(self._texts) > 1000:                  # numbers change: forget now and then
                self._texts.clear()
            label = self._texts[key] = font(size).render(text, True, color)
        return label

    def _screen_rect(self, view: View, rect) -> pygame.Rect:
        x, y = view.pt(rect[:2])
        return pygame.Rect(x, y, round(view.len(rect[2])), round(view.len(rect[3])))

    def _frame(self, surface, view, rect, title: str, bottom: bool = False) -> pygame.Rect:
        """A panel with its title at the top (or at the bottom), the title's size fitted to the
        panel's width (large text, small windows)."""
        r = self._screen_rect(view, rect)
        pygame.draw.rect(surface, (32, 35, 44), r)
        pygame.draw.rect(surface, (70, 74, 88), r, 1)
        label = self._render(title, LABEL, fit_size([title], self._size(view, TITLE_SIZE),
                                                    r.width - 12))
        surface.blit(label, (r.x + 6, r.bottom - label.get_height() - 4 if bottom else r.y + 4))
        return r

    def _text(self, surface, view, pos, text, color, size, right: bool = False,
              width: float | None = None, like: tuple[str, ...] = ()) -> None:
        """Text at a world point (its top-left, or its top-right if `right`); with `width`
        (world px) the text shrinks until it, and the texts `like` it, fit in that width."""
        px_size = self._size(view, size)
        if width is not None:
            px_size = fit_size([text, *like], px_size, int(view.len(width)))
        label = self._render(text, color, px_size)
        x, y = view.pt(pos)
        surface.blit(label, (x - label.get_width() if right else x, y))

    # left: the systems
    def _draw_systems(self, surface, view) -> None:
        clip = self._frame(surface, view, SYSTEM_RECT, f"{self.problem.title}  (white ring: exact)",
                           bottom=True)
        old_clip = surface.get_clip()
        surface.set_clip(clip.clip(old_clip))
        x_ref, _ = self.exact()
        kind = self.problem.name
        left, top = SYSTEM_RECT[0], SYSTEM_RECT[1]
        if kind == "spring":
            k = SPRING_DRAW_SCALE
            for i, name in enumerate(INTEGRATORS):
                origin = np.array([left + 40.0 + 80.0 * i, top + 22.0])
                run = next((r for r in self.runs if r.name == name), None)
                color = COLORS[name] if run else (110, 110, 110)
                self._text(surface, view, origin + (-36, 270), SHORT[name], color, TITLE_SIZE,
                           width=76, like=tuple(SHORT.values()))
                pygame.draw.line(surface, (150, 150, 160), view.pt(origin - (18, 0)), view.pt(origin + (18, 0)), 3)
                ghost = origin + k * self.problem.points(x_ref)[-1]
                pygame.draw.circle(surface, GHOST, view.pt(ghost), max(2, round(view.len(12))), 1)
                if run is None:
                    continue
                if run.blew_up_t is not None:
                    self._text(surface, view, origin + (-36, 60), "blew up", run.color, SMALL_SIZE,
                               width=74, like=("t=88.88s",))
                    self._text(surface, view, origin + (-36, 78), f"t={run.blew_up_t:.2f}s",
                               run.color, SMALL_SIZE, width=74, like=("t=88.88s",))
                    continue
                bob = np.clip(origin + k * self.problem.points(run.ps.x)[-1], -1e4, 1e4)
                self._spring(surface, view, origin, bob, run.color)
                pygame.draw.circle(surface, run.color, view.pt(bob), max(2, round(view.len(10))))
        else:
            origin = np.array([240.0, top + 30.0] if kind == "pendulum" else [270.0, top + 150.0])
            if kind == "orbit":
                ellipse = self.problem.exact_orbit_points()
                pygame.draw.lines(surface, (90, 90, 100), True, view.pts(origin + ellipse), 1)
            for run in self.live():
                pts = np.clip(origin + self.problem.points(run.ps.x), -1e4, 1e4)
                if kind == "pendulum":
                    pygame.draw.line(surface, run.color, view.pt(origin), view.pt(pts[0]), px(2))
                elif len(run.trail) > 1:
                    trail = np.clip(origin + run.trail.values(), -1e4, 1e4)
                    pygame.draw.lines(surface, run.color, False, view.pts(trail), px(2))
                for j, p in enumerate(pts):
                    radius = 10 if kind == "pendulum" else 6 + 3 * (j == 0)
                    pygame.draw.circle(surface, run.color, view.pt(p), max(2, round(view.len(radius))))
            for j, p in enumerate(origin + self.problem.points(x_ref)):
                radius = 13 if kind == "pendulum" else 8 + 3 * (j == 0)
                pygame.draw.circle(surface, GHOST, view.pt(p), max(2, round(view.len(radius))), 1)
            pygame.draw.circle(surface, (150, 150, 160), view.pt(origin), max(2, round(view.len(4))))
        surface.set_clip(old_clip)

    def _spring(self, surface, view, a, b, color) -> None:
        """A zig-zag from a to b (12 coils)."""
        s = np.linspace(0.0, 1.0, 26)
        d = b - a
        normal = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-9)
        wiggle = np.where(np.arange(26) % 2 == 0, -1.0, 1.0) * 8.0
        wiggle[[0, 1, -2, -1]] = 0.0
        pts = a + s[:, None] * d + wiggle[:, None] * normal
        pygame.draw.lines(surface, color, False, view.pts(pts), 1)

    # bottom: the table
    TABLE_TEMPLATES = ("9999.9", "-8.88e+88", "-8.888e+88")   # widest us/step, error, E/E0

    def _draw_table(self, surface, view) -> None:
        """One row per integrator; the columns are laid out from the measured widths of their
        text (and of the widest number each can show), and the text shrinks until the table fits
        its panel, so that no two columns ever run together."""
        r = self._screen_rect(view, self.panels()[1])
        pygame.draw.rect(surface, (32, 35, 44), r)
        pygame.draw.rect(surface, (70, 74, 88), r, 1)
        heads = ("integrator", "f evals", "us/step", "error", "E/E0")
        rows = []                                   # (colour, cells, note)
        for name, info in INTEGRATORS.items():
            run = next((r_ for r_ in self.runs if r_.name == name), None)
            evals = f"{info.evaluations}" if info.explicit else f"{info.evaluations} + CG"
            if run is None:
                rows.append(((110, 110, 110), (info.title, evals, "off", "", ""), ""))
                continue
            note = f"blew up at t = {run.blew_up_t:.2f} s" if run.blew_up_t is not None else ""
            rows.append((COLORS[name], (info.title, evals, f"{run.step_us:.1f}",
                                        f"{run.error:.2e}", f"{run.energy_ratio:.4g}"), note))
        columns = [[h, *(cells[i] for _, cells, _ in rows)] for i, h in enumerate(heads)]
        for column, widest in zip(columns[2:], self.TABLE_TEMPLATES):
            column.append(widest)
        notes = [note for _, _, note in rows if note] or [""]
        pad = max(4, r.height // 30)

        def layout(size: int) -> tuple[list[int], int, bool]:
            f = font(size)
            gap = f.size("  ")[0]
            widths = [max(f.size(t)[0] for t in column) for column in columns]
            chip = f.get_height()
            need_w = pad + chip + gap + sum(widths) + gap * len(widths) + max(
                f.size(n)[0] for n in notes)
            need_h = f.get_linesize() * (len(rows) + 1) + 2 * pad
            return widths, gap, need_w <= r.width and need_h <= r.height

        size = self._size(view, TABLE_SIZE)
        widths, gap, fits = layout(size)
        while not fits and size > 8:                # the smallest text that is still text
            size = max(8, int(size * 0.9))
            widths, gap, fits = layout(size)
        f = font(size)
        self.table_text = f.get_height()            # the text height it settled on (tests read it)
        chip = f.get_height()
        line = f.get_linesize()
        x = r.x + pad + chip + gap
        lefts = []
        for w in widths:
            lefts.append(x)
            x += w + gap
        note_x = x
        y = r.y + pad
        for i, head in enumerate(heads):            # numbers right-aligned, names left
            img = self._render(head, LABEL, size)
            surface.blit(img, (lefts[i] + (widths[i] - img.get_width() if i else 0), y))
        for color, cells, note in rows:
            y += line
            pygame.draw.rect(surface, color, (r.x + pad, y + chip // 6, chip * 2 // 3, chip * 2 // 3))
            for i, text in enumerate(cells):
                img = self._render(text, color, size)
                surface.blit(img, (lefts[i] + (widths[i] - img.get_width() if i else 0), y))
            if note:
                surface.blit(self._render(note, color, size), (note_x, y))

    # right: the two plots
    def _plot_map(self, rect, xlo, xhi, ylo, yhi):
        """data -> world point inside rect (margins for labels); far-off points are pulled in
        to +-1e4 px so pygame never sees a huge coordinate (the panel clips them anyway)."""
        m = TEXT.scale                          # room for the axis labels, as large as they
        x, y, w, h = rect[0] + 40 * m, rect[1] + 26 * m, rect[2] - 50 * m, rect[3] - 46 * m

        def to_world(px: np.ndarray, py: np.ndarray) -> np.ndarray:
            pts = np.stack((x + (px - xlo) / (xhi - xlo) * w, y + h - (py - ylo) / (yhi - ylo) * h), -1)
            return np.clip(pts, -1e4, 1e4)
        return to_world

    def _draw_phase(self, surface, view) -> None:
        qlab, plab = self.problem.phase_labels
        clip = self._frame(surface, view, PHASE_RECT, f"phase portrait: {plab} against {qlab}")
        c = self.curve
        qlo, qhi = c[:, 0].min(), c[:, 0].max()
        plo, phi = c[:, 1].min(), c[:, 1].max()
        qpad, ppad = 0.35 * (qhi - qlo), 0.35 * (phi - plo)
        to_world = self._plot_map(PHASE_RECT, qlo - qpad, qhi + qpad, plo - ppad, phi + ppad)
        old_clip = surface.get_clip()
        surface.set_clip(clip.inflate(-2, -24).move(0, 10).clip(old_clip))
        pygame.draw.lines(surface, GHOST, True, view.pts(to_world(c[:, 0], c[:, 1])), px(1))
        for run in self.runs:
            if len(run.phase) > 1:
                pts = run.phase.values()
                pygame.draw.lines(surface, run.color, False, view.pts(to_world(pts[:, 0], pts[:, 1])), 2)
            if len(run.phase):
                q, p = run.phase.last()
                pygame.draw.circle(surface, run.color, view.pt(to_world(q, p)), max(2, round(view.len(5))))
        q, p = self.exact_phase
        pygame.draw.circle(surface, GHOST, view.pt(to_world(q, p)), max(2, round(view.len(7))), 1)
        surface.set_clip(old_clip)

    def _draw_energy(self, surface, view) -> None:
        box = self.panels()[0]                 # the chart's rectangle for this text size
        clip = self._frame(surface, view, box, "energy error |E/E0 - 1| (log, last 10 s)")
        if len(self.sample_times) < 2:
            return
        t = self.sample_times.values()[:, 0]
        # one point per screen pixel of plot width is all a line can show: thin the samples out,
        # newest kept (the slice replaces a loop picking every stride-th sample)
        stride = max(1, len(t) // max(1, int(view.len(box[2] - 50))))
        keep = slice(len(t) - 1 - stride * ((len(t) - 1) // stride), None, stride)
        t = t[keep]
        # log10 |E/E0 - 1|: a magnitude (a log axis has no negative values), floored at 1e-16
        # (rounding); growth like forward Euler's is a straight line
        values = [np.log10(np.maximum(np.abs(r.energy.values()[keep, 0] - 1.0), 1e-16))
                  for r in self.runs]
        data = np.concatenate(values + [np.array([-3.0, 0.0])])
        lo, hi = max(float(data.min()), -16.0), min(float(data.max()), 6.0)
        pad = 0.08 * (hi - lo)
        lo, hi = lo - pad, hi + pad
        tlo, thi = max(t[-1] - PLOT_SECONDS, 0.0), max(t[-1], PLOT_SECONDS)
        to_world = self._plot_map(box, tlo, thi, lo, hi)
        old_clip = surface.get_clip()
        surface.set_clip(clip.inflate(-2, -24).move(0, 10).clip(old_clip))
        one = to_world(np.array([tlo, thi]), np.array([0.0, 0.0]))      # error 1 = 100%
        pygame.draw.line(surface, (120, 120, 125), view.pt(one[0]), view.pt(one[1]), 1)
        for run, e in zip(self.runs, values):
            n = min(len(e), len(t))
            if n > 1:
                clipped = np.clip(e[-n:], lo, hi)
                pygame.draw.lines(surface, run.color, False, view.pts(to_world(t[-n:], clipped)), 2)
        surface.set_clip(old_clip)
        for value in (lo, 0.0, hi):
            p = to_world(np.array(tlo), np.array(value))
            self._text(surface, view, (box[0] + 36 * TEXT.scale, float(p[1]) - 6),
                       f"{10 ** value:.0e}", (170, 170, 180), SMALL_SIZE - 2, right=True,
                       width=36 * TEXT.scale)
        self._text(surface, view, (box[0] + box[2] - 6,
                                   box[1] + box[3] - 18 * TEXT.scale),
                   f"t = {self.t:.1f} s", (170, 170, 180), SMALL_SIZE - 2, right=True)
