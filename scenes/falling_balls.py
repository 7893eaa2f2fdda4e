"""Falling balls: the lecture's first pymunk program. Balls drop in at random places, land on a
static L made of two segments, roll off and fall out of the world, where they are removed.

The lecture idea (pymunk tutorial, "add_ball" and "add_static_L"):
  * a ball is a Body (mass, moment of inertia from `moment_for_circle`) plus a Circle shape;
  * the L is two Segment shapes on one STATIC body: it never moves and costs almost nothing;
  * the space is stepped with a FIXED time step (dt = 1/hertz), never the frame time;
  * "You might notice that we never delete balls. This will make the simulation require more and
    more memory and use more and more CPU": balls that leave the world are removed from the space,
    so the number of live balls levels off (the HUD shows spawned / removed / alive);
  * sleeping: a ball group that has rested for `sleep_time_threshold` seconds falls asleep and is
    skipped by the solver until something touches it (drawn dimmer; the HUD says how many).
    Turn on `container` to catch every ball in a box and watch the settled pile fall asleep.
  * tunneling: a ball whose centre goes from above the L's long segment to below it between two
    steps (inside its x-extent) has passed THROUGH it; the `tunneled` metric counts them. Raise
    g, lower hertz or shrink the radius to look for it.

Like pymunk's current tutorial (gravity (0, 900), pygame's y down; its older edition was y up with
balls starting at y=550), this lab uses y DOWN with gravity (0, +g): balls fall onto the L (the
tutorial's, scaled by 1.5 to fill the 960x720 world) from just above the top of the world, as in
the tutorial (from higher up they land faster, which is what makes tunneling show).

Controls: drag a ball (or anything that moves) with the left mouse button; a left click on empty
space drops a ball there (not while max_balls are alive: clicks obey the spawner's cap, so no
clicking can push a step past its budget). A ball that leaves the world on any side (below, to
either side, or more than a world's height above it) is removed. Parameters: spawn_rate, radius,
max_balls, friction, container, g, iterations; effects: sleeping, gravity (off: balls float).
"""

from __future__ import annotations

import math

import numpy as np
import pygame
import pymunk
import pymunk.batch

from app.draw import pymunk_draw as D
from app.pymunk_scene import PYMUNK_EFFECTS, PYMUNK_PARAMS, PymunkScene
from app.scene import Effect, Param, ParamError, Scene, Try
from scenes.ball_checks import BallChecks
from scenes.ball_look import look, rearm
from scenes.ball_tables import BallTables, slot_table

S = 1.5                      # the tutorial's lengths scaled to this world
L_ORIGIN = (400.0, 440.0)    # where the tutorial's (300, 300) lands (y down)
L_LONG = ((-150 * S, 0.0), (255 * S, 0.0))      # the long arm, in the L body's frame
L_LIP = ((-150 * S, 0.0), (-150 * S, -50 * S))  # the short arm, pointing UP (y down)
L_RADIUS = 5 * S
SPAWN_X = (-180 * S, 80 * S)  # the tutorial's random.randint(120, 380) relative to the L at 300
SPAWN_Y = 0.0                 # new balls' bottom edge: they fall in from above the world
SLEEP_TIME = 0.5              # seconds at rest before a group of bodies falls asleep
# A body slower than this counts as resting. Chipmunk's own guess is |gravity| x dt, which at
# hertz 1 (dt/substeps = 0.5 s) is 450 px/s: balls fell asleep in mid-air. Fixed at its guess for
# 60 Hz and g 900, so sleeping means the same at every step size.
IDLE_SPEED = 15.0
# A step's cost grows as balls x substeps x (iterations + 20): a settled pile of 5000 balls took
# ~0.2 us per unit (measured while other work ran: 30 ms at iterations 10, 215 ms at 200, one
# substep; 11 s at 200 x 50). Combinations over this budget (~0.5 s per step) are refused.
STEP_BUDGET = 2_500_000


_POS_ANGLE = pymunk.batch.BodyFields.POSITION | pymunk.batch.BodyFields.ANGLE

