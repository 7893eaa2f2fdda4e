"""Mass-spring cloth: Hooke's springs, Blender's materials, and explicit vs implicit steps.

What it shows: the lectures' cloth as particles joined by damped springs (structural, shear,
bending), with Blender's cloth presets (cotton, denim, leather, rubber, silk) and all six
integrators of the particle system, switchable live. The HUD predicts the explicit methods'
stability limit from the cloth's highest frequency omega_max (power iteration with the stiffness
product and the masses; 2/omega_max undamped, less with spring damping: leather's is a tenth of
it) and says where the current step is. The limit belongs to the cloth's state: as the cloth
drapes its cells shear and its springs stretch, and its limit falls (to 0.62x of the value at
rest for rubber, 0.82x for silk; flung, to 0.62-0.74x), so the HUD re-estimates it on the moving
cloth (every 0.05 s), keeps the lowest seen, and gives a band: "stable" below half of it (0.4
for forward Euler), measured to hold for every material and explicit integrator from rest and
from a fling; "marginal" up to it (runs there blew up or gained energy from 0.6x to 0.9x of the
limit shown at the start); "past the limit" beyond. Past the limit the top mode grows (just past
it, it may only shiver), well past it an explicit integrator blows up, the shell's guard rolls
back and pauses, and implicit Euler (Baraff & Witkin's large steps) at the same step keeps going,
paying in artificial damping (watch the energy with damping, air and wind off). It linearises
the springs once per step (one Newton step), so a huge step still costs it: at hertz 1, cotton's
energy leaps from 0 to ~1.9e7 J at t = 3 s before the damping wins: within a minute it is back
to a few tens of J (where exactly depends on rounding: a 1e-12 px nudge of the start, or another
CPU's BLAS, moves it from -30 to +30 J; CG stops at 1e-2 of the residual, and a step this large
amplifies what that leaves). With cg_tolerance 1e-10 (exact: the sparse LU takes over where CG
cannot get there) the energy peaks at 4.7e7 J at t = 2 s and is -44 to -50 J (-45.6 measured),
hanging lower than it started, from 10 s on, on every machine.
Is the implicit step worth its solve? Measured (`python -m app bench mass_spring`: a 16x16 cloth,
wall time per simulated second, implicit Euler at 1/60 s against the cheapest explicit integrator at
its own measured limit; four runs at load 1-3, 2026-11-24): for stiff cloth by far (leather 33-38x
cheaper at Blender's stiffness, 220-310x at x10, 2800-3000x at x100; denim at x100 66-124x); at the
soft presets' own stiffness the margin is small or none (cotton 2.1x, rubber 2.5-3.3x, silk
0.74-1.4x: explicit won once; before CG was warm-started and block-preconditioned, mostly explicit
won, 0.3-1.1x) and noisy; and an explicit step kept in the stable band (half its limit) costs twice
as much as at the limit.
Which solver (`solver`)? Each implicit step solves one sparse linear system. `cg` is Baraff &
Witkin's choice and the lecture's: conjugate gradients only multiply by the matrix, stop at
cg_tolerance and start from the last steps' answer (with a 2x2 block Jacobi preconditioner);
`direct` is SciPy's sparse LU (SuperLU): exact up to rounding, but it factors the matrix anew every
step, and its factors fill in (11x the matrix's non-zeros at 64x64; 8x with shear on, whose springs
add more to the matrix than to its factors). Measured (`python -m app bench mass_spring`, denim;
four runs at load 1-3): the LU's solve costs 4.6-7.9x CG's at 32x32 and 6.4-10x at 64x64 (the ratio
swings from run to run), and grows faster with the cloth: as particles^1.1-1.3 against CG's
particles^0.7-1.1. The HUD gives each one's ms a step once it has run on this cloth: switch it live
to compare.
The step budget: the window waits for whole steps, and a frame runs hertz/60 of them (at most 8), so
a setting whose frame of steps would take over 0.1 s is refused, naming what would fit (fewer
substeps, a lower hertz, a looser cg_tolerance, solver=cg, fewer particles, or this cloth at 60 Hz,
1 substep, CG to 0.01). The estimate counts the forces, the matrix, CG's iterations (from the
substep against the cloth's highest frequency, and the tolerance) or the LU, times the substeps
(app/physics/mass_spring_cost.py); CG is also capped at the iterations that fit, and a solve stopped
there says so. When the physics cannot keep up with real time the HUD says so in words.
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
Obstacles (`obstacles`: the Verlet cloth's ball, box, table, floor, bar; drag one with LMB):
`contact` = projection (moved out, velocity filtered as Baraff & Witkin constrain a particle) or
penalty (a spring of contact_stiffness, which lowers the step limit); Coulomb friction `mu`.
scenes/mass_spring_contact.py; their cards: the scene mass_spring_collisions. Settings: material
sets the sliders below it (mass, tension, compression, shear_stiffness,
bending_stiffness, spring_damping, air_damping: Blender's names and units); moving one of them
afterwards makes the material `custom`. Integrator and every slider change live.

Metrics (units: px, s, kg): particles, springs, integrator; omega_max (1/s, the top mode's
frequency); explicit_limit_h (s: symplectic Euler's limit with this damping, which is what the HUD
compares your step with; undamped it would be 2/omega_max); step_limit_h (s: the explicit integrator
in use's limit, the lowest seen; null with implicit Euler) and limit_band; max_stretch and
mean_stretch (|length/rest - 1| of the structural springs); energy (kinetic + springs + gravity, 0
in the start pose, in kg px^2/s^2: the HUD divides by 256^2 to show joules, Blender's metre being
256 px); solver; cg_iterations (the last implicit solve's; null before the first solve, 0 with an
explicit integrator or solver=direct); cg_converged, cg_residual (|b - A dv| / |b| of the solver's
answer: CG's, or the LU's with solver=direct; where it stopped short and the other solve gave the
step, the HUD says so with that one's residual), cg_failures (solves that stopped short);
pinned_drift (px). The HUD and the metrics strip (F4) both write the energy in J, the stretches in
%, explicit_limit_h and step_limit_h in ms (`metric_units`).
"""

