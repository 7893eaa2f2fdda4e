"""What the mass-spring cloth says: its HUD lines, the second page (F4), the blow-up hint, the
real-time advice and its energy bars (E). The scene (scenes/mass_spring_cloth.py) holds the cloth and its state; this
mixin turns that state into the sentences a class reads, so a reader looking for a sentence on
screen finds it here, and one looking for the physics finds it there.
"""

from __future__ import annotations

import math

from app.loop import FPS_CAP, FixedStepClock
from app.physics.blender_cloth import PX_PER_M
from app.physics.integrators import INTEGRATORS
from app.physics.blender_cloth import PX_PER_M
from app.physics.mass_spring_cost import frame_cost
from app.physics.mass_spring_stability import ESTIMATE_EVERY, ESTIMATE_EVERY_IMPLICIT, marginal

SOLVER_WORDS = {"cg": "CG", "direct": "direct LU"}
ENERGY_GAIN_SHOWN = 0.01     # J above the start before the HUD says the step added energy (an
                             # exact solve overshoots by ~0.004 J at the sliders' stiffest corner)
EXACT_TOLERANCE = 1e-10      # the cg_tolerance slider's least: the solve is exact (LU takes over)
JOULE = PX_PER_M ** 2        # the energy's JSON unit per J (as scenes/mass_spring_cloth.py)
BAND_WORDS = {
    "stable": "stable",
    "marginal": "MARGINAL: safe only below {m:g}x of it, the limit falls as the cloth deforms",
    "past the limit": "PAST THE LIMIT: its top mode grows (a shiver, or a blow-up)",
}


