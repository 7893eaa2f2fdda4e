"""Verlet cloth: the lecture's centrepiece, grabbed with the mouse, honest about what accuracy costs.

What it shows: a grid of particles joined by rigid rods (Jakobsen, GDC 2001), moved by the
velocity-less Verlet step and kept together by relaxing the rods again and again. The lines are
coloured by how much each rod is stretched (a heat map of |length/rest - 1|), so raising
`iterations` or `substeps` shows at once what it gains (cooler colours) and what it costs (the
HUD's ms per step). Physics: app/physics/cloth.py; drawing: app/draw/cloth_draw.py.

Controls:
  LMB       grab the nearest particle and drag it; let go and it stays locked there (it follows
            the mouse at most 1e5 px beyond the world's edges, so no drag can tear it to inf)
  RMB       unlock a locked particle (a pin, or one you dropped)
  U         unlock everything and restore the default pins
  LMB inside an obstacle (obstacles=ball, box, table, floor, bar): drag the obstacle instead
Settings: iterations and substeps change live; try --set shear=on, --set tearing=on,
--set pins=corners, --set wind=on, --set obstacles=ball. Obstacles, friction and
self-collision, with their cards: the scene cloth_collisions (scenes/cloth_collisions.py).

Why shear is off by default: the slide's cloth has structural rods only, and in 2D shear rods turn
the cloth into a rigid truss. Yanked hard (say ten cloth widths in one frame) such a truss can come
back folded over itself and stay jammed: mirror-image cells satisfy every rod, and the seam between
flipped and unflipped cells stays strained (a real cloth would unfold in the third dimension).
Without shear the cloth always falls back to hanging (at worst with a crease). R resets.

Switching shear (or bending) on mid-run does not tear the cloth by itself. New rods at their full
rest length on a cloth the wind has sheared (some cells folded, their diagonals near zero) would
yank it back in a few sweeps, and with tearing on that tore hundreds of rods at once. So a rod set
switched on mid-run starts with every rod at its current length and eases to its true rest length
over one simulated second: the cloth is pulled back into shape instead of snapped. (Keeping the
current lengths for good would freeze the sheared shape into the cloth; the rods should pull it
back to square, just not break while they do.)

The stripes at low iterations (say 1 to 5): on the hanging cloth, rows of vertical rods alternate
red and blue (columns of horizontal rods do the same when it is pulled sideways). That is
Gauss-Seidel showing its order. A sweep solves the vertical rods starting in even rows first, all
at once, then those starting in odd rows, which share particles with them: the odd batch, solved
last, ends each sweep at its rest length (blue), and moving the shared particles has stretched the
even batch again (red). Measured after 2 s hanging at 1 iteration: even rows 27% stretched, odd
rows 0.0001%; at 20 iterations even rows 2%. More iterations shrink the red, and the stripes fade.
We keep the fixed order and explain it rather than alternate it: it is a real property of the
method, worth seeing (app/physics/rods.py, "batches").

The HUD's second page (F4) splits the physics time per step into its parts (the rod sets'
sweeps, the Verlet step, each force, tearing), as shares, so it agrees with whatever ms/step the
window shows for the whole step.
"""

from __future__ import annotations

import numpy as np

from app.physics.cloth import (DRAG, FORCE_NAMES, GRAVITY, ITERATIONS, PIN_CHOICES, TEAR_RATIO,
                               WIND_FIELDS, WIND_STRENGTH, Cloth)
from app.physics import rods_compiled
from app.physics.cloth_contact import CONTACT_EFFECTS as CONTACT_NAMES
from app.physics.rods import SET_NAMES, sweep_size
from app.scene import Effect, InputEvent, Param, ParamError, Scene, Try, Unit, common
from app.vectors import Arrows, grid_sample, sample_text
from scenes.cloth_contact import CONTACT_EFFECTS, CONTACT_PARAMS, CONTACT_UNITS, ClothContact

UNLOCK_KEY = "u"
# Work per step, in rod updates: iterations x substeps x (rods + BATCH_COST x batches), counting
# all three rod sets (shear and bending can be switched on live, without a check). Measured on the
# 2-core lab machine while other work ran: ~13 ns per rod update (a 256x256 sweep), ~19 us per
# batch call (NumPy's per-call overhead, which dominates small cloths: 1500 rod updates' worth).
# WORK_BUDGET = 4e7 rod updates keeps a step near 0.5 s (worst accepted cases: 0.4-0.6 s).
WORK_BUDGET = 4e7
BATCH_COST = 1500