from __future__ import annotations

import collections
import math

import numpy as np

from app.physics.bounds import clamp_point
from app.physics.grid_shared import nearest_cell
from app.physics.integrators import INTEGRATORS
from app.physics.blender_cloth import MATERIAL_KEYS, MATERIALS, PX_PER_M, material_settings
from app.physics.mass_spring import FORCE_EFFECTS, PINS, SOLVERS, MassSpringCloth
from app.physics.mass_spring_cost import FRAME_BUDGET_S, iteration_cap, refusal, steps_per_frame
from app.physics.mass_spring_stability import ESTIMATE_EVERY, ESTIMATE_EVERY_IMPLICIT, LimitWatch
from app.scene import Effect, InputEvent, Param, ParamError, Scene, Try, Unit, common
from app.vectors import Arrows, grid_sample, sample_text
from scenes.mass_spring_contact import (MS_CONTACT_EFFECTS, MS_CONTACT_PARAMS, MS_CONTACT_UNITS,
                                        MassSpringContact)
from scenes.mass_spring_words import MassSpringWords

UNLOCK_KEY = "u"
MATERIAL_CHOICES = ("custom",) + tuple(MATERIALS)
JOULE = PX_PER_M ** 2       # kg px^2/s^2 per J, with Blender's metre = 256 px (blender_cloth.py)
# settings that change the step or the solver, not the cloth: its limits seen so far still hold
STEP_SETTINGS = {"integrator", "hertz", "substeps", "cg_tolerance", "solver"}