BALL_PARAMS: tuple[Param, ...] = (
    Param("spawn_rate", 4.0, float, 0.0, 200.0, help="balls dropped per simulated second",
          rebuild=False),
    Param("radius", 14.0 * S, float, 2.0, 60.0, help="ball radius, px"),
    Param("max_balls", 500, int, 1, 5000, help="no new ball while this many are alive",
          rebuild=False),
    Param("friction", 0.5, float, 0.0, 2.0, help="friction of balls and the L"),
    Param("container", False, bool, help="a box around the world catches the balls (a pile)"),
)


class FallingBallsScene(BallChecks, BallTables, PymunkScene):
    """Falling balls: balls drop onto a static L, roll off and are removed when they leave the
    world. Asleep, a settled pile costs about pymunk's own step; `tunneled` counts balls that
    passed through the L.

    Mouse: drag a ball with the left button; left click on empty space drops a ball there.
    Effect `sleeping`: resting balls fall asleep (drawn dimmer; `python -m app bench pymunk`
    measures the pile asleep and awake, and against a bare pymunk loop). Param `container`: a
    box that catches every ball, to build a pile and watch it fall asleep.
    """

    name = "falling_balls"
    arrow_name = "ball"
    arm_extent = (L_LONG[0][0], L_LONG[1][0])     # (ball_checks: the tunneling test)
    title = "Falling balls (pymunk)"
    no_energy_words = "balls appear and leave, so its energy has no start to hold to"
    category = "Rigid bodies (pymunk)"
    params = PYMUNK_PARAMS + BALL_PARAMS
    effects = PYMUNK_EFFECTS + (
        Effect("sleeping", True, "resting groups of bodies fall asleep (not simulated)"),)
    world_keys = ("space", "balls", "L_shapes", "L_body", "walls", "counts", "_spawn_due")
    _step_plan = _moving_plan = None        # (advance's usual step: step_plan; pivoting_l's)
    color_key = ((D.BALL, "awake (simulated)"),
                 (D.dim(D.BALL), "asleep (skipped by the solver)"))
    tries = (
        Try("Catch 60 balls in a box", {"container": True, "spawn_rate": 20, "max_balls": 60},
            "a pile builds up; resting groups fall asleep one after another (drawn dim, "
            "counted by balls_asleep)"),
        Try("Same pile, sleeping off", {"container": True, "spawn_rate": 20,
                                            "max_balls": 60, "sleeping": False},
            "nothing sleeps (balls_asleep stays 0): every ball is simulated every step"),
        Try("Look for tunneling", {"g": 5000, "hertz": 15, "radius": 4},
            "fast, small balls and big steps: watch the tunneled count"),
    )

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The world, and above and below it the balls on their way in (they appear just above
        the top) and out (removed 2 radii below the bottom)."""
        w, h = self.world_size
        r = 2 * self.p["radius"]
        return (0.0, SPAWN_Y - r, float(w), h + 2 * r - SPAWN_Y)

    # ----- building -------------------------------------------------------------------------
    @classmethod
    def check_combination(cls, values) -> None:
        # Refused on the command line and in the panel, before a step can freeze the window.
        work = values["max_balls"] * values["substeps"] * (values["iterations"] + 20)
        if work > STEP_BUDGET:
            raise ParamError(
                f"max_balls x substeps x (iterations + 20) = {values['max_balls']} x "
                f"{values['substeps']} x ({values['iterations']} + 20) = {work:,} is too large: "
                f"a pile that big would take over half a second per step (budget "
                f"{STEP_BUDGET:,}); lower max_balls, substeps or iterations")

    def build_space(self, space: pymunk.Space) -> None:
        self.counts = {"spawned": 0, "removed": 0, "tunneled": 0}
        self._spawn_due = 0.0             # simulated seconds until the next ball
        self.balls: list[pymunk.Circle] = []
        self.walls: list[pymunk.Segment] = []      # the container's, when it is on
        self.L_body, self.L_shapes = self.add_L(space)
        if self.p.get("container", False):
            self.add_container(space)
        self.restored()

    def add_L(self, space: pymunk.Space) -> tuple[pymunk.Body, list[pymunk.Segment]]:
        """The tutorial's add_static_L: two segments on one static body."""
        body = pymunk.Body(body_type=pymunk.Body.STATIC)
        body.position = L_ORIGIN
        shapes = [pymunk.Segment(body, a, b, L_RADIUS) for a, b in (L_LONG, L_LIP)]
        for s in shapes:
            s.friction = self.p["friction"]
        space.add(body, *shapes)
        return body, shapes

    def add_container(self, space: pymunk.Space) -> None:
        """A floor and two walls at the world's edges (on the space's own static body)."""
        w, h = self.world_size
        t = 10.0
        walls = [pymunk.Segment(space.static_body, a, b, t)
                 for a, b in (((0, h), (w, h)), ((0, 0), (0, h)), ((w, 0), (w, h)))]
        for s in walls:
            s.friction = self.p["friction"]
        space.add(*walls)
        self.walls = walls

    def restored(self) -> None:
        """(Re)build the tables kept beside self.balls: a slot for each ball (its body id and last
        known centre, ball_checks), what is known of the L (its id; its pose, if static:
        nothing moves it), and the sleep threshold the effect says."""
        self._flag_now = None       # (ball_checks: the flags' matrix and limits)
        self._quick = None          # (ball_look: the usual look's arrays and key, and
        self._quick_moving = None   # a moving L's)
        self._L_id = self.L_body.id
        self._L_static_pose = None
        if self.L_body.body_type == pymunk.Body.STATIC:
            x, y = self.L_body.position
            self._L_static_pose = (x, y, self.L_body.angle)
        self.set_sleeping("sleeping" in self.on)  # (a restored space had its snapshot's)
        n = len(self.balls)
        self._slots = list(range(n))          # each ball's slot, in the order of self.balls
        self._ids = [shape.body.id for shape in self.balls]       # and its body's id
        self._slot_of = {body_id: k for k, body_id in enumerate(self._ids)}
        self._xy = slot_table(n)
        if n:
            self._xy[:n] = [tuple(shape.body.position) for shape in self.balls]
        self._used = n                        # slots handed out (the next one is this)
        self._index_changed()
        self._checks_reset()        # (ball_checks.py)
        self.wake()

    def _bodies_changed(self) -> None:
        """A ball came or went: the lookups made from the slots (BallTables._index_changed),
        and what wake() forgets, but the L's pose (it did not move)."""
        self._index_changed()
        PymunkScene.wake(self)
        self._rest_plan = None

    def set_sleeping(self, on: bool) -> None:
        """Sleeping on: groups at rest for SLEEP_TIME (and 4 substeps) fall asleep. Off: the
        threshold is infinite, so Chipmunk never counts idle time, and sleepers are woken."""
        self.space.sleep_time_threshold = SLEEP_TIME if on else math.inf
        self.space.idle_speed_threshold = IDLE_SPEED
        self._sleep_h = None
        self._step_plan = self._moving_plan = None
        if not on:
            for body in self.space.bodies:
                if body.body_type == pymunk.Body.DYNAMIC and body.is_sleeping:
                    body.activate()

    def settings_changed(self, names: set[str]) -> None:
        super().settings_changed(names)
        if "sleeping" in names:
            self.set_sleeping("sleeping" in self.on)

    # ----- balls ----------------------------------------------------------------------------
    def add_ball(self, pos: tuple[float, float], index: bool = True) -> pymunk.Circle:
        """The tutorial's add_ball: mass 1, moment for a solid circle, a Circle shape."""
        mass, radius = 1.0, self.p["radius"]
        body = pymunk.Body(mass, pymunk.moment_for_circle(mass, 0, radius, (0, 0)))
        body.position = pos
        shape = pymunk.Circle(body, radius, (0, 0))
        shape.friction = self.p["friction"]
        self.space.add(body, shape)
        self.balls.append(shape)
        if index:          # add_balls indexes once at the end
            body_id = body.id
            slot = self.new_slot(body_id, pos)
            self._slots.append(slot)
            self._ids.append(body_id)
            # who is awake, in Chipmunk's order, with the new ball (ball_checks; None: read again)
            self._awake, self._fast = self.awake_after_add(body_id, slot, pos)
            rearm(self)             # (ball_look: the next look's usual case, for them)
            self._bodies_changed()
        else:
            self.wake()
        self.counts["spawned"] += 1
        return shape

    def add_balls(self, n: int, gap: float = 0.5) -> int:
        """Drop up to n balls at once in a hexagonal grid, filling the world from the bottom
        up and skipping places taken by a shape (to build big piles quickly: the benchmark and
        the tests). Returns how many were added."""
        r = self.p["radius"]
        w, h = self.world_size
        dx, dy = 2 * r + gap, (2 * r + gap) * math.sqrt(3) / 2
        added, row = 0, 0
        y = h - 10 - r - gap if self.p.get("container", False) else h - r - gap
        while added < n and y > r:
            x = r + 10 + gap + (dx / 2 if row % 2 else 0)
            while added < n and x < w - 10 - r:
                if not self.place_taken((x, y), r + gap):
                    self.add_ball((x, y), index=False)
                    added += 1
                x += dx
            y -= dy
            row += 1
        self.restored()
        return added

    def remove_balls(self, which) -> None:
        """Remove the balls with these indices in self.balls from the space and from the list
        (the tutorial's balls_to_remove)."""
        gone = set(which.tolist() if isinstance(which, np.ndarray) else which)
        if not gone:
            return
        held = self.mouse_joint
        if held is not None and any(self.balls[k].body is held.b for k in gone):
            self.release()
        removed, balls, slots, ids, slot_of = [], self.balls, self._slots, self._ids, self._slot_of
        for k in gone:                      # (in the set's order: the space's order after it)
            self.space.remove(balls[k], balls[k].body)
            removed.append(ids[k])          # (kept: Body.id is a C call, ~0.4 us)
            del slot_of[ids[k]]                 # (a freed id may be a new body's one day)
        for k in sorted(gone, reverse=True):
            del balls[k], slots[k], ids[k]
        # who is awake, in Chipmunk's order, after the removal (ball_checks; None: read again)
        self._awake, self._fast = self.awake_after_removal(removed)
        rearm(self)                 # (ball_look: the next look's usual case, for them)
        self._bodies_changed()
        self.counts["removed"] += len(gone)

    def read_balls(self, fields: pymunk.batch.BodyFields = pymunk.batch.BodyFields.POSITION,
                   sleeping: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """(index into self.balls (n,), data (n, k), asleep (n,)) of every ball, in batch order,
        from one batch read (asleep is None when not asked for)."""
        ids, data = self.body_rows(fields)
        k = self.ball_index(ids)
        ball = k >= 0
        asleep = self.sleeping_rows(ids)[ball] if sleeping else None
        return k[ball], data[ball], asleep

    # ----- stepping -------------------------------------------------------------------------
    def wake(self) -> None:
        super().wake()
        # (a body may have been changed: is_finite reads them again; ball_look.rearm keeps the
        # read after which only balls came or went, every body finite still, in finite_kept)
        self.finite_kept = -1
        self._L_known = None      # the L's pose is read again before the next step
        self._rest_plan = self._step_plan = self._moving_plan = None   # (advance's: made again)

    def advance(self) -> None:
        """Scene.advance; while every body sleeps and no ball is due (a settled pile), only the
        engine's steps (step's first case, every substep at once, looked up once a rest: what
        could change it wakes the scene). A usual step (one substep, awake) is written out too
        (step_plan; tests/test_pymunk_checks.py compares both with the general way, step by
        step)."""
        if self.resting:
            plan = self._rest_plan
            if plan is None:
                plan = self._rest_plan = self.rest_plan()
            if plan:
                n, h, dt, after = plan
                step = self.space.step
                for _ in range(n):
                    step(h)
                self._rows = self._L_after = None
                self.time, self.steps = self.time + dt, self.steps + 1
                if after:
                    self.after_step()
                return
        else:
            plan = self._step_plan
            if plan is None:
                plan = self._step_plan = self.step_plan()
            if plan and self._L_known is not None:     # (step()'s last case, written out)
                dt, spawning, after = plan
                L0 = self._L_known
                self.space.step(dt)
                self._rows = None
                self._L_after = self._L_known = look(self, L0)
                self.step_done(dt, dt, spawning, after)
                return
        # The general way: Scene.advance's substeps. The balls are looked at once, after the
        # last substep (as the tutorial looks once a frame): a ball that tunneled is counted, one
        # that left removed; the substeps before step the engine, spawner and pivoting_l's joints
        n = self.p["substeps"]
        dt = self.dt
        h = dt / n
        self._look = False
        try:
            for _ in range(n - 1):
                self.step(h)
        finally:
            self._look = True
        self.step(h)
        self.time, self.steps = self.time + dt, self.steps + 1
        self.after_step()

    # False during the substeps before a step's last (advance): step() does not look at the balls
    _look = True

    def step_done(self, h: float, dt: float, spawning: bool, after: bool) -> None:
        """The written-out steps' end (here and pivoting_l's): the spawner's clock after the last
        substep h (spawn(0.0) when due), the step of dt counted, after_step if it does anything."""
        if spawning:
            self._spawn_due -= h
            if self._spawn_due <= 0:
                self.spawn(0.0)
        self.time += dt
        self.steps += 1
        if after:
            self.after_step()

    def step_plan(self) -> tuple | None:
        """(dt, spawning, whether after_step does anything) for advance's written-out step; () for
        the general way (several substeps, a subclass's own step or spawner); None while it must
        set the sleep threshold first (asked again next step). Kept until wake()."""
        p = self.p
        if p["substeps"] != 1 or type(self).step is not FallingBallsScene.step \
                or type(self).spawn is not FallingBallsScene.spawn:
            return ()
        dt = self.dt
        if dt != self._sleep_h and "sleeping" in self.on:
            return None
        return dt, p["spawn_rate"] > 0, type(self).after_step is not Scene.after_step

    def rest_plan(self) -> tuple:
        """(substeps, h, dt, whether after_step does anything) for a step at rest,
        or () if such a step must go the usual way (a ball is due, a subclass steps otherwise,
        or the sleep threshold is not yet set for this substep)."""
        p = self.p
        n = p["substeps"]
        dt = self.dt
        h = dt / n
        if p["spawn_rate"] > 0 or type(self).step is not FallingBallsScene.step \
                or h != self._sleep_h:
            return ()
        return (n, h, dt, type(self).after_step is not Scene.after_step)

    def step(self, h: float) -> None:
        if self.resting and h == self._sleep_h:   # every body sleeps: nothing moves, nothing
            self.space.step(h)                    # to read or test
            self._rows = self._L_after = None
            if self.p["spawn_rate"] > 0:
                self.spawn(h)
            return
        if h != self._sleep_h and "sleeping" in self.on:
            # at rest for SLEEP_TIME, and for at least 4 substeps: at hertz 1 one substep is as
            # long as SLEEP_TIME, and a ball spawned at rest fell asleep in mid-air
            self.space.sleep_time_threshold = max(SLEEP_TIME, 4 * h)
            self._sleep_h = h
        if self.resting:          # every body sleeps: nothing moves, nothing to read or test
            super().step(h)
            self._L_after = None
            self.spawn(h)
            return
        if not self._look:        # not the step's last substep: the engine's step, no look
            if self._L_known is None:             # (woken: the pose before the step, for the
                self._L_known = self.L_pose()     # look after its last substep)
            self.space.step(h)
            self._rows = None
            self._L_after = self.L_pose()         # (pivoting_l's joints read it)
            self.spawn(h)
            return
        # the L's pose before the step: where the last look left it, unless woken since
        L0 = self._L_known or self.L_pose()
        self.space.step(h)                        # (PymunkScene.step)
        self._rows = None
        self._L_after = self._L_known = look(self, L0)   # (check_balls; pivoting_l's joints
                                                         # use it)
        if type(self).spawn is not FallingBallsScene.spawn:
            self.spawn(h)                         # (a subclass's own spawner)
        elif self.p["spawn_rate"] > 0:            # (spawn's clock first: at the defaults a
            self._spawn_due -= h                  # ball is due once in 15 steps; spawn(0.0)
            if self._spawn_due <= 0:              # is spawn(h) with h taken off)
                self.spawn(0.0)

    def spawn(self, h: float) -> None:
        """Drop balls at a steady rate at random x above the L, from above the world (seeded:
        self.random); a ball whose place is taken goes on top of the ball there."""
        rate = self.p["spawn_rate"]
        if rate <= 0:
            return
        self._spawn_due -= h
        while self._spawn_due <= 0:
            self._spawn_due += 1.0 / rate
            if len(self.balls) >= self.p["max_balls"]:
                continue
            r = self.p["radius"]
            x, y = L_ORIGIN[0] + self.random.uniform(*SPAWN_X), SPAWN_Y - r
            # a place already taken (balls due in one long step, or not yet fallen: gravity
            # off) puts the ball on top: overlapping balls by the hundred made a step take
            # seconds; a column over a world's height is full (it would be removed at once)
            while self.place_taken((x, y), r):
                y -= 2 * r
            if y > -self.world_size[1]:
                self.add_ball((x, y))

    # ----- mouse ----------------------------------------------------------------------------
    def on_click(self, pos: tuple[float, float], button: int) -> None:
        """A left click on empty space drops a ball there, unless max_balls are alive (the
        spawner's cap, which check_combination's step budget counts on)."""
        if (button == 1 and len(self.balls) < self.p["max_balls"]
                and not self.place_taken(pos, self.p["radius"])):
            self.add_ball(pos)

    # ----- drawing --------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, view) -> None:
        for s in self.walls:
            D.draw_shape(surface, view, s, D.STATIC)
        self.draw_L(surface, view)
        _, data, asleep = self.read_balls(_POS_ANGLE)
        D.draw_circles(surface, view, data[:, :2], data[:, 2], self.p["radius"], D.BALL, asleep)
        self.draw_joints(surface, view)
        self.draw_mouse(surface, view)

    def draw_L(self, surface: pygame.Surface, view) -> None:
        D.draw_shapes(surface, view, self.L_shapes, D.STATIC)

    def draw_joints(self, surface: pygame.Surface, view) -> None:
        """Joints, drawn over the balls (none here)."""

    # ----- reporting ------------------------------------------------------------------------
    def asleep_count(self) -> int:
        """How many balls sleep now."""
        _, _, asleep = self.read_balls()
        return int(np.count_nonzero(asleep))

    def metrics(self) -> dict[str, float]:
        return {"balls_spawned": self.counts["spawned"], "balls_removed": self.counts["removed"],
                "balls_alive": len(self.balls), "tunneled": self.counts["tunneled"],
                "balls_asleep": self.asleep_count()}

    def hud_lines(self) -> list[str]:
        c = self.counts
        asleep = ("sleeping off" if "sleeping" not in self.on
                  else f"{self.asleep_count()} asleep")
        # (phrases parted by '  |  ': a row breaks between them at F2, never inside one)
        lines = [f"balls: {len(self.balls)} alive ({asleep})  |  {c['spawned']} spawned, "
                 f"{c['removed']} removed"]
        if c["tunneled"]:
            lines.append(f"TUNNELED through the L: {c['tunneled']} of {c['spawned']} "
                         f"(step too coarse?)")
        return lines

    def hud_details(self) -> list[str]:
        return ["LMB: drag a ball, or click empty space to drop one"]
