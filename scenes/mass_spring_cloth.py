"""Mass-spring cloth: Hooke's springs, Blender's materials, and explicit vs implicit steps.

What it shows: the lectures' cloth as particles joined by damped springs (structural, shear,
bending), with Blender's cloth presets (cotton, denim, leather, rubber, silk) and all six
integrators of the particle system, switchable live. The HUD predicts the explicit methods'
stability limit from the cloth's highest frequency omega_max (power iteration with the stiffness
product and the masses; 2/omega_max undamped, less with spring damping: leather's is a tenth of
it) and says where the current step is; past the limit the top mode grows (just past it, it may
only shiver), well past it an explicit integrator blows up, the shell's guard rolls back and
pauses, and implicit Euler (Baraff & Witkin's large steps) at the same step keeps going,
paying in artificial damping (watch the energy with damping, air and wind off). It linearises
the springs once per step (one Newton step), so a huge step still costs it: at hertz 1, cotton's
energy leaps from 0 to ~2.4e5 J in the first 10 s before the damping wins (~11 J after 2 min).
Physics: app/physics/mass_spring.py (Blender's units in pixels and seconds: blender_cloth.py);
drawing: app/draw/cloth_draw.py, the Verlet cloth's strain heat map and legend, so the two cloths
compare directly.

Controls:
  LMB       grab the nearest particle and drag it: it is a moving pin (placed at the mouse before
            every step, at rest, filtered out of the implicit solve); let go and it stays locked
  RMB       unlock a locked particle (a pin, or one you dropped)
  U         unlock everything and restore the default pins
Why shear is off by default: in 2D the diagonal springs make every preset a stiff truss (their
stiffness equals the tension in all five presets), so silk would swing like a leather board; the
materials differ in how they drape, which needs the cells free to shear. Without shear, on the
default cloth (implicit Euler, 60 Hz), leather's bending springs (bending 150) hold its top edge to
about half the sag of silk, cotton or denim (some 33 px against 55-61 px), and rubber (mass 3,
stiffness 15) sags most, stretches up to ~60 % as it drops and bounces; silk has no spring damping
at all and is the lightest, and the wind pushes on area, not mass: in the wind silk flows while
denim and rubber hang.
Settings: material sets the sliders below it (mass, tension, compression, shear_stiffness,
bending_stiffness, spring_damping, air_damping: Blender's names and units); moving one of them
afterwards makes the material `custom`. Integrator and every slider change live.

Metrics (units: px, s, kg): particles, springs, integrator; omega_max (1/s, the top mode's
frequency); explicit_limit_h (s: symplectic Euler's limit with this damping, which is what the HUD
compares your step with; undamped it would be 2/omega_max); max_stretch and mean_stretch
(|length/rest - 1| of the structural springs); energy (kinetic + springs + gravity, 0 in the
start pose, in kg px^2/s^2: the HUD divides by 256^2 to show joules, Blender's metre being
256 px); cg_iterations (the last implicit solve's; null before the first solve, 0 with an
explicit integrator); pinned_drift (px). The HUD and the metrics strip (F4) both write the energy
in J, the stretches in %, explicit_limit_h in ms (`metric_units`).
"""

from __future__ import annotations

import collections
import math

import numpy as np

from app.physics.bounds import clamp_point
from app.physics.grid_shared import nearest_cell
from app.physics.integrators import INTEGRATORS
from app.physics.blender_cloth import MATERIAL_KEYS, MATERIALS, PX_PER_M, material_settings
from app.physics.mass_spring import FORCE_EFFECTS, PINS, MassSpringCloth
from app.physics.mass_spring_stability import predicted_limit, symplectic_limit, top_mode
from app.scene import Effect, InputEvent, Param, ParamError, Scene, Try, Unit, common
from app.vectors import Arrows, grid_sample, sample_text