class MassSpringWords:
    """The mass-spring cloth scene's words (a mixin: it reads the scene's cloth, p, watch,
    metrics() and shown())."""

    def blowup_hint(self) -> str:
        """The explicit limit in so many words: where the step was against the limit (at rest
        and as the cloth moved), and a step that is inside the stable band of the lowest limit
        seen, never one at or below the step that just failed."""
        name, p = self.p["integrator"], self.p
        pred = self.limit(name) if INTEGRATORS[name].explicit else None
        if pred is None or pred <= 0 or not math.isfinite(pred):
            return ""
        h = self.dt / p["substeps"]
        rest = self.watch.rest(name) or pred
        now = p["hertz"] * p["substeps"]
        m = marginal(name)
        need = max(math.ceil(1.0 / (m * pred)), now + 1)   # steps per second in the stable band
        most = int(self.param("hertz").hi * self.param("substeps").hi)
        way = (f"Raise hertz x substeps from {now:,} to at least {need:,} (the stable band, "
               f"below {m:g}x), or take implicit_euler." if need <= most else
               f"That takes {need:,} steps per second, more than hertz x substeps reach "
               f"({most:,}): take implicit_euler.")
        title = INTEGRATORS[name].title
        where = (f"{_times(h / pred)}x {title}'s predicted limit ({pred * 1e3:.3g} ms"
                 + (f"; {rest * 1e3:.3g} ms at rest, lower as the cloth deformed)"
                    if rest > pred * 1.0005 else ")"))
        if h <= pred:
            where += (f": inside the limit but not below {m:g}x of it, where a "
                      f"deforming cloth can pass it")
        return f"h = {h * 1e3:.3g} ms was {where}. {way}"

    def blowup_headline(self) -> str:
        """The blow-up in a few words: '27x past its limit' (the pane's tag names the
        integrator)."""
        name = self.p["integrator"]
        pred = self.limit(name) if INTEGRATORS[name].explicit else None
        if pred is None or pred <= 0 or not math.isfinite(pred):
            return ""
        h = self.dt / self.p["substeps"]
        return f"{_times(h / pred)}x past its limit"

    def _energy_change(self) -> str:
        """The energy's change over the last simulated second, in the HUD's unit."""
        if len(self._energy) < 2:
            return ""
        t1, e1 = self._energy[-1]
        t0, e0 = next((t, e) for t, e in self._energy if t >= t1 - 1.0)
        if t1 <= t0:
            return ""
        change = self.shown("energy", e1 - e0)
        return f" ({'' if change.startswith('-') else '+'}{change} in {t1 - t0:.2g} s)"

    def energy_gain_words(self, energy: float) -> str:
        """Implicit Euler, undriven (wind off, no hand on the cloth since the settings last
        changed), with more energy than it started with: the step added it, not the physics.
        Say why: CG's loose tolerance (a step this stiff amplifies what it leaves) or, solved
        exactly, the one linearised Newton step; '' otherwise."""
        p, start = self.p, getattr(self, "_energy_start", None)
        if INTEGRATORS[p["integrator"]].explicit or start is None or "wind" in self.on \
                or energy - start <= ENERGY_GAIN_SHOWN * JOULE:
            return ""
        gain = self.shown("energy", energy - start)
        # (phrases parted by '  |  ' or '; ', each short enough for a row at 1024x768 with F2)
        if p["cg_tolerance"] > EXACT_TOLERANCE:
            return (f"energy {gain} above its start  |  not physics: the solve  |  CG stops at "
                    f"cg_tolerance {p['cg_tolerance']:g}; a step this stiff amplifies the rest"
                    f"  |  (cg_tolerance {EXACT_TOLERANCE:g}: exact, drains it)")
        return (f"energy {gain} above its start  |  a linearised step this large overshoots"
                "  |  smaller steps: higher hertz, more substeps")

    def _where(self) -> str:
        """Where the step is against the explicit limit and in which band: 'h = 16.667 ms  |
        33x symplectic Euler's limit (27x at rest)' (the line a class reads; its phrases
        parted by '  |  ' or '; ', each short enough for a row at 1024x768 with F2)."""
        p = self.p
        h = self.dt / p["substeps"]
        om, limit, name = self.omega_max, self.explicit_limit(), p["integrator"]
        title = INTEGRATORS[name].title
        where = f"h = {h * 1e3:.3f} ms"
        pred = self.limit(name)
        band = self.watch.band(name, h)
        if not INTEGRATORS[name].explicit:
            # the limit of the cloth as it is now: draped, it is stiffer than at rest (a held
            # explicit pane beside, rolled back to its start, reads the one at rest): say both
            rest = self.watch.rest("symplectic_euler")
            then = (f" ({_times(h / rest)}x at rest)" if rest and
                    _times(h / rest) != _times(h / limit) else "")
            where += (f"  |  {_times(h / limit)}x symplectic Euler's limit{then}"
                      if om > 0 else "")
        elif om <= 0:                          # every stiffness 0: no top mode, no limit
            where += ": no stiffness, so no step limit"
        elif pred is None:
            where += f": {title} is unstable at any h here (too little damping)"
        else:
            # symplectic Euler's is the linearised cloth's own limit (top_mode); the others' an
            # estimate on one mode: where damping mixes the modes, off by up to ~35 %
            kind = "damped" if name == "symplectic_euler" else "on one mode"
            rest = self.watch.rest(name) or pred
            seen = (f", {rest * 1e3:.3f} at rest" if rest > pred * 1.0005 else "")
            where += (f"  |  {_times(h / pred)}x {title}'s limit  |  {pred * 1e3:.3f} ms "
                      f"({kind}, lowest so far{seen})  |  "
                      + BAND_WORDS[band].format(m=marginal(name)))
        return where

    def hud_lines(self) -> list[str]:
        """What a class reads every frame: the material and integrator, the step against the
        explicit limit and its band, the energy and the stretch, and a solve that stopped
        short (in words)."""
        c, m, p = self.cloth, self.metrics(), self.p
        title = INTEGRATORS[p["integrator"]].title
        change = self._energy_change().strip()[1:-1]    # '-0.53 J in 0.93 s' (its zero named)
        lines = [f"{p['material']}, {title}: {self._where()}",
                 f"energy {self.shown('energy', m['energy'])} (0 at the start)"
                 f"{'  |  ' + change if change else ''}  |  "
                 f"max stretch {self.shown('max_stretch', m['max_stretch'])}"]
        if not INTEGRATORS[p["integrator"]].explicit:
            lines.append(self._solve_line())
        slow = self.real_time_words()
        if slow:
            from app.draw.hud import WARN_COLOR, Line
            lines.append(Line(slow, WARN_COLOR))
        gain = self.energy_gain_words(m["energy"])
        if gain:
            from app.draw.hud import WARN_COLOR, Line
            lines.append(Line(gain, WARN_COLOR))
        if self._cg_failure_t is not None:          # a solve that stopped short, in words
            n = c.ps.cg_failures
            lines.append(f"t = {self._cg_failure_t:.2f} s ({n} step{'s' if n > 1 else ''} so "
                         f"far): {c.ps.last_cg_failure.words()}")
        return lines

    def hud_details(self) -> list[str]:
        """The controls, the cloth's size, the limit's derivation and the CG residual."""
        m, name = self.metrics(), self.p["integrator"]
        om, limit = self.omega_max, self.explicit_limit()
        lines = ["LMB: move+lock | RMB: unlock | U: unlock all",
                 f"{m['particles']} particles, {m['springs']} springs; stretch: mean "
                 f"{self.shown('mean_stretch', m['mean_stretch'])}"]
        if om > 0:
            every = ESTIMATE_EVERY if INTEGRATORS[name].explicit else ESTIMATE_EVERY_IMPLICIT
            lines.append(f"omega_max {om:.4g}/s on the cloth as it is now (re-estimated every "
                         f"{every:g} s): undamped, explicit methods are stable below h = "
                         f"2/omega_max = {2e3 / om:.3f} ms (RK4: 2.83/omega_max = "
                         f"{2.83e3 / om:.3f} ms; forward Euler, midpoint: no h)"
                         + (f"; this damping lowers symplectic Euler's to {limit * 1e3:.3f} ms"
                            if self.mode_damping > 0 else ""))
        if not INTEGRATORS[name].explicit:
            lines.append(self._solve_details())
        return lines

    def _solve_line(self) -> str:
        """'solve: CG 86 iterations, 9.1 ms a step (direct LU: 58 ms, when last used)': the
        solver in use and its measured cost, beside the other one's if it ran on this cloth."""
        solver, report, ms = self.p["solver"], self.cloth.ps.solve, self._solve_ms
        if not report.method:
            return f"solve: {SOLVER_WORDS[solver]}, no step yet"
        cost = f"{ms[solver]:.3g} ms a step" if solver in ms else "-"
        text = (f"solve: CG {report.iterations} iterations, {cost}" if solver == "cg"
                else f"solve: {SOLVER_WORDS[solver]} {cost}")
        other = "direct" if solver == "cg" else "cg"
        if other in ms:
            text += f" ({SOLVER_WORDS[other]}: {ms[other]:.3g} ms, when last used)"
        return text

    def _solve_details(self) -> str:
        """The second page's line on the solve: CG's residual, its first guess and the cost of
        an iteration; the direct solve's residual and its factors' size against A's."""
        c, report = self.cloth, self.cloth.ps.solve
        nonzeros = c.ps.matrix.nonzeros if c.ps.matrix is not None else 0
        if report.method == "cg":
            start = "the last steps' dv" if report.warm else "dv = 0"
            factored = ("factored this step for the sparse LU that took it" if report.fallback
                        else "never factored")
            return (f"CG (block Jacobi, from {start}): residual {report.residual:.1e} (stops "
                    f"at {self.p['cg_tolerance']:g} |b|); A: {nonzeros:,} non-zeros, {factored}")
        if report.method:
            fill = (f": L and U hold {report.fill:,} non-zeros, {report.fill / nonzeros:.1f}x "
                    f"A's {nonzeros:,}" if report.fill and nonzeros else "")
            return f"direct: SuperLU factors A every step{fill}; residual {report.residual:.1e}"
        return "solve: no step yet"

    def real_time_words(self) -> str:
        """'' while the physics keeps up with real time; else in words how far behind it is and
        what would catch up. An explicit step is not offered fewer substeps (a larger h, nearer
        its limit: 'Leather inside its limit' would step past it), and implicit Euler at 60 Hz
        only where its estimated step (mass_spring_cost, which errs high) fits 1/60 s; a hertz
        whose frame asks for more steps than the loop runs (app/loop.py) is named, since there
        no cheaper step can catch up."""
        step, need = self.step_ms(), 1000.0 / self.p["hertz"]
        if self.steps < 5 or step <= need:
            return ""
        p, ms = self.p, self._solve_ms
        explicit = INTEGRATORS[p["integrator"]].explicit
        implicit_ms = frame_cost({**p, "integrator": "implicit_euler", "hertz": 60,
                                  "substeps": 1, "solver": "cg"}, self.world_size)[1] * 1e3
        implicit = (f"implicit_euler at 60 Hz (~{implicit_ms:.2g} ms a step, estimated)"
                    if implicit_ms < 1000.0 / 60 else "")
        if not explicit and p["solver"] == "direct" and (
                ms.get("cg", frame_cost({**p, "solver": "cg"}, self.world_size)[1] * 1e3)
                < ms.get("direct", 0.0)):           # CG as measured here, else as estimated
            way = "solver=cg"
        elif explicit:
            way = "a smaller cloth" + (f", or {implicit}," if implicit else "")
        else:
            way = "fewer particles or substeps" + (" or a looser cg_tolerance"
                                                  if p["solver"] == "cg" else "")
        text = f"not real time: {step:.3g} ms of physics per {need:.3g} ms step ({need / step:.2f}x)"
        cap, asked = FixedStepClock.max_steps_per_frame, p["hertz"] / FPS_CAP
        if asked <= cap:
            return f"{text}; {way} would catch up"
        most = cap * FPS_CAP                        # the highest hertz the loop runs in real time
        way = (f"{implicit} would" if explicit and implicit
               else f"hertz {most} or less, and {way}, would")
        text += (f", and the loop's {cap} steps a frame (app/loop.py) hold hertz {p['hertz']} "
                 f"to {cap / asked:.2f}x on any machine; {way} keep up")
        return text


    def energies(self):
        """Energy bars: the parts of `energy` (the metric), 0 at rest in the start pose."""
        from app.energy import Energies
        kinetic, springs, gravity = self.cloth.energy_parts()
        return Energies((("kinetic", kinetic), ("springs", springs), ("gravity", gravity)), 0.0,
                        zero="the start pose, at rest, every spring at its rest length",
                        losses="spring damping, air, implicit Euler's artificial damping; the "
                               "mouse and the wind put energy in", unit="J", scale=PX_PER_M ** 2)


def _times(ratio: float) -> str:
    """A ratio for the HUD: '0.72', '1.04', '3.50', '230' (not '2.3e+02')."""
    return f"{ratio:.2f}" if ratio < 10 else f"{ratio:.0f}"