class MassSpringClothScene(MassSpringContact, MassSpringWords, Scene):
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
    presets = {"material": MATERIAL_KEYS}
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
              help="stiffness of the skip-one springs (scaled as Blender's linear bending, /20; "
                   "ours push and pull)",
              rebuild=False),
        Param("spring_damping", 5.0, float, 0.0, 1e4,
              help="spring damping (Blender units; / 0.0528 s -> kg/s)", rebuild=False),
        Param("air_damping", 1.0, float, 0.0, 1e4,
              help="air resistance f = -k v, k = 0.01 x this / 0.0528 s (kg/s)", rebuild=False),
        Param("rows", 20, int, 2, 128, help="particles from top to bottom"),
        Param("cols", 24, int, 2, 128, help="particles from left to right"),
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
        Param("solver", "cg", str, choices=SOLVERS,
              help="implicit Euler's linear solve: cg (conjugate gradients, Baraff & Witkin's) "
                   "or direct (SciPy's sparse LU); the HUD gives the cost of each",
              rebuild=False),
        Param("cg_tolerance", 1e-2, float, 1e-10, 0.5,
              help="implicit Euler: CG stops at |residual| <= this x |b| (and a direct solve "
                   "must reach it too)", rebuild=False),
    ) + MS_CONTACT_PARAMS
    effects = (
        Effect("gravity", True, "gravity f = m g", amount="g"),
        Effect("air", True, "air resistance f = -k v", amount="air_damping"),
        Effect("wind", False, "a wind field pushes the cloth", amount="wind_strength"),
        Effect("damping", True, "spring damping along each spring", amount="spring_damping"),
        Effect("shear", False, "diagonal springs resist shearing (in 2D: a rigid truss, see the "
               "docstring)", amount="shear_stiffness"),
        Effect("bending", True, "skip-one springs resist folding", amount="bending_stiffness"),
    ) + MS_CONTACT_EFFECTS
    error_metric, error_label = "max_stretch", "largest stretch"
    # the HUD and the metrics strip write these alike (the JSON keeps px, s, kg and fractions)
    metric_units = {"energy": Unit("J", 1.0 / JOULE, resolution=1e-3),
                    "max_stretch": Unit("%", 100.0, resolution=0.01, digits=3),
                    "mean_stretch": Unit("%", 100.0, resolution=0.01, digits=3),
                    "omega_max": Unit("1/s"),
                    "explicit_limit_h": Unit("ms", 1e3),
                    "step_limit_h": Unit("ms", 1e3),
                    "pinned_drift": Unit("px", resolution=0.01), **MS_CONTACT_UNITS}
    tries = (
        Try("Leather past its limit", {"material": "leather", "integrator": "symplectic_euler"},
            "symplectic Euler at h = 16.7 ms, far past the predicted limit: it blows up, the "
            "guard rolls back"),
        Try("Leather inside its limit",
            {"material": "leather", "integrator": "symplectic_euler", "hertz": 1000,
             "substeps": 20},
            "h = 0.05 ms, below the HUD's damped limit (0.06-0.07 ms; leather's strong spring "
            "damping cuts 2/omega_max's 0.66 ms tenfold), in its marginal band (0.8x): it "
            "holds, at 20000 steps per second, far from real time"),
        Try("Implicit Euler at 30 Hz", {"material": "denim", "integrator": "implicit_euler",
                                         "hertz": 30},
            "h = 33 ms: 70x symplectic Euler's limit at rest, ~90x once the cloth hangs (22-25x "
            "2/omega_max), and still stable; watch the CG iterations"),
        Try("Silk in the wind", {"material": "silk", "wind": True},
            "the wind pushes on area, not mass: light silk flows; switch to denim or rubber "
            "(7x and 20x heavier) and it hardly moves"),
    )
    comparisons = (     # "try this" cards that run variants side by side (--compare)
        Try("Explicit vs implicit at 60 Hz", {"hertz": 60},
            "h = 16.7 ms is 27x symplectic Euler's limit for cotton at rest: pane A blows up "
            "within a few steps and its pane says why, while pane B's implicit Euler hangs on, "
            "paying in artificial damping and in ms per step (its CG)",
            compare=({"integrator": "symplectic_euler"}, {"integrator": "implicit_euler"})),
    )

    # ----- settings ---------------------------------------------------------------------------
    @classmethod
    def check_combination(cls, values) -> None:
        """Refuse a setting whose frame of steps would hold the window longer than
        FRAME_BUDGET_S (app/physics/mass_spring_cost.py: what a step costs, and what would
        fit), in one line."""
        text = refusal(values, cls.world_size)
        if text:
            raise ParamError(text)

    @classmethod
    def resolve(cls, overrides):
        """As Scene.resolve, then a named material fills in the sliders not given explicitly;
        a slider given with a value other than the material's makes the material 'custom'. (The
        preset's values are filled in before Scene.resolve checks the combination, so the step
        budget sees the cloth that will be built.)"""
        named = next((v for k, v in overrides.items() if cls.canonical(k) == "material"), None)
        if named is not None and cls.check_setting("material", named) != "custom":
            given = {cls.canonical(k) for k in overrides}
            preset = material_settings(cls.check_setting("material", named))
            overrides = {**{k: v for k, v in preset.items() if k not in given}, **overrides}
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
        self._sync(names)

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
        self.watch = LimitWatch()                # omega_max and the limits, on the moving cloth
        self._cg_failure_t: float | None = None      # when implicit Euler's CG last stopped short
        self._solve_ms: dict[str, float] = {}        # ms per step of each solver, as measured
        self._solve_mark = 0.0                       # cloth.spent["solve"] at the last step
        self.build_contact()
        self._sync()

    def _sync(self, names: set[str] | None = None) -> None:
        """Hand the settings to the cloth (new force list, masses) and re-estimate omega_max;
        a change of the cloth itself (not of the step or the solver) starts the watch anew."""
        c, p = self.cloth, self.p
        c.material = {k: p[k] for k in MATERIAL_KEYS}
        c.g, c.wind_field, c.wind_strength = p["g"], p["wind_field"], p["wind_strength"]
        c.on = set(self.on)
        c.configure()
        self.sync_contact()                          # the penalty joins the force list
        c.ps.cg_tolerance, c.ps.solver = p["cg_tolerance"], p["solver"]
        c.ps.budget_iterations = iteration_cap(        # CG's most in a substep (the budget)
            p, FRAME_BUDGET_S / steps_per_frame(p["hertz"]))
        if names is None or names - {"solver"}:
            self._solve_ms.clear()                   # the costs measured no longer hold
        self._energy.clear()
        self._energy_start = c.energy()      # what implicit Euler may not climb above, undriven
        if names is None or names - STEP_SETTINGS:
            self.watch.forget()
        self._estimate_mode(iterations=60)

    def _estimate_mode(self, iterations: int) -> None:
        """omega_max and the damping rate from the current state, from scratch (kept as they
        were while the state is blown up)."""
        if self.cloth.is_sane():
            self.watch.restart(self.cloth.ps, self.time, iterations)

    @property
    def omega_max(self) -> float:
        return self.watch.omega

    @property
    def mode_damping(self) -> float:
        return self.watch.damping

    def limit(self, name: str) -> float | None:
        """Integrator `name`'s predicted step limit: the lowest seen on the moving cloth since
        its settings changed (None: unstable at every step; inf: implicit)."""
        if not INTEGRATORS[name].explicit:
            return math.inf
        return self.watch.lowest(name)

    def step(self, h: float) -> None:
        failures = self.cloth.ps.cg_failures
        self.contact_start()                         # where the particles start (contact)
        self.cloth.step(h, self.p["integrator"])
        self.contact_step(h)                         # projection and friction, if on
        if self.cloth.ps.cg_failures > failures:
            self._cg_failure_t = self.cloth.t         # the end of the step that failed
        self._stretch = None

    def after_step(self) -> None:
        name = self.p["integrator"]
        explicit = INTEGRATORS[name].explicit
        # what this step's solve cost, kept per solver (smoothed) so the HUD can set them side
        # by side once both have run on this cloth
        spent = self.cloth.spent["solve"]
        if not explicit:
            ms, solver = (spent - self._solve_mark) * 1e3, self.p["solver"]
            old = self._solve_ms.get(solver)
            self._solve_ms[solver] = ms if old is None else 0.8 * old + 0.2 * ms
        self._solve_mark = spent
        # the cloth's limit falls as it shears and stretches: follow it (every ESTIMATE_EVERY
        # simulated seconds, warm-started) and keep the lowest for the current integrator
        every = ESTIMATE_EVERY if explicit else ESTIMATE_EVERY_IMPLICIT
        if self.cloth.is_sane() and self.watch.follow(self.cloth.ps, self.time, every):
            if explicit:
                self.watch.track(name, self.dt / self.p["substeps"])

    # ----- the mouse ----------------------------------------------------------------------------
    def handle_event(self, event: InputEvent) -> None:
        c = self.cloth
        self._stretch = None
        if event.kind.startswith("mouse"):
            self.mouse = clamp_point(event.pos, c.world)
            self._energy_start = None            # a hand did work on the cloth: no bound now
        if self.contact_event(event):                # a press inside an obstacle drags it
            return
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
        self.draw_contact(surface, view)
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
        return self.contact_bounds((x0, y0, min(w - x0, 1.6 * cw), min(h - y0, 1.6 * ch)))

    # ----- reports ------------------------------------------------------------------------------
    def explicit_limit(self) -> float:
        """Symplectic Euler's predicted largest step on the cloth as it is now (the latest
        estimate): 2/omega_max undamped, less with damping."""
        return self.watch.limit("symplectic_euler")

    def metrics(self) -> dict:
        c = self.cloth
        s = np.concatenate([st.ravel() for st in self.stretches()])
        energy = c.energy()
        if not self._energy or self._energy[-1][0] != self.time:
            self._energy.append((self.time, energy))
        name = self.p["integrator"]
        implicit = not INTEGRATORS[name].explicit
        solved = implicit and self.steps > 0 and bool(c.ps.solve.method)
        return {
            "particles": c.rows * c.cols,
            "springs": c.spring_count(),
            "integrator": self.p["integrator"],
            "solver": self.p["solver"],
            "omega_max": self.omega_max,
            "explicit_limit_h": self.explicit_limit(),
            # the integrator's own limit the band is judged against (the lowest seen) and the band
            "step_limit_h": None if implicit else _finite(self.limit(name)),
            "limit_band": None if implicit else self.watch.band(name, self.dt / self.p["substeps"]),
            "max_stretch": float(s.max()),
            "mean_stretch": float(s.mean()),
            "energy": energy,
            # implicit only (else 0); None before its first step (no solve yet)
            "cg_iterations": (c.ps.cg_iterations if solved else None) if implicit else 0,
            # how the last solve ended (None: no implicit solve yet, or an explicit integrator)
            "cg_converged": c.ps.solve.converged if solved else None,
            "cg_residual": c.ps.solve.residual if solved else None,
            "cg_failures": c.ps.cg_failures,          # implicit steps whose CG stopped short
            "pinned_drift": c.pinned_drift(),
            **self.contact_metrics(),
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
        shown = [k for k in FORCE_EFFECTS if k in self.on] + ["structural", "solve"] + \
            (["collisions"] if self.colliding else [])
        return {k: self._costs.get(k, 0.0) for k in shown}

    def step_ms(self) -> float:
        """Measured ms of physics per fixed step: the effects' costs added up (0 before any)."""
        self.effect_costs()
        return sum(self._costs.values())

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
        self._estimate_mode(iterations=60)     # the lowest limit seen before stays (the hint)
        self.watch.estimated_at = -math.inf    # the runner sets the time back: estimate anew


def _finite(x: float | None) -> float | None:
    return x if x is not None and math.isfinite(x) else None

