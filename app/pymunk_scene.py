"""What every pymunk scene shares: the space, stepping, dragging bodies with the mouse, the state
for hashing and the non-finite guard, and snapshots for rollback.

A pymunk scene subclasses PymunkScene and fills the space in `build_space()`:

    class Balls(PymunkScene):
        name = "balls"
        def build_space(self, space: pymunk.Space) -> None:
            ...add bodies, shapes and joints...

Dragging (the usual pymunk pattern): the mouse holds a kinematic body; pressing the left button on
a dynamic body joins the two with a PivotJoint whose force is bounded (`max_force`), so a dragged
body pushes others and is held by its joints instead of teleporting through them.

Reading many bodies at once: `body_rows(fields)` returns the body ids and the requested fields of
every body in ONE pymunk.batch call. The batch lists sleeping bodies too (Chipmunk's
cpSpaceEachBody walks the awake bodies, then the static ones, then the sleeping groups), so
`sleeping_rows(ids)` tells which rows sleep from that order alone, with no call per body. The base
adds one shapeless static "marker" body to every space, so that order always has a static part.

pymunk (Chipmunk2D) aborts the whole process on some bad values (iterations=0, negative damping) and
silently accepts others (a NaN time step). Every setting that reaches pymunk here comes from a
declared Param, whose range keeps such values out; mouse positions come from events, which the
shell checks finite (an --input file's positions on reading; the window's are screen pixels),
and which handle_event pulls within REACH (1e5 px) of the world as the cloth does
(app/physics/bounds.py): a body dragged towards (1.797e308, 0) once drove the space to NaN.
"""

from __future__ import annotations

import copy
import functools
import math
import operator
import struct
from dataclasses import replace
from typing import Any, Callable, Iterable, Sequence

import numpy as np
import pymunk
import pymunk.batch

from app.draw.pymunk_draw import draw_pivot_joint
from app.physics.bounds import clamp_point
from app.pymunk_reader import _STATE_FIELDS, _StateReader, _ffi, _lib
from app.scene import Effect, InputEvent, Param, Scene
from app.vectors import Arrows, sample_every, sample_text

_ROW = struct.Struct("6d")          # one of those rows: (x, y, angle, vx, vy, w), float64s
FEW_NUMBERS = 96                    # is_finite: a state of up to this many numbers (16
                                    # bodies) is measured without a BLAS call (_numbers)
_ANY = pymunk.ShapeFilter()         # place_taken's filter (every shape), and its C answer
_NEAREST = _ffi.new("cpPointQueryInfo *") if _ffi is not None else None


def _rows_getter(rows: list[int]) -> Callable[[tuple], tuple]:
    """A function that takes these rows (six numbers each) out of the rows' numbers as one flat
    tuple, as a tuple of rows: an itemgetter of their slices (for one row or none, itemgetter
    alone would return the row itself, or cannot be made)."""
    if len(rows) >= 2:
        return operator.itemgetter(*(slice(6 * i, 6 * i + 6) for i in rows))
    if rows:
        i = rows[0]
        return lambda numbers: (numbers[6 * i:6 * i + 6],)
    return lambda numbers: ()


@functools.cache
def _numbers(n: int) -> struct.Struct:
    """The struct that unpacks n float64s (made once for each n)."""
    return struct.Struct(f"{n}d")


# The same names as the cloth's: the number is the param `g`, the on/off switch the effect `gravity`
# (so `--scene all --set g=...` means one thing everywhere).
PYMUNK_PARAMS: tuple[Param, ...] = (
    Param("g", 900.0, float, 0.0, 5000.0, help="gravity, px/s^2 (downwards)", rebuild=False),
    Param("iterations", 10, int, 1, 200, help="pymunk solver iterations per step", rebuild=False),
)
PYMUNK_EFFECTS: tuple[Effect, ...] = (
    Effect("gravity", True, "gravity pulls every body down (off: space.gravity is (0, 0))",
           amount="g"),
)


