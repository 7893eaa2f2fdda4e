"""Pivoting L: "Joints. Just wait and the L will tip over." The L of the falling-balls scene is now
a moving body, pinned at its rotation centre and held by a slide joint that limits how far it turns.

The lecture idea (pymunk tutorial, "add_L"):
  * the L is a DYNAMIC body carrying the two segments: mass 10 and moment 10000 as in pymunk's
    example file (examples/slide_and_pinjoint.py) and the tutorial's older edition; the current
    tutorial sets a mass on each segment instead, from which pymunk computes the body's mass and
    moment. Here the `L_mass` slider scales the example's pair;
  * a PinJoint ties it to a static "rotation centre" body: both anchors at (0, 0), so the L can
    only turn about that point (the pin keeps the distance between the anchors at 0);
  * a SlideJoint(L, rotation_limit_body, (-100, 0), (0, 0), 0, 25) joins a point on the L's long
    arm to a second static body: like a pin joint, but the distance may be anything from min to
    max, so the L turns freely until the joint reaches 25 and then stops;
  * balls keep landing on the L; as they collect on one side it tips until the slide joint stops it,
    and the balls roll off. Balls that leave the world are removed.
A lesson in the numbers: a PinJoint keeps a DISTANCE (here 0) between its anchors, so it pushes
only along the line between them; with both anchors on one point it acts only once they have
separated, and a ball's blow sideways opens a gap that the joint then closes step by step. The
`pin_error` metric shows it (about 0.7 to 1.2 px with one substep, 0.6 to 0.7 px with two, the
default here: 30 s runs, seeds 0 to 2); set `pivot=pivot` for a PivotJoint, which holds both
directions at once. The slide joint is just as soft: when the loaded L slams into it, it
overshoots its max by about 1 to 3 px with two substeps (3.5 to 5 px with one): `slide_seen_max`
is larger than the param `slide_max`.

On screen: the pin (white dot), the slide joint's allowed range (the green band from its min to its
max, measured from the static anchor; the dot on the L turns red at a limit).

Metrics: angle_deg (the L's angle), slide_distance (between the slide joint's anchors now),
slide_seen_min / slide_seen_max (the smallest and largest seen over the run; not `slide_max`,
which is the joint's limit, a parameter), pin_error (largest distance between the pin's anchors
seen: a perfect pin keeps it 0), and falling_balls' counts; `tunneled` matters here: at a coarse
step (hertz 1) most balls fall through the L without touching it, the L never tips, and the HUD
says so rather than showing an L at rest as if it were the result; the few that hit it open the
pin by a hundred px and more within a substep: the HUD flags a pin error beyond 5 px too, and
the metrics' pin_let_go says so in the JSON.

Layout as in falling_balls: y down, the tutorial's lengths scaled by 1.5 (so the slide's max is
25 * 1.5 = 37.5 px by default).

Controls: drag the L or a ball with the left mouse button; a left click on empty space drops a
ball there. Parameters: spawn_rate, radius, max_balls, friction, slide_max, L_mass, pivot,
g, iterations, substeps (2 here); effects: sleeping, gravity.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pygame
import pymunk

from app.draw import pymunk_draw as D
from app.pymunk_scene import PYMUNK_PARAMS
from app.scene import Param, Scene, Try, Unit, common
from scenes.falling_balls import BALL_PARAMS, L_LIP, L_LONG, L_ORIGIN, L_RADIUS, S, \
    FallingBallsScene
from scenes.ball_look import look_moving
from scenes.ball_checks import BallChecks
from scenes.l_frame import body_pose, cos_sin

SLIDE_ANCHOR = (-100 * S, 0.0)   # the slide joint's anchor on the L (the tutorial's (-100, 0))
PIN_LOOSE = 5.0                  # px: a pin error beyond this is flagged (HUD, pin_let_go)
TIP_REACH = 210.0                # px below the pin the tipped L reaches (measured: y 644 at
                                 # slide_max 150, the largest; 547 at the default 37.5)

PIVOT_PARAMS: tuple[Param, ...] = (
    Param("slide_max", 25 * S, float, 0.0, 150.0,
          help="the slide joint's max distance, px (the tutorial's 25, scaled)"),
    Param("L_mass", 10.0, float, 0.1, 1000.0, help="mass of the L (moment scales with it)"),
    Param("pivot", "pin", str, choices=("pin", "pivot"),
          help="joint at the rotation centre: the tutorial's PinJoint, or a PivotJoint"),
)
# Two substeps by default: the slide joint then overshoots its max by about 1 to 3 px instead of
# 3.5 to 5 when a loaded L slams into it, and the pin holds within 1 px (see the module docstring).
SUBSTEPS_2 = common("substeps", default=2)
_SPAWN = next(p for p in BALL_PARAMS if p.name == "spawn_rate")
SPAWN_2 = replace(_SPAWN, default=2.0,
                  help=_SPAWN.help + " (the tutorial: one every 25 ticks at 50 fps)")


class PivotingLScene(FallingBallsScene):
    """Pivoting L: an L pinned at its rotation centre (PinJoint) and held by a SlideJoint (0 to
    its max) to a second static body; balls land on it until it tips. The pin and the slide
    joint's range are drawn.

    Mouse: drag the L or a ball with the left button; left click on empty space drops a ball.
    """

    name = "pivoting_l"
    arrow_name = "body"
    error_metric, error_label = "pin_error", "largest pin error"
    title = "Pivoting L: pin and slide joints (pymunk)"
    no_energy_words = "balls appear, land and leave, so its energy has no start to hold to"
    category = "Rigid bodies (pymunk)"
    params = PYMUNK_PARAMS + (SPAWN_2,) \
        + tuple(p for p in BALL_PARAMS if p.name not in ("container", "spawn_rate")) \
        + PIVOT_PARAMS + (SUBSTEPS_2,)
    world_keys = FallingBallsScene.world_keys + ("pin", "slide", "record")
    color_key = ((D.SLIDE, "green: the slide joint's range"), (D.SLIDE_LIMIT, "red: at a limit"),
                 (D.DYNAMIC, "the L"))
    metric_units = {"angle_deg": Unit("deg"), "slide_distance": Unit("px"),
                    "slide_seen_min": Unit("px"), "slide_seen_max": Unit("px"),
                    "pin_error": Unit("px")}
    tries = (
        Try("PivotJoint, not the pin", {"pivot": "pivot"},
            "the L turns the same way: a pivot joint is a pin joint of length 0"),
        Try("Back to the PinJoint", {"pivot": "pin"},
            "pin_error in the metrics: how far the pin's two anchors drift apart"),
        Try("No slide range", {"slide_max": 0},
            "slide_max 0 locks the L level: it cannot tip (angle_deg stays near 0)"),
    )

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The L and where it can tip to, the balls' way in from the top, the slide joint (the
        balls' fall to the world's bottom after they roll off is left out: nothing happens
        there)."""
        left = L_ORIGIN[0] + L_LONG[0][0] - 60
        right = L_ORIGIN[0] + L_LONG[1][0] + 60
        _, top, _, _ = super().content_bounds()
        bottom = L_ORIGIN[1] + TIP_REACH + 20
        return (left, top, right - left, bottom - top)

    def build_space(self, space: pymunk.Space) -> None:
        super().build_space(space)
        self.record = {"slide_seen_min": self.slide_distance(),
                       "slide_seen_max": self.slide_distance(), "pin_error": self.pin_error()}

    def add_L(self, space: pymunk.Space) -> tuple[pymunk.Body, list[pymunk.Segment]]:
        """The tutorial's add_L: a dynamic L, a pin at its rotation centre, a slide joint."""
        rotation_center_body = pymunk.Body(body_type=pymunk.Body.STATIC)
        rotation_center_body.position = L_ORIGIN
        rotation_limit_body = pymunk.Body(body_type=pymunk.Body.STATIC)
        rotation_limit_body.position = (L_ORIGIN[0] + SLIDE_ANCHOR[0], L_ORIGIN[1])

        mass = self.p["L_mass"]
        body = pymunk.Body(mass, 10000 * S * S * mass / 10.0)   # the tutorial's (10, 10000)
        body.position = L_ORIGIN
        shapes = [pymunk.Segment(body, a, b, L_RADIUS) for a, b in (L_LONG, L_LIP)]
        for s in shapes:
            s.friction = self.p["friction"]

        joint = pymunk.PinJoint if self.p["pivot"] == "pin" else pymunk.PivotJoint
        self.pin = joint(body, rotation_center_body, (0, 0), (0, 0))
        self.slide = pymunk.SlideJoint(body, rotation_limit_body, SLIDE_ANCHOR, (0, 0),
                                       0, self.p["slide_max"])
        space.add(rotation_center_body, rotation_limit_body, body, *shapes, self.pin, self.slide)
        return body, shapes

    # ----- the joints, measured -------------------------------------------------------------
    @staticmethod
    def anchor_distance(joint: pymunk.Constraint) -> float:
        """Distance between a joint's two anchors in the world, px (D.length: a blown-up L is
        reported, not fatal)."""
        a, b = D.anchors(joint)
        return D.length(a - b)

    def slide_distance(self) -> float:
        return self.anchor_distance(self.slide)

    def pin_error(self) -> float:
        return self.anchor_distance(self.pin)

    def advance(self) -> None:
        """FallingBallsScene.advance, its usual case written out (the step() of each substep and
        its super() calls cost ~1 us a step): the substeps, the joints' records after each, one
        look at the balls after the last, the spawner's clock. Anything else (a world at rest,
        woken since the last step, the sleep threshold to set for a new substep (sleeping on:
        with it off there is none), one substep, a subclass's own step or spawner) goes the
        general way, which does the same (a test compares). What it tests first is made once,
        in moving_plan, and kept until wake()."""
        plan = self._moving_plan
        if plan is None:
            plan = self._moving_plan = self.moving_plan()
        if not plan or self.resting or self._L_known is None:
            super().advance()
            return
        n, h, dt, spawning, after = plan
        space_step, record = self.space.step, self.record_joints
        for _ in range(n - 1):          # (FallingBallsScene.step without its look)
            space_step(h)
            self._rows = None           # (the rows read before this step are old now)
            record(body_pose(self.L_body))          # (L_pose's, the L not static: the plan)
            if spawning:                # (spawn(h)'s clock written out: spawn(0.0) when due)
                self._spawn_due -= h
                if self._spawn_due <= 0:
                    self.spawn(0.0)
        L0 = self._L_known
        space_step(h)
        self._rows = None
        pose = self._L_after = self._L_known = look_moving(self, L0)   # (check_balls)
        record(pose)
        self.step_done(h, dt, spawning, after)

    def moving_plan(self) -> tuple | None:
        """(substeps, h, dt, spawning, whether after_step does anything) for advance's written-out
        step; () if steps go the general way (one substep, a static L, a subclass's own step,
        spawner or L_pose); None while the general way must first set the sleep threshold
        (asked again next step)."""
        p = self.p
        n = p["substeps"]
        if n == 1 or type(self).step is not PivotingLScene.step \
                or type(self).spawn is not FallingBallsScene.spawn \
                or type(self).L_pose is not BallChecks.L_pose or self._L_static_pose is not None:
            return ()
        dt = self.dt
        h = dt / n
        if h != self._sleep_h and "sleeping" in self.on:
            return None
        return n, h, dt, p["spawn_rate"] > 0, type(self).after_step is not Scene.after_step

    def step(self, h: float) -> None:
        super().step(h)
        pose = self._L_after          # the L's (x, y, angle) after this substep
        if pose is not None:          # (None: the world rests: nothing moved, nothing new)
            self.record_joints(pose)

    def record_joints(self, pose: tuple[float, float, float]) -> None:
        """Take in the joints' lengths with the L at pose (after a substep): the slide's
        smallest and largest, the pin's largest error."""
        fixed = self._joint_flat
        if fixed is None:
            d, pin = self.joint_distances(pose)
        else:            # joint_distances' sums written out (a call and a loop: ~1 us a substep)
            x, y, a = pose
            c, s = cos_sin(a)
            vx, vy, fx, fy, wx, wy, gx, gy = fixed
            dx, dy = c * vx - s * vy + x - fx, s * vx + c * vy + y - fy
            d = math.sqrt(dx * dx + dy * dy)
            dx, dy = c * wx - s * wy + x - gx, s * wx + c * wy + y - gy
            pin = math.sqrt(dx * dx + dy * dy)
        r = self.record
        if d < r["slide_seen_min"] or d > r["slide_seen_max"] or pin > r["pin_error"]:
            r["slide_seen_min"] = min(r["slide_seen_min"], d)
            r["slide_seen_max"] = max(r["slide_seen_max"], d)
            r["pin_error"] = max(r["pin_error"], pin)

    def joint_distances(self, pose: tuple[float, float, float]) -> tuple[float, float]:
        """(slide_distance(), pin_error()) with the L at pose, computed without a call into
        pymunk: each joint joins a point fixed on the L to a fixed point in the world (a static
        body's anchor), so its length is |p + R(angle) (anchor - cog) - fixed point|, what
        Body.local_to_world gives (a test compares the two). A joint built otherwise (a student's
        add_L may) is read from pymunk."""
        x, y, a = pose
        c, s = cos_sin(a)
        out = []
        for joint, points in zip((self.slide, self.pin), self._joint_points):
            if points is None:
                out.append(self.anchor_distance(joint))
                continue
            vx, vy, fx, fy = points
            dx, dy = c * vx - s * vy + x - fx, s * vx + c * vy + y - fy
            out.append(math.sqrt(dx * dx + dy * dy))
        return out[0], out[1]

    def restored(self) -> None:
        super().restored()
        self._joint_points = tuple(self.fixed_points(j) for j in (self.slide, self.pin))
        self._joint_flat = None if None in self._joint_points else \
            self._joint_points[0] + self._joint_points[1]      # (step: both, one tuple)

    def fixed_points(self, joint: pymunk.Constraint) -> tuple[float, float, float, float] | None:
        """(vx, vy, fx, fy): the joint's anchor on the L less the L's centre of gravity (v) and
        its other anchor in the world, on a static body (f); None if it is not such a joint."""
        L = self.L_body
        if joint.a is L and joint.b.body_type == pymunk.Body.STATIC:
            on_L, other = joint.anchor_a, joint.b.local_to_world(joint.anchor_b)
        elif joint.b is L and joint.a.body_type == pymunk.Body.STATIC:
            on_L, other = joint.anchor_b, joint.a.local_to_world(joint.anchor_a)
        else:
            return None
        cog = L.center_of_gravity
        return on_L.x - cog.x, on_L.y - cog.y, other.x, other.y

    # ----- drawing and reporting --------------------------------------------------------------
    def draw_L(self, surface: pygame.Surface, view) -> None:
        D.draw_shapes(surface, view, self.L_shapes, D.DYNAMIC)

    def draw_joints(self, surface: pygame.Surface, view) -> None:
        D.draw_slide_joint(surface, view, self.slide)
        D.draw_pin_joint(surface, view, self.pin)     # the pin: anchors and the gap between them

    def metrics(self) -> dict[str, float]:
        m = {"angle_deg": math.degrees(self.L_body.angle),
             "slide_distance": self.slide_distance(),
             "slide_seen_min": self.record["slide_seen_min"],
             "slide_seen_max": self.record["slide_seen_max"],
             "pin_error": self.record["pin_error"],
             # the flag on a run whose step was too coarse for the joints (hertz 1: 225 px)
             "pin_let_go": self.record["pin_error"] > PIN_LOOSE}
        m.update(super().metrics())
        return m

    def hud_lines(self) -> list[str]:
        pin = self.record["pin_error"]
        # a pin that opened by more than a few px is no result to read angles from: say why
        loose = ": PIN LET GO (step too coarse)" if pin > PIN_LOOSE else ""
        balls = super().hud_lines()
        d = self.slide_distance()
        # pymunk's joints are soft: a loaded L pushes the slide a little past its max (docstring)
        # (phrases parted by '  |  ', each short enough for a row at 1024x768 with F2: a row
        # breaks between them, never inside one: "0.1 px past: a" / "soft joint")
        over = (f"  |  {d - self.slide.max:.1f} px past its max: a soft joint"
                if d - self.slide.max >= 0.05 else "")
        return [f"L angle {math.degrees(self.L_body.angle):6.1f} deg   slide "
                f"{d:5.1f} px (range {self.slide.min:g}..{self.slide.max:g}){over}",
                f"largest pin error {pin:.3f} px{loose}"] + balls[1:]   # (+ tunneling)

    def hud_details(self) -> list[str]:
        return ["LMB: drag the L or a ball; click empty space to drop a ball",
                super().hud_lines()[0]]          # the balls' count