def _sci(x: float) -> str:
    """2.0e9, not 2.0e+09."""
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa.removesuffix('.0')}e{int(exponent)}"


class ClothScene(ClothContact, Scene):
    """Verlet cloth (Jakobsen's rods relaxed by local iteration), strain shown as a heat map.

    LMB: grab a particle, drag it, drop it: it stays locked where you drop it.
    RMB: unlock a locked particle.   U: unlock all and restore the default pins.
    Raise `iterations` or `substeps` and watch the stretch fall and the ms per step rise.
    Effects: gravity, drag, wind, shear, bending, tearing (each on/off). Shear is off by default:
    in 2D it makes the cloth a rigid truss that, yanked hard, can jam folded over itself.
    """

    name = "cloth"
    title = "Verlet cloth"
    category = "Cloth"
    aliases = {"bend": "bending", "tear": "tearing"}   # the names the lecture and issue use
    params = (
        Param("rows", 28, int, 2, 256, help="particles from top to bottom"),
        Param("cols", 40, int, 2, 256, help="particles from left to right"),
        Param("spacing", 16.0, float, 2.0, 60.0,
              help="rest length of a rod in px (shrunk if the cloth would not fit the world)"),
        Param("iterations", ITERATIONS, int, 1, 100,
              help="relaxation sweeps over all rods per substep", rebuild=False),
        common("substeps"),            # here, not at the end: next to iterations in the panel
        Param("g", GRAVITY, float, 0.0, 5000.0, help="gravity in px/s^2 (downwards)",
              rebuild=False),
        Param("drag_coef", DRAG, float, 0.0, 0.5,
              help="fraction of velocity lost per 1/60 s, whatever the substeps "
                   "(0.01: Verlet's 2 becomes 1.99 at 60 Hz)",
              rebuild=False),
        Param("wind_strength", WIND_STRENGTH, float, 0.0, 5000.0, help="wind acceleration in px/s^2",
              rebuild=False),
        Param("wind_field", "gust", str, choices=WIND_FIELDS,
              help="gust: travelling gusts; lecture: the slide's (sin(x*y*t), cos(t))",
              rebuild=False),
        Param("tear_ratio", TEAR_RATIO, float, 1.05, 20.0,
              help="a rod breaks when stretched beyond this times its rest length", rebuild=False),
        Param("pins", "top", str, choices=PIN_CHOICES,
              help="what holds the cloth: the whole top row, its two corners, or nothing"),
        Param("precision", "float32", str, choices=("float32", "float64"),
              help="float type of the positions (float32: about twice as fast)"),
        Param("kernel", "numpy", str, choices=rods_compiled.KERNELS,
              help="who solves the rods and self-collision's grid pass: numpy (batches of "
                   "array operations, the default) or numba (the same loops compiled: needs "
                   "numba; the first step compiles them)",
              rebuild=False),
    ) + CONTACT_PARAMS
    effects = (
        Effect("gravity", True, "gravity pulls every particle down", amount="g"),
        Effect("drag", True, "velocity-proportional damping (Verlet 2 -> 1.99)", amount="drag_coef"),
        Effect("wind", False, "a wind field pushes the cloth", amount="wind_strength"),
        Effect("shear", False, "diagonal rods: resist shearing (a stiff 2D truss: see the docstring)"),
        Effect("bending", False, "skip-one rods: resist folding"),
        Effect("tearing", False, "rods stretched beyond tear_ratio break"),
    ) + CONTACT_EFFECTS
    error_metric, error_label = "max_stretch", "largest stretch"
    metric_units = {"max_stretch": Unit("%", 100.0, resolution=0.01, digits=3),
                    "mean_stretch": Unit("%", 100.0, resolution=0.01, digits=3),
                    "pinned_drift": Unit("px", resolution=0.01), **CONTACT_UNITS}
    tries = (
        Try("Stretchy: 2 iterations", {"iterations": 2, "substeps": 1},
            "the rods cannot relax in 2 sweeps: the cloth sags, warm colours, the stretch in the "
            "HUD rises; then try 50"),
        Try("Stiff: 50 iterations", {"iterations": 50, "substeps": 1},
            "the stretch falls; the physics ms/step grows with the sweeps: about 5x the "
            "default 10 iterations' (over 10x the 2 iterations')"),
        Try("2 iterations x 5 subst.", {"iterations": 2, "substeps": 5},
            "10 sweeps per step as at the default 10 iterations, yet much less stretch: small "
            "steps beat many iterations"),
        Try("Wind and tearing", {"wind": True, "tearing": True},
            "the gusts billow the cloth; yank it with the mouse and rods stretched past "
            "tear_ratio break (torn in the HUD)"),
    )
    comparisons = (     # "try this" cards that run variants side by side (--compare)
        Try("2 vs 20 iterations", {},
            "side by side from the same start: ten times the sweeps buy about ten times less "
            "stretch (pane B's colours stay cool) for several times the ms per step",
            compare=({"iterations": 2}, {"iterations": 20})),
        Try("1x10 vs 10x1", {},
            "the same 10 sweeps a step, spent as 10 iterations of 1 substep (A) or 1 iteration "
            "in each of 10 substeps (B): B stretches about ten times less for a little more "
            "time; small steps beat many iterations",
            compare=({"substeps": 1, "iterations": 10}, {"substeps": 10, "iterations": 1})),
    )

    # ----- world --------------------------------------------------------------------------------
    @classmethod
    def step_work(cls, values) -> float:
        """Rod updates one step costs at most (all three rod sets on), see WORK_BUDGET."""
        rods, batches = sweep_size(values["rows"], values["cols"], SET_NAMES)
        return values["iterations"] * values["substeps"] * (rods + BATCH_COST * batches)

    @classmethod
    def check_combination(cls, values) -> None:
        # Every param is in range alone, but 256x256 x 100 iterations x 50 substeps would take
        # half a minute per step: refuse what a step cannot do in about 0.5 s.
        if values.get("kernel") == "numba" and not rods_compiled.available():
            raise ParamError(rods_compiled.why_not())
        work = cls.step_work(values)
        if work > WORK_BUDGET:
            r, c, it, sub = (values[k] for k in ("rows", "cols", "iterations", "substeps"))
            per_sweep = work / (it * sub)
            raise ParamError(
                f"rows x cols x iterations x substeps too large: a {r}x{c} cloth with {it} "
                f"iterations x {sub} substeps needs ~{_sci(work)} rod updates per step (all rod "
                f"sets); accepted: at most {_sci(WORK_BUDGET)} (about 0.5 s), here iterations x "
                f"substeps <= {int(WORK_BUDGET // per_sweep)}")

    def build(self) -> None:
        p = self.p
        rows, cols = p["rows"], p["cols"]
        w, h = self.world_size
        spacing = min(p["spacing"], 0.8 * w / (cols - 1), 0.7 * h / (rows - 1))
        origin = ((w - spacing * (cols - 1)) / 2, 0.28 * h)   # below the window's HUD box
        dtype = np.float32 if p["precision"] == "float32" else np.float64
        self.cloth = Cloth(rows, cols, spacing, origin, p["pins"], self.on, dtype)
        self.origin = origin
        self.cloth.world = (float(w), float(h))
        self.grab_radius = max(14.0, 1.2 * spacing)
        self.mouse: tuple[float, float] | None = None
        self._costs: dict[str, float] = {}
        self._cost_mark = (0, dict(self.cloth.spent))
        self._stretch: tuple[np.ndarray, np.ndarray] | None = None   # see stretches()
        self.build_contact((origin[0], origin[1], spacing * (cols - 1), spacing * (rows - 1)))
        self._sync()

    def _sync(self) -> None:
        """Hand the live-tunable params to the cloth (cheap: read on every substep)."""
        c, p = self.cloth, self.p
        c.iterations = p["iterations"]
        c.gravity = p["g"]
        c.drag = p["drag_coef"]
        c.wind_strength = p["wind_strength"]
        c.wind_field = p["wind_field"]
        c.tear_ratio = p["tear_ratio"]
        c.kernel = p["kernel"]
        self.sync_contact()

    def settings_changed(self, names: set[str]) -> None:
        self.cloth.set_effects(self.on)
        self.contact_settings_changed(names)

    def step(self, h: float) -> None:
        self._sync()
        if self.obstacles:
            self.move_obstacles(h)
        self.cloth.step(h)
        if "self_collision" in self.on:
            self.note_pressed()                 # (the HUD's "pressed into itself": cloth_contact)
        self._stretch = None

    def stretches(self) -> tuple[np.ndarray, np.ndarray]:
        """|length / rest - 1| of the horizontal and the vertical structural rods (torn ones
        included), for the metrics, the HUD and the drawing: computed at most once per change of
        the positions (a step, a mouse event or a restore forgets it)."""
        if self._stretch is None:
            horizontal, vertical = self.cloth.sets["structural"].families
            self._stretch = (self.cloth.stretch(horizontal), self.cloth.stretch(vertical))
        return self._stretch

    # ----- the mouse ----------------------------------------------------------------------------
    def handle_event(self, event: InputEvent) -> None:
        c = self.cloth
        self._stretch = self._contact_cache = None   # a grab, drop or unlock may move particles
        if event.kind.startswith("mouse"):
            self.mouse = c.clamp(event.pos)     # any finite double: kept within 1e5 px of the world
        if c.grabbed is None and self.contact_event(event):
            return                              # a press inside an obstacle drags the obstacle
        if event.kind == "mouse_down" and event.button == 1:
            cell = c.nearest(event.pos, self.grab_radius)
            if cell is not None:
                c.grab(cell, event.pos)
        elif event.kind == "mouse_move" and c.grabbed is not None:
            c.move_grab(event.pos)
        elif event.kind == "mouse_up" and event.button == 1 and c.grabbed is not None:
            c.release(event.pos)
        elif event.kind == "mouse_down" and event.button == 3 and c.grabbed is None:
            cell = c.nearest(event.pos, self.grab_radius, c.locked)
            if cell is not None:
                c.unlock(*cell)
        elif event.kind == "key_down" and event.key == UNLOCK_KEY:
            c.unlock_all()

    def arrows(self) -> Arrows:
        """A regular sample of the particles (edges included): position and the Verlet
        velocity (x - x_prev) / h of the last substep. No masses: the force arrow is the
        acceleration."""
        c = self.cloth
        ids = grid_sample(c.rows, c.cols)
        x = c.x.reshape(2, -1)[:, ids].T.astype(float)
        v = (c.x - c.x_prev).reshape(2, -1)[:, ids].T.astype(float) / \
            c.travelled_in(self.dt / self.p["substeps"])
        return Arrows(ids, x, v, None, sample_text(len(ids), c.rows * c.cols, "particle"))

    # ----- drawing ------------------------------------------------------------------------------
    def draw(self, surface, view) -> None:
        from app.draw.cloth_draw import draw_cloth
        from app.draw.obstacle_draw import draw_obstacles
        hover = active = None
        if self.mouse is not None and self.cloth.grabbed is None:
            active = self.dragged if self.dragged is not None else self.obstacle_at(self.mouse)
            if active is None:
                hover = self.cloth.nearest(self.mouse, self.grab_radius)
        draw_obstacles(surface, view, self.obstacles, active)
        draw_cloth(surface, view, self.cloth, hover, self.stretches())

    @property
    def color_key(self) -> tuple:
        """The strain colours, for the HUD's colour key (the HUD never covers the cloth)."""
        from app.draw.cloth_draw import strain_key
        return strain_key()

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The hanging cloth with room to swing and billow."""
        c = self.cloth
        cw, ch = c.spacing * (c.cols - 1), c.spacing * (c.rows - 1)
        ox, oy = self.origin
        return self.contact_bounds((ox - 0.3 * cw, oy - 0.1 * ch, 1.6 * cw, 1.35 * ch))

    # ----- reports ------------------------------------------------------------------------------
    def energies(self):
        """Energy bars: kinetic (mass 1 a particle, v = (x - x_prev)/h) and gravity's potential,
        both 0 at rest in the start pose; rigid rods store none, and their projection, drag and
        tearing take energy out."""
        from app.energy import Energies
        c = self.cloth
        h = c.travelled_in(self.dt / self.p["substeps"])    # the last substep's
        free = c.w > 0
        v = (c.x - c.x_prev) / h
        kinetic = 0.5 * float(np.sum(free * (v[0] * v[0] + v[1] * v[1])))
        gravity = (-c.gravity * float(np.sum(free * (c.x[1] - c.rest_x[1])))
                   if "gravity" in self.on else 0.0)
        return Energies((("kinetic", kinetic), ("gravity", gravity)), 0.0,
                        zero="the start pose, at rest (every particle of mass 1)",
                        losses="the rods' projection, drag, tearing, contacts and friction; the "
                               "mouse, the wind and a dragged obstacle put energy in",
                        unit="px^2/s^2")

    def metrics(self) -> dict[str, float]:
        c = self.cloth
        s = np.concatenate([st[f.alive > 0] for st, f in
                            zip(self.stretches(), c.sets["structural"].families)])
        return {
            "particles": c.rows * c.cols,
            "constraints": c.constraint_count(),
            "iterations": self.p["iterations"],
            "substeps": self.p["substeps"],
            "max_stretch": float(s.max()) if s.size else 0.0,
            "mean_stretch": float(s.mean()) if s.size else 0.0,
            "pinned_drift": c.pinned_drift(),
            "torn": c.torn_count(),
            "locked": int(np.count_nonzero(c.locked)),
            **self.contact_metrics(),
        }

    def effect_costs(self) -> dict[str, float]:
        """ms per step of each active effect (and of the structural rods and the Verlet step),
        averaged since the last call, lightly smoothed."""
        steps0, spent0 = self._cost_mark
        if self.steps > steps0:
            spent = self.cloth.spent
            n = self.steps - steps0
            for k in spent:
                now = (spent[k] - spent0.get(k, 0.0)) * 1000.0 / n
                self._costs[k] = now if k not in self._costs else 0.7 * self._costs[k] + 0.3 * now
            self._cost_mark = (self.steps, dict(spent))
        c = self.cloth
        running = {k for k, _ in c.before_sweeps + c.after_sweeps}   # contact: only with work
        shown = [k for k in FORCE_NAMES + SET_NAMES + ("tearing",) + CONTACT_NAMES
                 if (k in self.on and k not in CONTACT_NAMES) or k in running
                 or k == "structural"]
        return {k: self._costs.get(k, 0.0) for k in shown}

    def time_shares(self) -> dict[str, float]:
        """The physics time per step split into its parts (each effect's, the structural rods',
        the Verlet step's), as fractions that add up to 1 (empty before the first step)."""
        costs = {**self.effect_costs(), "verlet": self._costs.get("verlet", 0.0)}
        total = sum(costs.values())
        return {k: v / total for k, v in costs.items()} if total > 0 else {}

    def hud_lines(self) -> list[str]:
        """What a class reads every frame: the sweeps a step buys and the stretch they leave."""
        m = self.metrics()
        it, sub = self.p["iterations"], self.p["substeps"]
        torn = f"  |  {m['torn']} rods torn" if m["torn"] else ""
        kernel = ""
        if self.p["kernel"] == "numba":     # (self-collision's grid pass is compiled too)
            both = "self_collision" in self.on and self.p["self_method"] == "grid"
            kernel = ", numba kernel (rods, self-collision)" if both else ", numba kernel"
        return [f"{it} iterations x {sub} substeps = {it * sub} sweeps/step{kernel}",
                f"stretch: mean {self.shown('mean_stretch', m['mean_stretch'])}  max "
                f"{self.shown('max_stretch', m['max_stretch'])}{torn}"] + self.contact_hud(m)

    def hud_details(self) -> list[str]:
        c, m = self.cloth, self.metrics()
        sets = "+".join(rs.name for rs in c.active_sets)
        shares = sorted(self.time_shares().items(), key=lambda kv: -kv[1])
        # the three largest parts, the others summed (one line on the projector)
        parts = [f"{k} {100 * v:.0f}%" for k, v in shares[:3]]
        if len(shares) > 3:
            parts.append(f"rest {100 * sum(v for _, v in shares[3:]):.0f}%")
        split = ", ".join(parts) or "-"
        drag = "  |  LMB in an obstacle: drag it" if self.obstacles else ""
        return [
            f"LMB: move+lock  |  RMB: unlock  |  U: unlock all{drag}",
            f"{c.rows}x{c.cols} particles, {m['constraints']} rods ({sets})",
            f"physics time: {split}",
        ]

    # ----- state --------------------------------------------------------------------------------
    def state_arrays(self):
        return self.cloth.state_arrays() + [self.obstacle_state()]

    def snapshot(self):
        return {"cloth": self.cloth.snapshot(), **self.contact_snapshot()}

    def restore(self, snap) -> None:
        if snap is None:
            self.reset()
        else:
            self.cloth.restore(snap["cloth"])
            self.contact_restore(snap)
            self._stretch = None