class PymunkScene(Scene):
    """Base of the pymunk scenes. Subclasses add their own params to PYMUNK_PARAMS and their own
    effects to PYMUNK_EFFECTS."""

    params = PYMUNK_PARAMS
    effects = PYMUNK_EFFECTS
    world_keys: tuple[str, ...] = ("space",)   # attributes that hold world state (for snapshots)
    drag_force: float = 50000.0                 # bound on the mouse joint's force, N (px units)

    def build(self) -> None:
        self.space = pymunk.Space()
        self.space.iterations = self.p["iterations"]
        self.space.gravity = (0.0, self.gravity())
        self.wake()
        self.mouse_body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        self.mouse_joint: pymunk.PivotJoint | None = None
        self._buffer = pymunk.batch.Buffer()
        self._state_reader = _StateReader()
        self._rows = None           # the state read since the last step (state_rows)
        self.finite_read = -1       # the reader's read the scene's own checks found finite
        self.finite_kept = -1       # one after which only bodies found finite came or went
        self._rows_of = None        # (bodies, batch ids as bytes, _rows_at's answer: where their
                                    # rows are) for rows_of and rows_list
        # A static body without shapes: it costs nothing and guarantees the batch's row order
        # (awake | static | sleeping) has a static part to split at (see sleeping_rows).
        self.space.add(pymunk.Body(body_type=pymunk.Body.STATIC))
        self.build_space(self.space)
        self.refresh_static_ids()
        self.apply_settings()

    def build_space(self, space: pymunk.Space) -> None:
        """Add the scene's bodies, shapes and joints."""

    def step(self, h: float) -> None:
        # The space's settings are given to it when they change (settings_changed, restore), not
        # here: a step is the engine's step and nothing else.
        self.space.step(h)
        self._rows = None

    def advance(self) -> None:
        """Scene.advance; a scene whose step is the engine's own calls space.step directly, with
        no call of step() for each substep (a cradle takes 30 substeps a step)."""
        if type(self).step is not PymunkScene.step:
            Scene.advance(self)          # (named, not super(): a step of a few us pays for it)
            return
        n = self.p["substeps"]
        dt = self.dt
        h = dt / n
        step = self.space.step
        for _ in range(n):
            step(h)
        self._rows = None
        self.time += dt
        self.steps += 1
        self.after_step()

    def apply_settings(self) -> None:
        """Give the space the settings in use (called on build's end, on a change from the panel
        and after a restore; subclasses add their own, e.g. damping)."""
        if self.space.iterations != self.p["iterations"]:
            self.space.iterations = self.p["iterations"]
        self.sync_gravity()

    # ----- a world at rest --------------------------------------------------------------------
    # `resting` is True once a read found every body of the space asleep (a settled pile). Then
    # nothing moves until something wakes a body, and only the lab can: a sleeping body is woken
    # by an awake one (there is none), or by a change made to the space (adding or removing a
    # body, the mouse joint, a new gravity or setting, a restore), and every such change here
    # goes through wake(). While resting, a scene's step reads and tests nothing (its cost is
    # the engine's own). Code that changes a body directly (a test's kick) calls wake() too.
    def wake(self) -> None:
        """Forget that the world was at rest: the next step reads the bodies again."""
        self.resting = False
        self._finite_at_rest: bool | None = None
        self._rows = None

    # ----- gravity ----------------------------------------------------------------------------
    def gravity(self) -> float:
        """The downward acceleration in use, px/s^2: the param g, or 0 with the effect off."""
        return self.p["g"] if "gravity" in self.on else 0.0

    def sync_gravity(self) -> None:
        """Give the space the gravity in use, if it changed (g or the effect, from the panel, or a
        restored snapshot), and tell the scene (gravity_changed)."""
        g = self.gravity()
        if self.space.gravity.y != g:
            # only on a change: setting gravity wakes every sleeping body (Chipmunk)
            self.space.gravity = (0.0, g)
            self.gravity_changed()

    def gravity_changed(self) -> None:
        """Called when the gravity in use changed: re-baseline anything measured against the old
        one (an energy at release: its potential part depends on g)."""

    def settings_changed(self, names: set[str]) -> None:
        self.wake()
        self.apply_settings()    # if g or gravity changed: now, so metrics read before the next
                                 # step are right

    # ----- mouse --------------------------------------------------------------------------
    def handle_event(self, event: InputEvent) -> None:
        self.wake()              # a drag or a click may wake a body (or add one)
        if event.kind.startswith("mouse"):
            event = replace(event, pos=clamp_point(event.pos, self.world_size))
        if event.kind == "mouse_move":
            self.mouse_body.position = event.pos
        elif event.kind == "mouse_down" and event.button == 1:
            self.mouse_body.position = event.pos
            if not self.grab(event.pos):
                self.on_click(event.pos, event.button)
        elif event.kind == "mouse_down":
            self.on_click(event.pos, event.button)
        elif event.kind == "mouse_up" and event.button == 1:
            self.release()

    def grab(self, pos: tuple[float, float]) -> bool:
        """Join the dynamic body under `pos` (within 5 px) to the mouse; True if one was found."""
        self.release()
        hit = self.space.point_query_nearest(pos, 5.0, pymunk.ShapeFilter())
        if hit is None or hit.shape is None or hit.shape.body.body_type != pymunk.Body.DYNAMIC:
            return False
        body = hit.shape.body
        # Grab at the nearest point on the shape, so a touch at the rim does not jerk the body.
        anchor = hit.point if hit.distance > 0 else pos
        self.mouse_joint = pymunk.PivotJoint(self.mouse_body, body, (0, 0),
                                             body.world_to_local(anchor))
        self.mouse_joint.max_force = self.drag_force
        self.mouse_joint.error_bias = (1 - 0.15) ** 60
        self.space.add(self.mouse_joint)
        return True

    def place_taken(self, point: tuple[float, float], r: float) -> bool:
        """Whether a shape lies within r of point: space.point_query(point, r, ShapeFilter())
        not empty, asked as Chipmunk's nearest-point query (one C call, no list: 2.35 -> 0.43 us
        alone; falling_balls' long run 256.8k -> 256.2k instructions a step; the same answer for
        15,000 random points and radii in a running falling_balls, 2,422 taken; the test too)."""
        if _lib is None:
            return bool(self.space.point_query(point, r, _ANY))
        return _lib.cpSpacePointQueryNearest(self.space._space, point, r, _ANY, _NEAREST) \
            != _ffi.NULL

    def release(self) -> None:
        """Let go of the body held by the mouse, if any (then the dropped() hook runs)."""
        if self._detach_mouse():
            self.dropped()

    def _detach_mouse(self) -> bool:
        """Take the mouse joint out of the space without telling the scene (a rollback throws
        the held state away: it is no release to measure from). True if a body was held."""
        if self.mouse_joint is None:
            return False
        if self.mouse_joint in self.space.constraints:
            self.space.remove(self.mouse_joint)
        self.mouse_joint = None
        return True

    def dropped(self) -> None:
        """A dragged body was let go (e.g. re-arm a measurement from the state the hand left)."""

    def on_click(self, pos: tuple[float, float], button: int) -> None:
        """A click that grabbed nothing (e.g. drop a ball there)."""

    # ----- reading many bodies at once --------------------------------------------------------
    def refresh_static_ids(self) -> None:
        """Remember the ids of the space's static bodies (called after build_space and restore;
        call it again if a scene adds static bodies later)."""
        ids = [b.id for b in self.space.bodies if b.body_type == pymunk.Body.STATIC]
        self._static_ids = np.array(sorted(ids + [self.space.static_body.id]), dtype=np.int64)
        self._static_set = frozenset(self._static_ids.tolist())

    def body_rows(self, fields: pymunk.batch.BodyFields) -> tuple[np.ndarray, np.ndarray]:
        """(ids, data) of every body in the space (awake, static and sleeping), in one batch call:
        ids (n,) int64 body ids, data (n, k) float64 with the fields in pymunk's order (position
        x y, angle, velocity x y, angular velocity, force x y, torque; those asked for)."""
        self._buffer.clear()
        pymunk.batch.get_space_bodies(self.space, fields | pymunk.batch.BodyFields.BODY_ID,
                                      self._buffer)
        ids = np.frombuffer(self._buffer.int_buf(), dtype=np.int64).copy()
        data = np.frombuffer(self._buffer.float_buf(), dtype=np.float64)
        return ids, data.reshape(len(ids), -1).copy()

    def read_rows(self, fields: pymunk.batch.BodyFields) -> tuple[np.ndarray, np.ndarray]:
        """Like body_rows, without copying: (ids, data) are views of the batch buffer, good
        until the next read. `fields` must include BODY_ID."""
        self._buffer.clear()
        pymunk.batch.get_space_bodies(self.space, fields, self._buffer)
        ids = np.frombuffer(self._buffer.int_buf(), dtype=np.int64)
        return ids, np.frombuffer(self._buffer.float_buf(), dtype=np.float64).reshape(len(ids), -1)

    def state_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """(ids, rows) of every body in the batch's order, rows (n, 6) = (x, y, angle, vx, vy,
        w): read in one batch call at most once between two steps (the scene's own checks after
        a step and the runner's is_finite share it). Views of a buffer of their own, good until
        the next step or wake(); a scene that steps the space itself sets self._rows = None."""
        rows = self._rows
        if rows is None:
            rows = self._rows = self._state_reader.read(self.space)
        return rows

    def rows_of(self, bodies: list[pymunk.Body]) -> np.ndarray:
        """The state_rows of these bodies, in their order: (n, 6) = (x, y, angle, vx, vy, w)
        each (a copy). Where each one's row is, is kept while the batch lists the same bodies in
        the same order (a scene without sleeping: always)."""
        at = self._rows_at(bodies)
        if at is None:
            # a body that is not in the space (a student's builder may forget to add one):
            # read from each body, as the batch would if it were there
            return np.array([(*b.position, b.angle, *b.velocity, b.angular_velocity)
                             for b in bodies], dtype=np.float64).reshape(-1, 6)
        return self.state_rows()[1][at[0]]

    def rows_list(self, bodies: list[pymunk.Body], guard: bool = False
                  ) -> Sequence[Sequence[float]]:
        """rows_of(bodies) as rows of Python floats: each body's six unpacked from the rows'
        bytes (struct: ~180 instructions a number; NumPy 2's tolist() costs ~340).
        guard: the non-finite guard's one pass made on the same read, where it is made with
        Python floats (a few bodies and a blow-up reach: _state_is_finite): every number of
        every body unpacked at once; if their length is below the reach, the runner's
        is_finite after the step needs no look of its own (finite_read). The double pendulum
        reads its bobs every step: its lab step 0.4-0.5 us shorter (of ~14; 2026-11-27). The
        bodies' rows are then taken out of those numbers by one itemgetter of their slices
        (kept with where they are: _rows_at), not a list comprehension (a function call of its
        own), and the read is asked for once, not twice: with the double pendulum's after_step
        written out (its energy terms a class attribute, not getattr; one call less), its
        lab step 13.2 -> 12.4 us twice, lab/bare 1.44 -> 1.35 and 1.44 -> 1.36 (one process, the
        two versions taking turns, 60 rounds of 120 steps, load ~0.4; 2026-11-27)."""
        ids, state = self.state_rows()
        at = self._rows_at(bodies, ids)
        if at is None:
            return self.rows_of(bodies).tolist()
        reach = self.blowup_reach
        if guard and reach is not None and state.size <= FEW_NUMBERS:
            numbers = _numbers(state.size).unpack_from(state)
            if math.hypot(*numbers) < reach:
                self.finite_read = self._state_reader.reads
            return at[2](numbers)
        data, unpack = state.tobytes(), _ROW.unpack_from
        return [unpack(data, 48 * i) for i in at[1]]

    def _rows_at(self, bodies: list[pymunk.Body], ids: np.ndarray | None = None
                 ) -> tuple[np.ndarray, list[int], Callable[[tuple], tuple]] | None:
        """Where the bodies' rows are in state_rows (as an array, as a list, and an itemgetter
        that takes them out of the rows' numbers as one flat tuple: rows_list), or None if one
        is not in the space; kept while the batch lists the same bodies in the same order (ids:
        state_rows' ids, if the caller has them)."""
        if ids is None:
            ids = self.state_rows()[0]
        key = ids.tobytes()
        cache = self._rows_of
        if cache is None or cache[0] is not bodies or cache[1] != key:
            wanted = np.array([b.id for b in bodies], dtype=np.int64)
            order = np.argsort(ids)
            # (np.minimum, not .clip: the method costs ~5 us more)
            at = order[np.minimum(np.searchsorted(ids, wanted, sorter=order), len(ids) - 1)] \
                if len(ids) else wanted
            if not len(ids) or not np.array_equal(ids[at], wanted):
                return None
            cache = self._rows_of = (bodies, key, (at, at.tolist(), _rows_getter(at.tolist())))
        return cache[2]

    def static_rows(self, ids: np.ndarray) -> np.ndarray:
        """Bool mask of the rows (from body_rows) that are static bodies."""
        if len(self._static_ids) <= 16:      # a few static bodies: compare with each at once
            return (ids[:, None] == self._static_ids).any(axis=1)
        return np.isin(ids, self._static_ids)

    def awake_count(self, ids: np.ndarray) -> int:
        """How many rows (from body_rows) are awake bodies: those before the first static row,
        by the batch's order awake | static | sleeping."""
        if len(ids) <= 64:      # a few bodies: a look at each beats an (n, k) comparison
            static = self._static_set
            for i, body_id in enumerate(ids.tolist()):
                if body_id in static:
                    return i
            return len(ids)
        static = self.static_rows(ids)
        return int(np.argmax(static)) if static.any() else len(ids)

    def sleeping_rows(self, ids: np.ndarray) -> np.ndarray:
        """Bool mask of the rows (from body_rows) that are sleeping bodies: the rows after the
        last static one, by the batch's order awake | static | sleeping (tested against
        Body.is_sleeping in tests/test_falling_balls.py)."""
        static = self.static_rows(ids)
        asleep = np.zeros(len(ids), dtype=bool)
        last = np.flatnonzero(static)
        if len(last):
            asleep[last[-1] + 1:] = True
        return asleep

    def draw_mouse(self, surface, view) -> None:
        """Draw the mouse's drag joint while a body is held (call it at the end of draw)."""
        if self.mouse_joint is not None:
            draw_pivot_joint(surface, view, self.mouse_joint)

    # ----- arrows (only while the overlay is on) ------------------------------------------------
    arrow_name = "body"     # what the legend calls a body ("ball", "bob")

    def arrows(self) -> Arrows:
        """Every dynamic body (a sample if there are more than MAX_ARROWS): ids, positions,
        velocities in one batch call, masses by id (read once per new body)."""
        ids, data = self.body_rows(pymunk.batch.BodyFields.POSITION
                                   | pymunk.batch.BodyFields.VELOCITY)
        masses = getattr(self, "_masses", None)
        if masses is None or not np.isin(ids, masses[0]).all():
            dynamic = [b for b in self.space.bodies if b.body_type == pymunk.Body.DYNAMIC]
            masses = (np.array([b.id for b in dynamic], dtype=np.int64),
                      np.array([b.mass for b in dynamic], dtype=float))
            self._masses = masses
        keep = np.isin(ids, masses[0])         # dynamic bodies only (not static, not kinematic)
        ids, data = ids[keep], data[keep]
        n_all = len(ids)
        every = sample_every(n_all)
        ids, data = ids[::every], data[::every]
        order = np.argsort(masses[0])
        mass = masses[1][order][np.searchsorted(masses[0][order], ids)]
        return Arrows(ids, data[:, 0:2], data[:, 2:4], mass,
                      sample_text(len(ids), n_all, self.arrow_name))

    # ----- state --------------------------------------------------------------------------
    def body_state(self) -> np.ndarray:
        """Position, angle, velocity and angular velocity of every body in the space (dynamic,
        kinematic, static and sleeping; static rows do not change), one row each
        (x, y, angle, vx, vy, w), read from pymunk in one batch call."""
        return self.body_rows(_STATE_FIELDS)[1]

    def state_arrays(self) -> Iterable[np.ndarray]:
        return (self.body_state(),)

    # A scene whose bodies are all held by joints sets this: a body farther than this many px
    # from the world has blown up (finite, but no pendulum or cradle gets there), and the run is
    # reported and rolled back as a non-finite one. None: bodies may leave (falling balls).
    blowup_reach: float | None = None

    def is_finite(self) -> bool:
        if self.resting:         # nothing moved since the world came to rest: checked once
            if self._finite_at_rest is None:
                self._finite_at_rest = self._state_is_finite()
            return self._finite_at_rest
        reads = self._state_reader.reads    # (finite_kept: falling_balls' ball_look.rearm)
        if (self._rows is not None and self.finite_read == reads) or self.finite_kept == reads:
            return True     # the rows read since the step, found finite by the scene's checks
        return self._state_is_finite()

    def _state_is_finite(self) -> bool:
        state = self.state_rows()[1]
        if self.finite_read == self._state_reader.reads:
            return True     # these very rows were found finite by the scene's checks (1.75 us)
        # One pass first: the length of the flat state as one vector, |s| = sqrt(the sum of
        # the squares of every number), is finite only if every number is, and below r only if
        # every |x| and |y| is below r, inside the blow-up reach. If not, each test again on its
        # own (a fast body may be within reach; the dot product's sum can overflow).
        # (The reader keeps a flat view beside its rows: a reshape a step cost 0.7 us, a third.)
        flat = self._state_reader.flat
        reach = self.blowup_reach
        if flat.size <= FEW_NUMBERS:
            # a few bodies (the pendulums, the cradle): math.hypot over the numbers as Python
            # floats, no NumPy call. Not the dot product flat.dot(flat): that is a BLAS call,
            # and after OpenBLAS's AVX-512 kernel the engine's next steps run slower (the
            # cradle's 30 substeps: 3-5 us a step, 5-9 % of the lab's step; none with
            # OPENBLAS_CORETYPE=Haswell, whose kernel is AVX2: bench pymunk, 2026-11-27)
            size = math.hypot(*_numbers(flat.size).unpack_from(flat))
            if reach is not None and size < reach:
                return True
        else:   # (many bodies: one BLAS call beats a Python float per number)
            size = flat.dot(flat)
            if reach is not None and size < reach * reach:
                return True
        if not math.isfinite(size) and not np.isfinite(state).all():
            return False
        if reach is None or not len(state):
            return True
        w, h, r = *self.world_size, reach
        x0, y0, x1, y1 = extent(state)
        return bool(x0 > -r and x1 < w + r and y0 > -r and y1 < h + r)   # (all finite here)

    def snapshot(self) -> Any:
        """A deep copy of the world (the space and the scene's lists of its objects, copied
        together so they still refer to each other). A drag in progress is left out of it."""
        joint = self.mouse_joint
        if joint is not None:
            self.space.remove(joint)
        try:
            return copy.deepcopy({k: getattr(self, k) for k in self.world_keys})
        finally:
            if joint is not None:
                self.space.add(joint)

    def restore(self, snap: Any) -> None:
        if snap is None:
            self.reset()
            return
        self._detach_mouse()
        for key, value in copy.deepcopy(snap).items():
            setattr(self, key, value)
        self.refresh_static_ids()      # the copies are new bodies with new ids
        self._masses = None
        self.wake()
        self.restored()
        self.apply_settings()          # the copy holds the settings of its time

    def restored(self) -> None:
        """Called after restore() put copied objects in place: rebuild anything keyed by body
        ids or holding references to the old objects."""


def extent(rows: np.ndarray) -> tuple[float, float, float, float]:
    """(x min, y min, x max, y max) of the points in the first two columns of rows (n >= 1; NaN
    if a coordinate is: argmin and argmax point at a NaN). A reduction down the columns of an
    (n, 2) array is slow in NumPy (several us for a few rows, 159 us at 3000), and a ufunc's
    min() on one column costs several times an argmin: so argmin and argmax, column by column."""
    x, y = rows[:, 0], rows[:, 1]
    return x[x.argmin()], y[y.argmin()], x[x.argmax()], y[y.argmax()]
