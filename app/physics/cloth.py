"""Verlet cloth: Jakobsen's rods relaxed by local iteration, written with NumPy arrays.

The lecture's cloth (Jakobsen, "Advanced Character Physics", GDC 2001) in three ideas:

1. **The velocity-less Verlet step.** Each particle stores its position x and its previous position
   x_prev; (x - x_prev) is the distance travelled in the last step, i.e. the velocity times h:

       x' = x + (x - x_prev) * (1 - drag) + a * h^2          (drag 0.01 is "2 becomes 1.99")

   then x_prev takes x's place. With two arrays that is a pointer swap, as the slide says.
   x - x_prev is the velocity times the h it was travelled in: where h changes (substeps or
   hertz set live) it is scaled by h / h_prev first, so the velocity carries over (without
   it, a falling cloth set from 1 substep to 4 fell 4 times as fast, and 4 set to 1 a quarter
   as fast), and in that one step each acceleration adds a h (h + h_prev) / 2, not a h^2: the
   step exact for a constant a (with a h^2 alone a falling cloth's speed was off by
   g (h_prev - h) / 2 from then on, 6 px/s of 297 for 1 -> 4 substeps: tests/test_cloth.py).
   `drag` is the fraction of velocity lost per 1/60 s (the slide's step at 60 fps). A substep of
   h seconds applies the same loss per second, (1 - drag) ** (h * 60): otherwise the damping would
   grow with hertz x substeps (at drag 0.01, 50 substeps at 60 Hz would keep 8e-14 of the velocity
   per second instead of 0.55, and more substeps would buy honey, not accuracy).
2. **Rods, not springs.** Each pair of neighbours is a distance constraint |x_b - x_a| = rest.
   One constraint is satisfied by moving both ends along their difference, each by its share of
   the error, w_a / (w_a + w_b) with w = 1/mass (w = 0: pinned, it never moves).
3. **Local iteration.** Satisfying one rod breaks its neighbours, so all rods are swept again and
   again: `iterations` sweeps per substep. More sweeps -> less stretch, at a price in time.

Rods come in three sets, like the mass-spring cloth's springs: structural (grid neighbours,
always on), shear (the diagonals) and bending (skip one particle). Forces: gravity, drag, wind
(the table FORCES). Tearing: a rod stretched beyond `tear_ratio` times its rest length breaks. A
set switched on mid-run eases its rods in from their current lengths (set_effects), so switching
an effect on never tears the cloth by itself. What each part of a step costs is measured around
the formulas by a Stopwatch (app/physics/timing.py), not inside them.

How NumPy makes it fast: the rods are grouped into batches of strided slices
(app/physics/rods.py).

Positions are float32 by default: half the memory traffic of float64, so about twice the speed,
and a relative precision of 1e-7, far below anything the stretch metric or the eye can see.
(Only at extreme sub-stepping, hertz * substeps in the thousands, does a*h^2 fall below float32's
resolution of a position; use float64 there.)
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from app.physics.bounds import REACH, clamp_point
from app.physics.cloth_contact import ContactState, contact_passes
from app.physics.grid_shared import nearest_cell, wind_field
from app.physics.rods import SET_NAMES, Family, RodSet, rod_lengths, rod_sets, solve_batch
from app.physics.timing import Stopwatch

FORCE_NAMES = ("drag", "gravity", "wind")       # force effects, in the order they apply (FORCES)

# The defaults of the settings a Cloth reads every step; the cloth scene's parameters start from
# these (one source). GRAVITY: 980 px/s^2 is 9.8 m/s^2 at 100 px per metre; the pymunk scenes use
# 900, the pymunk tutorial's gravity (0, 900): the same earth, two conventions of scale.
ITERATIONS = 10
GRAVITY = 980.0
DRAG = 0.01            # fraction of velocity lost per 1/60 s: the slide's "2 becomes 1.99"
WIND_STRENGTH = 600.0  # px/s^2
TEAR_RATIO = 2.5       # a rod breaks beyond this times its rest length
EASE_TIME = 1.0        # s: a rod set switched on mid-run reaches its rest lengths (set_effects)
PIN_CHOICES = ("top", "corners", "none")
WIND_FIELDS = ("gust", "lecture")



# ----- the cloth --------------------------------------------------------------------------------
class Cloth:
    """A rows x cols grid of particles joined by rods; see the module docstring.

    Settings read on every step (change them freely between steps): iterations, gravity (px/s^2,
    downwards), drag (0..1, the fraction of velocity lost per 1/60 s, whatever the substep),
    wind_strength (px/s^2),
    wind_field, tear_ratio. The effects that are on are chosen with set_effects()."""

    def __init__(self, rows: int, cols: int, spacing: float, origin: tuple[float, float] = (0, 0),
                 pins: str = "top", effects: set[str] | frozenset[str] = frozenset(SET_NAMES[:1]),
                 dtype: type = np.float32):
        if rows < 2 or cols < 2:
            raise ValueError("a cloth needs at least 2 x 2 particles")
        if pins not in PIN_CHOICES:
            raise ValueError(f"pins must be one of {PIN_CHOICES}")
        self.rows, self.cols, self.spacing, self.dtype = rows, cols, float(spacing), dtype
        self.iterations = ITERATIONS
        self.gravity = GRAVITY
        self.drag = DRAG
        self.wind_strength = WIND_STRENGTH
        self.wind_field = "gust"
        self.tear_ratio = TEAR_RATIO
        self.t = 0.0
        self.world = (960.0, 720.0)             # the wind field is scaled to this area

        rr, cc = np.mgrid[0:rows, 0:cols]
        self.rest_x = np.stack([origin[0] + cc * spacing, origin[1] + rr * spacing]).astype(dtype)
        self.x = self.rest_x.copy()             # positions, shape (2, rows, cols)
        self.x_prev = self.x.copy()             # positions one substep ago
        self.v = np.empty_like(self.x)          # work buffer: x - x_prev (velocity * h)
        self.h_prev: float | None = None        # the substep x - x_prev was travelled in
        self.w = np.ones((rows, cols), dtype)   # inverse masses; 0 = pinned (locked or grabbed)
        self.free = np.ones((rows, cols), dtype)  # 1 where a particle may move
        self.locked = np.zeros((rows, cols), bool)
        self.anchor = self.x.copy()             # where each locked particle was locked
        self.grabbed: tuple[int, int] | None = None
        self.grab_target = (0.0, 0.0)
        self.default_pins = self._pin_cells(pins)

        self.sets = rod_sets(rows, cols, spacing, dtype)
        for rs in self.sets.values():
            for fam in rs.families:
                for bt in fam.batches:
                    shape = bt.alive.shape
                    bt.d = np.empty((2,) + shape, dtype)
                    bt.t = np.empty((2,) + shape, dtype)
                    bt.length = np.empty(shape, dtype)
                    bt.ka = np.empty(shape, dtype)
                    bt.kb = np.empty(shape, dtype)
        self.kernel = "numpy"                   # or "numba": rods_compiled (an option)
        self._weights_version = 0               # counts weight changes (the kernel re-reads)
        self.timed = Stopwatch()                # what each part of the step costs (wall s)
        self.spent = self.timed.spent
        self.active_sets: list[RodSet] = []
        self.tearing = False
        self.ease_end = -math.inf                # rods switched on mid-run ease in until then
        self.contact = ContactState()           # obstacles and self-collision (cloth_contact.py)
        self.lock_cells(self.default_pins)
        self.set_effects(set(effects))

    # ----- set-up -------------------------------------------------------------------------------
    def _pin_cells(self, pins: str) -> list[tuple[int, int]]:
        if pins == "top":
            return [(0, c) for c in range(self.cols)]
        if pins == "corners":
            return [(0, 0), (0, self.cols - 1)]
        return []

    def set_effects(self, on: set[str]) -> None:
        """Choose what the step computes: only the rod sets and forces named in `on` (structural
        rods are always solved). What is off is not in these lists, so it costs nothing.

        Switching a rod set on never tears the cloth by itself. Rods that came on at their full
        rest length on a deformed cloth (shear on a cloth the wind has sheared, folded cells
        with diagonals near 0) would yank its particles in the next sweeps, hard enough to tear
        their neighbours (769 rods at once, once). So a set switched on mid-run starts with each
        rod's rest length at its current length, and these ease linearly to the true rest
        length over EASE_TIME simulated seconds (ease_rest_lengths): the cloth is pulled back
        into shape, not snapped. At build every rod is at rest anyway."""
        before = {rs.name for rs in self.active_sets}
        self.on = set(on)
        self.active_sets = [self.sets[n] for n in SET_NAMES
                            if n == "structural" or n in self.on]
        self.forces: list[tuple[str, Force]] = [(n, FORCES[n]) for n in FORCE_NAMES
                                                if n in self.on]
        self.tearing = "tearing" in self.on
        if before:                                      # mid-run (not at build)
            for rs in self.active_sets:
                if rs.name not in before:
                    for fam in rs.families:
                        fam.rest_now = rod_lengths(self.x, fam).astype(self.dtype)
                    self.ease_end = self.t + EASE_TIME
        self._make_plan()
        self._make_contact_plan()

    def set_obstacles(self, obstacles: list) -> None:
        """The obstacles the `collisions` effect keeps the cloth out of (app/physics/obstacles.py)."""
        self.contact.obstacles = list(obstacles)
        self._make_contact_plan()

    def _make_contact_plan(self) -> None:
        """The contact passes before and after the sweeps: only those of the effects that are on
        (app/physics/cloth_contact.py); none at all without contact effects."""
        self.before_sweeps, self.after_sweeps = contact_passes(self.on, self.contact.obstacles)

    def _make_plan(self) -> None:
        """The sweep's plan: every batch of every active set, with its rest length(s)."""
        self._plan = [(rs, [(bt, fam.rest_of(bt.cells)) for fam in rs.families
                            for bt in fam.batches]) for rs in self.active_sets]
        self._compiled: tuple[int, object] | None = None    # (weights version, CompiledPlan)

    def ease_rest_lengths(self, h: float) -> None:
        """Move the easing rods' rest lengths a step h closer to their true rest length, linearly,
        arriving at ease_end; then drop the per-rod values (the plain scalar rest again)."""
        frac = min(1.0, h / (self.ease_end - self.t)) if self.ease_end > self.t else 1.0
        easing = [f for rs in self.sets.values() for f in rs.families if f.rest_now is not None]
        for fam in easing:
            fam.rest_now += (fam.rest - fam.rest_now) * frac
            if frac >= 1.0:
                fam.rest_now = None
        if frac >= 1.0:
            self.ease_end = -math.inf
            self._make_plan()

    def update_weights(self) -> None:
        """Recompute every batch's correction shares from w and alive (after pins, grabs or tears).
        w_a/(w_a+w_b), with 0 where both ends are pinned (0/0)."""
        self.free = (self.w > 0).astype(self.dtype)
        for rs in self.sets.values():
            for fam in rs.families:
                self._update_family(fam)

    def _update_family(self, fam: Family) -> None:
        self._weights_version += 1
        for bt in fam.batches:
            wa, wb = self.w[bt.a], self.w[bt.b]
            total = wa + wb
            safe = np.where(total > 0, total, 1)
            np.multiply(np.where(total > 0, wa / safe, 0), bt.alive, out=bt.ka)
            np.multiply(np.where(total > 0, wb / safe, 0), bt.alive, out=bt.kb)

    # ----- pins and the mouse -------------------------------------------------------------------
    def lock_cells(self, cells: list[tuple[int, int]], at: np.ndarray | None = None) -> None:
        """Lock particles (inverse mass 0) where they are, or at the positions `at` (2, n)."""
        for k, (r, c) in enumerate(cells):
            if at is not None:
                self.x[:, r, c] = at[:, k]
            self.x_prev[:, r, c] = self.x[:, r, c]
            self.anchor[:, r, c] = self.x[:, r, c]
            self.locked[r, c] = True
            self.w[r, c] = 0
        self.update_weights()

    def unlock(self, r: int, c: int) -> None:
        """Give a locked particle its mass back."""
        self.locked[r, c] = False
        self.w[r, c] = 1
        self.update_weights()

    def unlock_all(self) -> None:
        """Free every particle (and drop a grab), then restore the default pins where they
        started."""
        self.grabbed = None
        self.locked[:] = False
        self.w[:] = 1
        cells = self.default_pins
        at = np.array([self.rest_x[:, r, c] for r, c in cells]).T if cells else None
        self.lock_cells(cells, at)

    def clamp(self, pos: tuple[float, float]) -> tuple[float, float]:
        """pos moved into the box REACH px around the world (NaN counts as 0).

        The mouse may report any finite double (1e39, -1e300); a grabbed particle follows it only
        this far, so positions stay far inside float32's range and rod lengths squared (up to
        ~1e11) cannot overflow: the cloth is stretched, never torn to inf or NaN."""
        return clamp_point(pos, self.world, REACH)

    def nearest(self, pos: tuple[float, float], radius: float,
                mask: np.ndarray | None = None) -> tuple[int, int] | None:
        """The particle nearest to pos within radius (among `mask` if given), or None."""
        return nearest_cell(self.x, self.clamp(pos), radius, mask)

    def grab(self, cell: tuple[int, int], pos: tuple[float, float]) -> None:
        """Start dragging a particle: it follows grab_target and nothing else moves it."""
        self.release()
        r, c = cell
        self.grabbed = cell
        self.grab_target = self.clamp(pos)
        self.locked[r, c] = False
        self.w[r, c] = 0
        self.update_weights()

    def move_grab(self, pos: tuple[float, float]) -> None:
        """Move the grab target to pos (kept within REACH px of the world: see clamp)."""
        self.grab_target = self.clamp(pos)

    def release(self, pos: tuple[float, float] | None = None) -> None:
        """Drop the grabbed particle: it stays locked where it was dropped (the seed's 'move+lock')."""
        if self.grabbed is None:
            return
        r, c = self.grabbed
        self.grabbed = None
        at = None if pos is None else np.array([[v] for v in self.clamp(pos)], self.dtype)
        self.lock_cells([(r, c)], at)

    def _follow_mouse(self) -> None:
        r, c = self.grabbed
        self.x[:, r, c] = self.grab_target
        self.x_prev[:, r, c] = self.grab_target

    # ----- the step -----------------------------------------------------------------------------
    def step(self, h: float) -> None:
        """One substep of h seconds: the Verlet step x' = x + (x - x_prev) + a h^2 (each force
        adds its a h^2 to v = x - x_prev, drag scales v), the mouse, tearing, then `iterations`
        sweeps. `timed` only measures what each part costs, around the formulas."""
        timed = self.timed
        v = np.subtract(self.x, self.x_prev, out=self.v)     # x - x_prev = velocity * h
        h_prev = self.h_prev
        changed = bool(h_prev) and h != h_prev  # (substeps or hertz set live: module docstring)
        if changed:
            v *= h / h_prev                     # the same velocity over the new h
        self.h_prev = h
        for name, force in self.forces:
            with timed(name):
                force(self, v, h)
        if changed:
            self._first_after_change(v, h, h_prev)
        with timed("verlet"):
            v *= self.free                                   # pinned and grabbed: no motion
            np.add(self.x, v, out=self.x_prev)               # x' = x + (x - x_prev)(..) + a h^2
            self.x, self.x_prev = self.x_prev, self.x        # swap: the old x becomes x_prev
            if self.grabbed is not None:
                self._follow_mouse()
        for name, run in self.before_sweeps:                 # collisions, friction
            with timed(name):
                run(self, h)
        if self.tearing:
            with timed("tearing"):
                self.tear()
        self.relax(self.iterations)
        for name, run in self.after_sweeps:                  # self-collision, collisions, friction
            with timed(name):
                run(self, h)
        if self.ease_end > -math.inf:
            self.ease_rest_lengths(h)
        self.t += h

    def _first_after_change(self, v: np.ndarray, h: float, h_prev: float) -> None:
        """The first step after h changed: each acceleration's a h^2 (drag is none) becomes
        a h (h + h_prev) / 2, so that x' = x + (x - x_prev) h / h_prev + a h (h + h_prev) / 2,
        the step that is exact for a constant a (time-corrected Verlet)."""
        extra = np.zeros_like(v)
        for name, force in self.forces:
            if name != "drag":
                force(self, extra, h)           # a h^2 of each acceleration, alone
        v += extra * ((h_prev - h) / (2 * h))

    def relax(self, iterations: int) -> None:
        """`iterations` Gauss-Seidel sweeps over every active rod set, batch after batch."""
        x, timed = self.x, self.timed
        if self.kernel == "numba" and self.ease_end == -math.inf:   # (easing: per-rod rests)
            with timed("rods (numba)"):
                self.compiled_plan().relax(x, iterations)
            for rs, _ in self._plan:
                rs.sweeps += iterations
            return
        for _ in range(iterations):
            for rs, batches in self._plan:
                with timed(rs.name):
                    for bt, rest in batches:
                        solve_batch(x, bt, rest)
        for rs, _ in self._plan:
            rs.sweeps += iterations

    def compiled_plan(self):
        """The plan packed for the numba kernel (app/physics/rods_compiled.py), its weights
        refreshed after any change."""
        from app.physics.rods_compiled import CompiledPlan
        if self._compiled is None:
            plan = [pair for _, batches in self._plan for pair in batches]
            self._compiled = (self._weights_version, CompiledPlan(plan, self.dtype))
        version, packed = self._compiled
        if version != self._weights_version:
            packed.refresh()
            self._compiled = (self._weights_version, packed)
        return packed

    def tear(self) -> int:
        """Break every rod of the active sets stretched beyond tear_ratio x rest; return how many
        broke. A rod is broken by zeroing its `alive` entry (and its correction shares)."""
        broke = 0
        for rs in self.active_sets:
            for fam in rs.families:
                # an easing rod may start far shorter than its rest (a folded cell's diagonal):
                # it tears only beyond tear_ratio x the longer of the two
                rest = fam.rest if fam.rest_now is None else np.maximum(fam.rest_now, fam.rest)
                too_long = (rod_lengths(self.x, fam) > self.tear_ratio * rest) & (fam.alive > 0)
                n = int(np.count_nonzero(too_long))
                if n:
                    fam.alive[too_long] = 0
                    self._update_family(fam)
                    broke += n
        return broke

    # ----- what the scene reports ---------------------------------------------------------------
    def stretch(self, family: Family) -> np.ndarray:
        """|length / rest - 1| of every rod of a family (torn rods included)."""
        return np.abs(rod_lengths(self.x, family) / family.rest - 1.0)

    def constraint_count(self) -> int:
        """Intact rods in the active sets (what a sweep solves)."""
        return sum(int(np.count_nonzero(f.alive)) for rs in self.active_sets for f in rs.families)

    def torn_count(self) -> int:
        return sum(int(f.alive.size - np.count_nonzero(f.alive))
                   for rs in self.sets.values() for f in rs.families)

    def pinned_drift(self) -> float:
        """Largest distance a locked particle has moved from where it was locked."""
        if not self.locked.any():
            return 0.0
        d = self.x[:, self.locked] - self.anchor[:, self.locked]
        return float(np.sqrt((d.astype(np.float64) ** 2).sum(0)).max())

    def travelled_in(self, h: float) -> float:
        """The substep x - x_prev was travelled in: the last step's (h_prev), h before any."""
        return self.h_prev or h

    def state_arrays(self) -> list[np.ndarray]:
        return [self.x, self.x_prev, self.w] + [f.alive for rs in self.sets.values()
                                                 for f in rs.families]

    def snapshot(self) -> dict:
        """Copies of everything that changes while running."""
        return {"x": self.x.copy(), "x_prev": self.x_prev.copy(), "w": self.w.copy(),
                "locked": self.locked.copy(), "anchor": self.anchor.copy(), "t": self.t,
                "grabbed": self.grabbed, "grab_target": self.grab_target,
                "ease_end": self.ease_end, "h_prev": self.h_prev,
                "rest_now": [None if f.rest_now is None else f.rest_now.copy()
                             for rs in self.sets.values() for f in rs.families],
                "alive": [f.alive.copy() for rs in self.sets.values() for f in rs.families]}

    def restore(self, snap: dict) -> None:
        self.x[...] = snap["x"]
        self.x_prev[...] = snap["x_prev"]
        self.w[...] = snap["w"]
        self.locked[...] = snap["locked"]
        self.anchor[...] = snap["anchor"]
        self.t = snap["t"]
        self.grabbed, self.grab_target = snap["grabbed"], snap["grab_target"]
        fams = [f for rs in self.sets.values() for f in rs.families]
        self.ease_end = snap["ease_end"]
        self.h_prev = snap.get("h_prev")
        for f, a, rest_now in zip(fams, snap["alive"], snap["rest_now"]):
            f.alive[...] = a
            f.rest_now = None if rest_now is None else rest_now.copy()
        self._make_plan()
        self.update_weights()


# ----- forces: each adds its a*h^2 to v = x - x_prev (drag scales v); only the active ones run ----
Force = Callable[[Cloth, np.ndarray, float], None]


def drag(c: Cloth, v: np.ndarray, h: float) -> None:
    v *= (1.0 - c.drag) ** (h * 60.0)                   # "2 -> 1.99" per 1/60 s, for any h


def gravity(c: Cloth, v: np.ndarray, h: float) -> None:
    v[1] += c.gravity * h * h                           # a h^2, a = (0, +g): y points down


def wind(c: Cloth, v: np.ndarray, h: float) -> None:
    ax, ay = wind_field(c.wind_field, c.x[0], c.x[1], c.t, c.world)
    s = c.wind_strength * h * h
    v[0] += s * ax
    v[1] += s * ay


# The force effects by name, in FORCE_NAMES order: the explicit table set_effects picks from.
FORCES: dict[str, Force] = {"drag": drag, "gravity": gravity, "wind": wind}