UNLOCK_KEY = "u"
# particles x substeps per step: 32x32 x 39, 64x64 x 9. Measured at 64x64 x 9, implicit Euler:
# 0.06 s per step (cotton) to 0.4 s (every stiffness 1e5, mass 0.001, shear on); 1.2 s with
# cg_tolerance 1e-10 on top (CG iterations, not particles, decide the rest)
STEP_BUDGET = 40_000
MODE_EVERY = 30             # fixed steps between two estimates of omega_max (warm-started)
MATERIAL_CHOICES = ("custom",) + tuple(MATERIALS)
JOULE = PX_PER_M ** 2       # kg px^2/s^2 per J, with Blender's metre = 256 px (blender_cloth.py)


class MassSpringClothScene(Scene):
    """Mass-spring cloth: damped springs, Blender's materials, six integrators.

    LMB: grab a particle and drag it (a moving pin); drop it: it stays locked there.
    RMB: unlock a locked particle.   U: unlock all and restore the default pins.
    material sets the sliders (Blender's units); moving a slider makes it 'custom'.
    The HUD gives the step you are at against the explicit limit (F4: the limit itself, h <
    2/omega_max undamped, less with damping): switch the integrator to symplectic_euler at 60 Hz
    and it blows up (rolled back); implicit_euler goes on.
    Effects: gravity, air, wind, damping, shear, bending (each on/off, each with its cost: F4).
    """

    name = "mass_spring_cloth"
    title = "Mass-spring cloth"
    category = "Cloth"
    params = (
        Param("material", "cotton", str, choices=MATERIAL_CHOICES,
              help="a Blender cloth preset (sets the sliders below); custom: your own values",
              rebuild=False),
        Param("integrator", "implicit_euler", str, choices=tuple(INTEGRATORS),
              help="time integrator (implicit_euler: Baraff-Witkin, CG solve)", rebuild=False),
        common("hertz"),
        common("substeps"),
        Param("mass", 0.3, float, 0.001, 100.0,
              help="Blender's vertex mass in kg: a 16x16 px cell's mass (density = mass/256 px^2)",
              rebuild=False),
        Param("tension", 15.0, float, 0.0, 1e5,
              help="stiffness of a stretched structural spring (Blender units; x9.17e4/spacing "
                   "-> kg/s^2)", rebuild=False),
        Param("compression", 15.0, float, 0.0, 1e5,
              help="stiffness of a compressed structural spring (Blender units)", rebuild=False),
        Param("shear_stiffness", 15.0, float, 0.0, 1e5, help="stiffness of the diagonal springs",
              rebuild=False),
        Param("bending_stiffness", 0.5, float, 0.0, 1e5,
              help="stiffness of the skip-one springs (Blender's linear bending: /20)",
              rebuild=False),
        Param("spring_damping", 5.0, float, 0.0, 1e4,
              help="spring damping (Blender units; / 0.0528 s -> kg/s)", rebuild=False),
        Param("air_damping", 1.0, float, 0.0, 1e4,
              help="air resistance f = -k v, k = 0.01 x this / 0.0528 s (kg/s)", rebuild=False),
        Param("rows", 20, int, 2, 64, help="particles from top to bottom"),
        Param("cols", 24, int, 2, 64, help="particles from left to right"),
        Param("spacing", 16.0, float, 4.0, 40.0,
              help="rest length of a structural spring in px (shrunk if the cloth would not fit)"),
        Param("pins", "corners", str, choices=PINS,
              help="what holds the cloth: its top-left corner (it swings down), both top "
                   "corners, the whole top row, or nothing"),
        Param("g", 900.0, float, 0.0, 5000.0, help="gravity in px/s^2 (downwards)",
              rebuild=False),
        Param("wind_strength", 600.0, float, 0.0, 5000.0,
              help="the wind's push on the cloth's area, as the acceleration it gives cotton in "
                   "px/s^2 (silk, half as heavy, gets 2x; denim 0.3x)",
              rebuild=False),
        Param("wind_field", "gust", str, choices=("gust", "lecture"),
              help="gust: travelling gusts; lecture: the slide's (sin(x*y*t), cos(z*t)), z = 1",
              rebuild=False),
        Param("cg_tolerance", 1e-2, float, 1e-10, 0.5,
              help="implicit Euler: CG stops at |residual| <= this x |b|", rebuild=False),
    )
    effects = (
        Effect("gravity", True, "gravity f = m g", amount="g"),
        Effect("air", True, "air resistance f = -k v", amount="air_damping"),
        Effect("wind", False, "a wind field pushes the cloth", amount="wind_strength"),
        Effect("damping", True, "spring damping along each spring", amount="spring_damping"),
        Effect("shear", False, "diagonal springs resist shearing (in 2D: a rigid truss, see the "
               "docstring)", amount="shear_stiffness"),
        Effect("bending", True, "skip-one springs resist folding", amount="bending_stiffness"),
    )
    error_metric, error_label = "max_stretch", "largest stretch"
    # the HUD and the metrics strip write these alike (the JSON keeps px, s, kg and fractions)
    metric_units = {"energy": Unit("J", 1.0 / JOULE, resolution=1e-3),
                    "max_stretch": Unit("%", 100.0, resolution=0.01, digits=3),
                    "mean_stretch": Unit("%", 100.0, resolution=0.01, digits=3),
                    "omega_max": Unit("1/s"),
                    "explicit_limit_h": Unit("ms", 1e3),
                    "pinned_drift": Unit("px", resolution=0.01)}
    tries = (
        Try("Leather past its limit", {"material": "leather", "integrator": "symplectic_euler"},
            "symplectic Euler at h = 16.7 ms, far past the predicted limit: it blows up, the "
            "guard rolls back"),
        Try("Leather inside its limit",
            {"material": "leather", "integrator": "symplectic_euler", "hertz": 1000,
             "substeps": 20},
            "h = 0.05 ms, below the HUD's damped limit (~0.07 ms; leather's strong spring "
            "damping cuts 2/omega_max's 0.66 ms tenfold): stable, but 20000 steps per second"),
        Try("Implicit Euler at 30 Hz", {"material": "denim", "integrator": "implicit_euler",
                                         "hertz": 30},
            "h = 33 ms: 70x symplectic Euler's limit at rest, ~90x once the cloth hangs (22-25x "
            "2/omega_max), and still stable; watch the CG iterations"),
        Try("Silk in the wind", {"material": "silk", "wind": True},
            "the wind pushes on area, not mass: light silk flows; switch to denim or rubber "
            "(7x and 20x heavier) and it hardly moves"),
    )

    # ----- settings ---------------------------------------------------------------------------
    @classmethod
    def check_combination(cls, values) -> None:
        work = values["rows"] * values["cols"] * values["substeps"]
        if work > STEP_BUDGET:
            raise ParamError(
                f"rows x cols x substeps too large: {values['rows']}x{values['cols']} x "
                f"{values['substeps']} substeps = {work} particle-steps per step; accepted: at "
                f"most {STEP_BUDGET} (up to ~0.4 s per step with implicit Euler)")

    @classmethod
    def resolve(cls, overrides):
        """As Scene.resolve, then a named material fills in the sliders not given explicitly;
        a slider given with a value other than the material's makes the material 'custom'."""
        values, on = super().resolve(overrides)
        if values["material"] != "custom":
            given = {cls.canonical(k) for k in overrides}
            preset = material_settings(values["material"])
            if any(k in given and values[k] != v for k, v in preset.items()):
                values["material"] = "custom"
            values.update({k: v for k, v in preset.items() if k not in given})
        return values, on

    def settings_changed(self, names: set[str]) -> None:
        if "material" in names and self.p["material"] != "custom":
            self.p.update(material_settings(self.p["material"]))
        elif names & set(MATERIAL_KEYS):
            self.p["material"] = "custom"
        self._sync()

    # ----- world --------------------------------------------------------------------------------
    def build(self) -> None:
        p = self.p
        rows, cols = p["rows"], p["cols"]
        w, h = self.world_size
        spacing = min(p["spacing"], 0.6 * w / (cols - 1), 0.6 * h / (rows - 1))
        # one corner: the cloth swings down under it, so start it right of the middle
        left = 0.3 * w if p["pins"] == "corner" else (w - spacing * (cols - 1)) / 2
        origin = (left, 0.36 * h)
        self.cloth = MassSpringCloth(rows, cols, spacing, origin, p["pins"], (float(w), float(h)))
        self.grab_radius = max(14.0, 1.2 * spacing)
        self.mouse: tuple[float, float] | None = None
        self._costs: dict[str, float] = {}
        self._cost_mark = (0, dict(self.cloth.spent))
        self._stretch: tuple[np.ndarray, np.ndarray] | None = None
        self._energy: collections.deque = collections.deque(maxlen=600)   # (time, energy)
        self._mode: np.ndarray | None = None
        self._sync()

    def _sync(self) -> None:
        """Hand the settings to the cloth (new force list, masses) and re-estimate omega_max."""
        c, p = self.cloth, self.p
        c.material = {k: p[k] for k in MATERIAL_KEYS}
        c.g, c.wind_field, c.wind_strength = p["g"], p["wind_field"], p["wind_strength"]
        c.on = set(self.on)
        c.configure()
        c.ps.cg_tolerance = p["cg_tolerance"]
        self._energy.clear()
        self._estimate_mode(iterations=60)

    def _estimate_mode(self, iterations: int) -> None:
        """omega_max and the damping rate from the current state (kept as they were while the
        state is blown up; a fresh start after a rollback)."""
        if not self.cloth.is_sane():
            return
        self.omega_max, self.mode_damping, self._mode = top_mode(self.cloth.ps, iterations,
                                                                 self._mode)
        self._limits: dict[str, float | None] = {}

    def limit(self, name: str) -> float | None:
        """Integrator `name`'s predicted step limit on the top mode (cached until the next
        estimate of omega_max)."""
        if name not in self._limits:
            self._limits[name] = predicted_limit(name, self.omega_max, self.mode_damping)
        return self._limits[name]

    def blowup_hint(self) -> str:
        """The explicit limit in so many words: how far past it the step was, and the way out."""
        name, p = self.p["integrator"], self.p
        pred = self.limit(name) if INTEGRATORS[name].explicit else None
        if pred is None or pred <= 0:
            return ""
        h = self.dt / p["substeps"]
        need = math.ceil(1.0 / pred)               # steps per second inside the limit
        most = int(self.param("hertz").hi * self.param("substeps").hi)
        way = (f"Raise hertz x substeps to at least {need:,}, or take implicit_euler."
               if need <= most else
               f"That takes {need:,} steps per second, more than hertz x substeps reach "
               f"({most:,}): take implicit_euler.")
        title = INTEGRATORS[name].title
        return (f"h = {h * 1e3:.3g} ms is {_times(h / pred)}x {title}'s predicted limit "
                f"({pred * 1e3:.3g} ms): keep the step below it. {way}")

    def step(self, h: float) -> None:
        self.cloth.step(h, self.p["integrator"])
        self._stretch = None

    def after_step(self) -> None:
        if self.steps % MODE_EVERY == 0:
            self._estimate_mode(iterations=10)     # the stretch changes omega_max a little

    # ----- the mouse ----------------------------------------------------------------------------
    def handle_event(self, event: InputEvent) -> None:
        c = self.cloth
        self._stretch = None
        if event.kind.startswith("mouse"):
            self.mouse = clamp_point(event.pos, c.world)
        if event.kind == "mouse_down" and event.button == 1:
            cell = nearest_cell(c.x, self.mouse, self.grab_radius)
            if cell is not None:
                c.grab(cell, self.mouse)
        elif event.kind == "mouse_move" and c.grabbed is not None:
            c.grab_target = self.mouse
        elif event.kind == "mouse_up" and event.button == 1 and c.grabbed is not None:
            c.release(self.mouse)
        elif event.kind == "mouse_down" and event.button == 3 and c.grabbed is None:
            cell = nearest_cell(c.x, self.mouse, self.grab_radius, c.locked)
            if cell is not None:
                c.unlock(cell)
        elif event.kind == "key_down" and event.key == UNLOCK_KEY:
            c.unlock_all()

    # ----- drawing ------------------------------------------------------------------------------
    def stretches(self) -> tuple[np.ndarray, np.ndarray]:
        """|length / rest - 1| of the horizontal and vertical structural springs (cached until
        the particles move)."""
        if self._stretch is None:
            horizontal, vertical = self.cloth.sets["structural"].families
            self._stretch = (self.cloth.stretch(horizontal), self.cloth.stretch(vertical))
        return self._stretch

    def arrows(self) -> Arrows:
        """A regular sample of the particles (edges included) with their masses."""
        c = self.cloth
        ids = grid_sample(c.rows, c.cols)
        ps = c.ps
        return Arrows(ids, ps.x[ids].copy(), ps.v[ids].copy(), ps.mass[ids].copy(),
                      sample_text(len(ids), c.rows * c.cols, "particle"))

    def draw(self, surface, view) -> None:
        from app.draw.cloth_draw import draw_cloth
        hover = None
        if self.mouse is not None and self.cloth.grabbed is None:
            hover = nearest_cell(self.cloth.x, self.mouse, self.grab_radius)
        draw_cloth(surface, view, self.cloth, hover, self.stretches())

    @property
    def color_key(self) -> tuple:
        """The strain colours of the Verlet cloth, for the HUD's colour key (same legend)."""
        from app.draw.cloth_draw import strain_key
        return strain_key()

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The hanging cloth with room to sag (rubber), swing and billow, inside the world."""
        c, (w, h) = self.cloth, self.world_size
        cw, ch = c.spacing * (c.cols - 1), c.spacing * (c.rows - 1)
        ox, oy = c.rest_x[0]                                    # the top-left particle at rest
        x0, y0 = max(0.0, ox - 0.3 * cw), max(0.0, oy - 0.1 * ch)
        return (x0, y0, min(w - x0, 1.6 * cw), min(h - y0, 1.6 * ch))

    # ----- reports ------------------------------------------------------------------------------
    def explicit_limit(self) -> float:
        """Symplectic Euler's predicted largest step: 2/omega_max undamped, less with damping."""
        return symplectic_limit(self.omega_max, self.mode_damping)

    def metrics(self) -> dict:
        c = self.cloth
        s = np.concatenate([st.ravel() for st in self.stretches()])
        energy = c.energy()
        if not self._energy or self._energy[-1][0] != self.time:
            self._energy.append((self.time, energy))
        implicit = self.p["integrator"] == "implicit_euler"
        return {
            "particles": c.rows * c.cols,
            "springs": c.spring_count(),
            "integrator": self.p["integrator"],
            "omega_max": self.omega_max,
            "explicit_limit_h": self.explicit_limit(),
            "max_stretch": float(s.max()),
            "mean_stretch": float(s.mean()),
            "energy": energy,
            # implicit only (else 0); None before its first step (no solve yet)
            "cg_iterations": (c.ps.cg_iterations if self.steps else None) if implicit else 0,
            "pinned_drift": c.pinned_drift(),
        }

    def effect_costs(self) -> dict[str, float]:
        """ms per step of each active effect, the structural springs and the integrator's own
        work ('solve': its arithmetic, and implicit Euler's CG), lightly smoothed."""
        steps0, spent0 = self._cost_mark
        if self.steps > steps0:
            spent, n = self.cloth.spent, self.steps - steps0
            for k in spent:
                now = (spent[k] - spent0.get(k, 0.0)) * 1000.0 / n
                self._costs[k] = now if k not in self._costs else 0.7 * self._costs[k] + 0.3 * now
            self._cost_mark = (self.steps, dict(spent))
        shown = [k for k in FORCE_EFFECTS if k in self.on] + ["structural", "solve"]
        return {k: self._costs.get(k, 0.0) for k in shown}

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

    def _where(self) -> str:
        """Where the step is against the explicit limit: 'h = 16.667 ms = 33x symplectic
        Euler's limit' (the line a class reads)."""
        c, p = self.cloth, self.p
        h = self.dt / p["substeps"]
        om, limit, name = self.omega_max, self.explicit_limit(), p["integrator"]
        title = INTEGRATORS[name].title
        where = f"h = {h * 1e3:.3f} ms"
        pred = self.limit(name)
        if not INTEGRATORS[name].explicit:
            where += ((f" = {h / limit:.0f}x symplectic Euler's limit" if om > 0 else "")
                      + f"; CG {c.ps.cg_iterations} iterations")
        elif om <= 0:                          # every stiffness 0: no top mode, no limit
            where += ": no stiffness, so no step limit"
        elif pred is None:
            where += f": {title} is unstable at any h here (too little damping)"
        elif name == "symplectic_euler":       # the linearised cloth's own limit (top_mode)
            where += (f" = {_times(h / pred)}x {title}'s limit ({pred * 1e3:.3f} ms, damped)"
                      + (": its top mode grows (a shiver, or a blow-up)" if h > pred
                         else ": stable"))
        else:       # one mode's limit: where damping mixes the modes, off by up to ~35 %
            where += (f" = {_times(h / pred)}x {title}'s limit estimated on one mode "
                      f"({pred * 1e3:.3f} ms)")
        return where

    def hud_lines(self) -> list[str]:
        """What a class reads every frame: the material and integrator, the step against the
        explicit limit, the energy and the stretch."""
        m, p = self.metrics(), self.p
        title = INTEGRATORS[p["integrator"]].title
        return [f"{p['material']}, {title}: {self._where()}",
                f"energy {self.shown('energy', m['energy'])}{self._energy_change()}  |  "
                f"max stretch {self.shown('max_stretch', m['max_stretch'])}"]

    def hud_details(self) -> list[str]:
        """The controls, the cloth's size, the limit's derivation and the CG residual."""
        c, m = self.cloth, self.metrics()
        om, limit = self.omega_max, self.explicit_limit()
        lines = ["LMB: move+lock | RMB: unlock | U: unlock all",
                 f"{m['particles']} particles, {m['springs']} springs; stretch: mean "
                 f"{self.shown('mean_stretch', m['mean_stretch'])}"]
        if om > 0:
            lines.append(f"undamped, explicit methods are stable below h = 2/omega_max = "
                         f"{2e3 / om:.3f} ms (RK4: 2.83/omega_max = {2.83e3 / om:.3f} ms; forward "
                         f"Euler, midpoint: no h)"
                         + (f"; this damping lowers symplectic Euler's to {limit * 1e3:.3f} ms"
                            if self.mode_damping > 0 else ""))
        if not INTEGRATORS[self.p["integrator"]].explicit:
            lines.append(f"CG: {c.ps.cg_iterations} iterations, residual {c.ps.cg_residual:.1e} "
                         f"(stops at {self.p['cg_tolerance']:g} x |b|)")
        return lines

    # ----- state --------------------------------------------------------------------------------
    def state_arrays(self):
        c = self.cloth
        return [c.ps.x, c.ps.v, c.locked]

    def is_finite(self) -> bool:
        """False once the state is NaN/inf or has blown up (MassSpringCloth.is_sane)."""
        return self.cloth.is_sane()

    def snapshot(self):
        return self.cloth.copy_state()

    def restore(self, snap) -> None:
        if snap is None:
            self.reset()
            return
        self.cloth.restore_state(snap)
        self._stretch = None
        self._energy.clear()
        self._mode = None
        self._estimate_mode(iterations=60)


def _times(ratio: float) -> str:
    """A ratio for the HUD: '0.72', '3.5', '230' (not '2.3e+02')."""
    return f"{ratio:.2g}" if ratio < 10 else f"{ratio:.0f}"
