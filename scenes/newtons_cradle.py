"""Newton's cradle (the lecture's pymunk classwork): N equal balls hang on strings side by side;
lift k of them, let go, and k balls swing out at the far end while the middle ones stay still.

What it shows. An elastic collision of equal masses swaps their velocities, so momentum AND energy
pass down the row ball by ball: k balls in, k balls out. A real cradle's balls touch; the
compression wave runs through them in microseconds, one contact at a time.

Why a cradle is hard for an impulse solver (the teaching point). Chipmunk (pymunk) finds every
contact at the start of a step and solves them all *together*, iteratively, at the velocity level:
each contact's target is "separate at e times the approach speed", where the approach speed is
the one the step started with. If the balls touch at rest, the first ball's contact sees an
approach speed v but the next contacts see 0, so the solver only asks them not to interpenetrate:
it pushes the whole row along together, like one soft lump, and several balls leave slowly
instead of one ball leaving fast. The cure is to make the real cradle's sequence happen in the
simulation:
  * `gap`: a hair of space between the balls at rest (default 0.02 px, invisible), so each impact
    is a separate collision of TWO balls, one after the other. A negative gap presses the balls
    together (overlapping by less than the slop, so their contacts persist at rest): then 1 ball in
    sends the whole row of 4 off together at 41% of the speed, "1 in, 0 out", the solver's answer
    for simultaneous contacts. At gap 0 the balls touch exactly and the result hangs on rounding.
    A large gap works too, but every impact then carries a ball across the gap before it stops,
    and the middle balls creep (see below);
  * elasticity 0.9999999 on every ball (the slide's hint). pymunk multiplies the two shapes'
    values, so a contact gets e = 0.9999998; e = 1 exactly is allowed too. Friction 0: a rubbing
    contact would spin the balls and take energy;
  * many small steps (hertz 120, substeps 30): a ball moves v*h per substep and is found already
    overlapping its neighbour by up to that much. Every impact shifts the struck balls forward by
    roughly gap + v*h, and the middle balls, being pendulums of the same period as the swing,
    collect these shifts in step with it, so their wobble grows by that amount every impact.
    With h = 1/3600 s, over ten seconds the middle balls stay under a pixel (0.4 px for 1 in,
    0.8 px for 2 in) and the resting end balls within 1.6 px; at substeps 5 the middle balls of
    2-in-2-out wobble by 4.5 px and at substeps 2 by almost 10 px;
  * the "strings" are rigid rods: PinJoints to fixed anchors, which hold the distance in both
    directions (a string could go slack; these push as well as pull), with their error fully
    corrected every step (error_bias 0), so a rod does not stretch and slowly bleed energy;
    collision_slop is small (0.01 px) so resting contacts are not allowed to overlap.
  * a step must be short against the swing: omega*h = sqrt(g/L)/(hertz x substeps) above
    MAX_OMEGA_H (0.2) is refused. At g 900 that is hertz x substeps of at least 9; coarser than
    that the pin joints cannot hold the rods (at 1 x 1 they stretched by 250 px and the
    "energy ratio" read -4.5, which is no ratio of energies at all).
Break it on purpose: gap -0.01 (touching), gap 5, substeps 2, elasticity 0.9 (the energy drains and
the swings shrink), damping 0.99 (air drag: space.damping is the fraction of velocity kept per
second; 1 is none. Negative values would abort pymunk, so the range is 0..1).

Metrics (DESIGN.md): `lifted` (k lifted: at most balls-1, a larger value is refused),
`balls_out` (balls that swing out past half the release amplitude in the first half-swing after
the first impact; counted while that window is open, then frozen), `middle_max_drift` (largest
distance from its rest position, px, of any ball that is neither lifted nor expected out: balls
k .. N-k-1; 0 when there are none), `energy_ratio` (kinetic + potential energy now / at release;
null when there was no energy at release, e.g. released with gravity off).
Also `release_speed` (px/s, the lifted balls just before the first impact) and `out_speed_ratio`
(the slowest of the k far balls' top speed after the impact / release speed).

Controls: drag a ball with the left mouse button (the strings hold it). Letting go re-arms the
measurement: the balls more than a radius from rest count as lifted and the energy at that moment
is the new baseline. Parameters: balls, lifted, angle, gap, elasticity, damping, substeps,
iterations, g; effect: gravity (off: legal but odd. Released without gravity nothing moves: the
lifted balls start at rest and no force acts. Switched off mid-swing, each moving ball keeps its
distance to its anchor, the rod pulling it round a circle at constant speed). Changing g or
gravity while it runs re-baselines `energy_ratio` (the potential energy depends on g: the old
baseline would fake a gain or loss).

The verdict ("k in, k out") waits: while a ball is held with the mouse there is none (the hand is
doing the work), and after the first impact it comes when the half-swing that decides it is over,
not while the far balls are still on their way out.
"""

from __future__ import annotations

import math
from typing import Iterable

import numpy as np
import pygame
import pymunk

from app.draw import pymunk_draw as D
from app.pymunk_scene import PYMUNK_PARAMS, PymunkScene
from app.draw.text import px
from app.scene import Param, ParamError, Try, Unit, common

RADIUS = 24.0            # ball radius, px
STRING = 280.0           # string length, anchor to ball centre, px
ANCHOR_Y = 230.0         # height of the anchor bar (below the HUD box)
MASS = 1.0
SLOP = 0.01              # collision_slop: allowed overlap of resting contacts, px
MAX_OMEGA_H = 0.2        # sqrt(g/L) x h above this is refused: the rods cannot hold (docstring)

CRADLE_PARAMS: tuple[Param, ...] = (
    common("hertz", default=120),
    common("substeps", default=30, help="sub-steps per step: a cradle needs small steps"),
    Param("balls", 5, int, 2, 9, help="number of balls in the row"),
    Param("lifted", 1, int, 1, 8, help="balls lifted and released (at most balls-1)"),
    Param("angle", 30.0, float, 1.0, 60.0, help="lift angle of the released balls, degrees"),
    Param("gap", 0.02, float, -1.0, 20.0,
          help="space between neighbouring balls at rest, px (< 0: pressed together)"),
    Param("elasticity", 0.9999999, float, 0.0, 1.0, help="elasticity of each ball (1 = no loss)"),
    Param("damping", 1.0, float, 0.0, 1.0,
          help="space.damping: fraction of velocity kept per second (1 = none)", rebuild=False),
)

BALL_COLOR = (86, 180, 233)
LIFTED_COLOR = (240, 200, 70)
STRING_COLOR = (200, 200, 210)
REST_COLOR = (90, 95, 110)


def build_cradle(space: pymunk.Space, balls: int, radius: float, lifted: int, *,
                 gap: float = 0.02, angle: float = 30.0, elasticity: float = 0.9999999,
                 centre_x: float = 480.0) -> list[pymunk.Body]:
    """The classwork (and the reference answer of exercises/newtons_cradle.py): `balls` balls
    hanging on STRING-long strings from anchors on the bar at ANCHOR_Y, `gap` px apart at rest,
    centred on centre_x; the first `lifted` are pulled out to the left by `angle` degrees.
    Returns the bodies in order along the row."""
    pitch = 2 * radius + gap
    lift = math.radians(angle)
    bodies = []
    for i in range(balls):
        ax, ay = centre_x + (i - (balls - 1) / 2) * pitch, ANCHOR_Y
        body = pymunk.Body(MASS, pymunk.moment_for_circle(MASS, 0, radius))
        th = -lift if i < lifted else 0.0       # the first k balls are pulled out to the left
        body.position = (ax + STRING * math.sin(th), ay + STRING * math.cos(th))
        ball = pymunk.Circle(body, radius)
        ball.elasticity = elasticity
        ball.friction = 0.0
        string = pymunk.PinJoint(space.static_body, body, (ax, ay), (0, 0))
        string.error_bias = 0.0                # correct the whole length error every step
        space.add(body, ball, string)
        bodies.append(body)
    return bodies


def string_of(space: pymunk.Space, body: pymunk.Body) -> tuple[pymunk.PinJoint, tuple]:
    """The PinJoint that hangs `body` from a static body, and its anchor point in the world."""
    for joint in space.constraints:
        if isinstance(joint, pymunk.PinJoint) and body in (joint.a, joint.b):
            other, anchor = (joint.b, joint.anchor_b) if joint.a is body else (joint.a,
                                                                              joint.anchor_a)
            if other.body_type == pymunk.Body.STATIC:
                return joint, tuple(other.local_to_world(anchor))
    raise ValueError("a ball hangs on no string (a PinJoint to a static body)")


class NewtonsCradleScene(PymunkScene):
    """Newton's cradle: lift k balls, release, and k balls swing out at the other end while the
    middle ones stay still, if the impulse solver sees one two-ball collision at a time. The HUD
    gives the verdict ("2 in, 2 out") and the energy left.

    Mouse: drag a ball (letting go re-arms the verdict). Try to break it: gap -0.01 (balls
    pressed together), gap 5, substeps 2, elasticity 0.9, damping 0.99.
    """

    name = "newtons_cradle"
    arrow_name = "ball"
    title = "Newton's cradle (pymunk)"
    category = "Rigid bodies (pymunk)"
    blowup_reach = 1e6      # px beyond the world: a body held by rods out there has blown up
    params = PYMUNK_PARAMS + CRADLE_PARAMS
    world_keys = ("space", "bodies", "strings", "track")
    color_key = ((LIFTED_COLOR, "lifted and released"), (BALL_COLOR, "at rest"))
    metric_units = {"middle_max_drift": Unit("px", resolution=0.01),
                    "energy_ratio": Unit("%", 100.0), "release_speed": Unit("px/s"),
                    "out_speed_ratio": Unit("%", 100.0)}
    tries = (
        Try("Two balls in", {"lifted": 2}, "two balls swing in, two swing out at the far end"),
        Try("Balls pressed together", {"gap": -0.01},
            "no gap: every contact is solved at once; watch balls_out and the middle balls move"),
        Try("A 5 px gap", {"gap": 5}, "watch the middle balls move (middle drift) and the "
            "verdict"),
        Try("Two substeps", {"substeps": 2}, "bigger steps: watch the middle drift and the "
            "verdict"),
    )

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The anchor bar and every place a ball can swing to: the lift angle and 10 degrees
        more either way (no collision gives a ball more than it came in with), 60 where
        pressed-together balls push apart (a gap below 0 puts energy in) and where a subclass
        has no such settings (the exercise: a student's collisions may put energy in). A
        fixed 60 degrees left the 30-degree cradle 20 % smaller than the room allowed."""
        gap, angle = self.p.get("gap", -1.0), self.p.get("angle", 60.0)
        swing = 60.0 if gap < 0 else min(angle + 10.0, 60.0)
        reach = STRING * math.sin(math.radians(swing)) + RADIUS + 8
        left, right = self.anchors[:, 0].min() - reach, self.anchors[:, 0].max() + reach
        return (left, ANCHOR_Y - 20, right - left, STRING + RADIUS + 40)

    # ----- building -------------------------------------------------------------------------
    @classmethod
    def check_combination(cls, values) -> None:
        # Refused on the command line and in the panel (lower `lifted` before `balls`).
        if values["lifted"] > values["balls"] - 1:
            raise ParamError(f"lifted={values['lifted']} does not fit a row of {values['balls']} "
                             f"balls; accepted: lifted from 1 to balls-1 ({values['balls'] - 1})")
        # (the step is checked with g even if the gravity effect is off: it may come back on)
        per_second = values["hertz"] * values["substeps"]
        omega = math.sqrt(values["g"] / STRING)
        if omega / per_second > MAX_OMEGA_H:
            need = math.ceil(omega / MAX_OMEGA_H)
            raise ParamError(f"hertz x substeps = {per_second} is too coarse for a cradle at g "
                             f"{values['g']:g}: the rods stretch and the energy means nothing; "
                             f"accepted: hertz x substeps >= {need}")

    def build_space(self, space: pymunk.Space) -> None:
        space.collision_slop = SLOP
        space.damping = self.p["damping"]
        self.bodies: list[pymunk.Body] = self.add_balls(space)
        strings = [string_of(space, b) for b in self.bodies]
        self.strings: list[pymunk.PinJoint] = [joint for joint, _ in strings]
        self.anchors = np.array([anchor for _, anchor in strings])
        self.rest = self.anchors + np.array([(0.0, s.distance) for s in self.strings])
        self._rest_x = self.rest[:, 0].copy()
        self._groups_cache = None
        self.arm(self.p["lifted"])

    def add_balls(self, space: pymunk.Space) -> list[pymunk.Body]:
        """The balls on their strings, in order along the row (the exercise scene replaces this
        with the student's build_cradle)."""
        return build_cradle(space, self.p["balls"], RADIUS, self.p["lifted"], gap=self.p["gap"],
                            angle=self.p["angle"], elasticity=self.p["elasticity"],
                            centre_x=self.world_size[0] / 2)

    def arm(self, k: int, side: int = +1) -> None:
        """Start a measurement: k balls count as lifted, at the left end (side +1, they swing in
        to the right) or the right end (side -1); the energy now is the baseline, and the first
        impact is still to come."""
        lifted = np.arange(k) if side > 0 else np.arange(len(self.bodies) - k, len(self.bodies))
        dx = np.abs(self.displacements()[lifted])
        self.track = {
            "lifted": k,
            "side": side,
            "amplitude": float(dx.mean()) if k else 0.0,   # how far out they were let go, px
            "energy0": self.energy(),
            "impact_time": None,          # simulated time of the first impact (None before)
            "release_speed": 0.0,
            "last_speed": 0.0,            # mean speed of the lifted balls at the previous step
            "reach": np.zeros(self.p["balls"]),       # furthest swing onwards since impact
            "top_speed": np.zeros(self.p["balls"]),   # top speed since impact
            "balls_out": 0,
            "window_open": False,
            "middle_max_drift": 0.0,
        }

    def half_period(self) -> float:
        """Half the small-angle period of one string, pi sqrt(L/g) (inf without gravity)."""
        g = self.gravity()
        return math.pi * math.sqrt(STRING / g) if g > 0 else math.inf

    # ----- stepping -------------------------------------------------------------------------
    def apply_settings(self) -> None:
        super().apply_settings()
        self.space.damping = self.p["damping"]

    def after_step(self) -> None:
        self.observe()

    def xv(self) -> tuple[np.ndarray, np.ndarray]:
        """Positions (n, 2) and velocities (n, 2) of the balls, in order along the row."""
        rows = self.rows_of(self.bodies)        # (one batch read a step, shared)
        return rows[:, :2], rows[:, 3:5]

    def displacements(self) -> np.ndarray:
        """Each ball's horizontal distance from its rest position, px (+ = to the right)."""
        return np.array([b.position.x for b in self.bodies]) - self.rest[:, 0]

    def groups(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Index arrays of the lifted balls, the far balls expected out, and the middle balls
        (neither; empty when 2k >= N), for the current measurement."""
        return self._groups()[:3]

    def _groups(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, slice, np.ndarray]:
        """groups(), the middle balls as a slice, and a mask of the balls not lifted: made once
        per measurement (observe reads them every step)."""
        k, n, side = self.track["lifted"], len(self.bodies), self.track["side"]
        cache = self._groups_cache
        if cache is None or cache[0] != (k, n, side):
            left, right = np.arange(k), np.arange(n - k, n)
            middle = np.arange(k, max(k, n - k))
            lifted, far = (left, right) if side > 0 else (right, left)
            others = np.ones(n, dtype=bool)
            others[lifted] = False
            cache = self._groups_cache = ((k, n, side), (lifted, far, middle,
                                                         slice(k, max(k, n - k)), others))
        return cache[1]

    def observe(self) -> None:
        """Per step bookkeeping for the metrics: the first impact, the release speed, who swings
        out in the half-swing after it, and the middle balls' drift."""
        t = self.track
        lifted, _, middle, middle_slice, not_lifted = self._groups()
        rows = self.rows_of(self.bodies)         # (x, y, angle, vx, vy, w) of each ball
        speed = np.hypot(rows[:, 3], rows[:, 4])
        onwards = t["side"] * (rows[:, 0] - self._rest_x)   # displacement in the swing's direction
        if len(middle):         # (a[a.argmax()]: the max, NaN included, in one cheap call)
            drift = np.abs(onwards[middle_slice])
            t["middle_max_drift"] = max(t["middle_max_drift"], float(drift[drift.argmax()]))
        if t["impact_time"] is None and len(lifted):
            # The impact: the lifted group is at the bottom (its leading ball within half a
            # radius of rest) and a ball outside it has picked up speed.
            lead = lifted[-1] if t["side"] > 0 else lifted[0]
            others = speed[not_lifted]
            if (abs(onwards[lead]) < 0.5 * RADIUS
                    and others[others.argmax()] > max(0.25 * t["last_speed"], 1.0)):
                t["impact_time"] = self.time
                t["release_speed"] = t["last_speed"]
                t["window_open"] = True
            else:
                t["last_speed"] = float(speed[lifted].mean())
        if t["window_open"]:
            t["reach"] = np.maximum(t["reach"], onwards)
            t["top_speed"] = np.maximum(t["top_speed"], speed)
            t["balls_out"] = int(np.count_nonzero(t["reach"] > 0.5 * t["amplitude"]))
            if self.time - t["impact_time"] > 0.9 * self.half_period():
                t["window_open"] = False

    # ----- energy -----------------------------------------------------------------------------
    def energy(self) -> float:
        """Kinetic + potential energy of the balls, potential zero with every ball at rest."""
        xy, v = self.xv()
        w = np.array([b.angular_velocity for b in self.bodies])
        moment = np.array([b.moment for b in self.bodies])
        # a ball of infinite moment (pymunk.Body(m, inf): it cannot spin) has no spin energy;
        # inf * 0 would make the whole energy NaN
        spin = np.where(np.isfinite(moment), 0.5 * np.where(np.isfinite(moment), moment, 0.0)
                        * w * w, 0.0)
        kinetic = 0.5 * MASS * float((v ** 2).sum()) + float(spin.sum())
        height = self.rest[:, 1] - xy[:, 1]               # y is down: up is rest_y - y
        return kinetic + MASS * self.gravity() * float(height.sum())

    def gravity_changed(self) -> None:
        """g (or the gravity effect) changed: the energy now, with the new g, is the baseline."""
        self.track["energy0"] = self.energy()

    # ----- mouse ----------------------------------------------------------------------------
    def dropped(self) -> None:
        """After a drag: the balls more than a radius from rest at one end of the row are the new
        lifted group (the larger run if both ends are out); none if every ball is out."""
        out = np.abs(self.displacements()) > RADIUS
        # the run of displaced balls at each end: argmin finds the first ball at rest (0 if
        # there is none, so every ball out gives k = 0)
        left, right = int(np.argmin(out)), int(np.argmin(out[::-1]))
        self.arm(max(left, right), side=+1 if left >= right else -1)

    # ----- state ----------------------------------------------------------------------------
    def state_arrays(self) -> Iterable[np.ndarray]:
        return (self.body_state(),)      # positions, angles, velocities and spins, in one read

    # ----- reporting ------------------------------------------------------------------------
    def energies(self):
        """Energy bars: kinetic (with spin) and potential of the balls, as `energy()`, against
        the energy at release."""
        from app.energy import Energies
        total = self.energy()
        xy, _ = self.xv()
        potential = MASS * self.gravity() * float((self.rest[:, 1] - xy[:, 1]).sum())
        return Energies((("kinetic", total - potential), ("gravity", potential)),
                        self.track["energy0"], zero="every ball hanging at rest",
                        losses="impacts (elasticity below 1), damping; a drag with the mouse "
                               "puts energy in", unit="kg px^2/s^2")

    def metrics(self) -> dict[str, float]:
        t = self.track
        k = t["lifted"]
        e0 = t["energy0"]
        far = t["top_speed"][self.groups()[1]]
        ratio = (float(far.min()) / t["release_speed"]
                 if len(far) and t["release_speed"] > 0 else 0.0)
        return {
            "lifted": k,
            "balls_out": t["balls_out"],
            "middle_max_drift": t["middle_max_drift"],
            # no energy at release (gravity off, nothing moving): no ratio exists (null, "-")
            "energy_ratio": self.energy() / e0 if e0 > 0 else None,
            "release_speed": t["release_speed"],
            "out_speed_ratio": ratio,
        }

    def hud_lines(self) -> list[str]:
        m = self.metrics()
        k, out = int(m["lifted"]), int(m["balls_out"])
        lines = []
        t = self.track
        if self.mouse_joint is not None:
            lines.append("held by the mouse: no verdict while your hand moves the balls")
            return lines
        if k == 0:
            lines.append("nothing lifted: drag a ball out and let go")
        elif t["impact_time"] is None:
            lines.append(f"{k} lifted, released: waiting for the impact")
        elif t["window_open"]:
            left = t["impact_time"] + 0.9 * self.half_period() - self.time
            lines.append(f"{k} in: the far end is swinging out; the verdict in {left:.1f} s")
        else:
            failed = self.failed_criteria(m)
            lines.append(f"{k} in, {out} out: "
                         + ("NOT like a real cradle" if failed else "like a real cradle"))
            if failed:
                lines.append("why: " + "; ".join(failed))
                causes = self.suspects()
                if causes:
                    lines.append("the setting that breaks it: " + "; ".join(causes))
        ratio = m["energy_ratio"]
        lines.append(f"energy left: {self.shown('energy_ratio', ratio)}")
        return lines

    def hud_details(self) -> list[str]:
        m = self.metrics()
        drag = "LMB: drag a ball (letting go re-arms the verdict)"
        if self.track["impact_time"] is None or self.track["window_open"]:
            return [drag]
        return [drag, f"out speed {self.shown('out_speed_ratio', m['out_speed_ratio'])} of "
                f"{self.shown('release_speed', m['release_speed'])}; middle drift "
                f"{self.shown('middle_max_drift', m['middle_max_drift'])}"]

    @staticmethod
    def failed_criteria(m: dict) -> list[str]:
        """What a real cradle does and this run did not: k balls out, the middle ones still
        (under 2 px), the far ones leaving at 97 % of the release speed or more."""
        k, out = int(m["lifted"]), int(m["balls_out"])
        failed = []
        if out != k:
            failed.append(f"{out} out, not {k}")
        if m["middle_max_drift"] >= 2.0:
            failed.append(f"the middle moved {m['middle_max_drift']:.1f} px (>= 2)")
        if m["out_speed_ratio"] < 0.97:
            failed.append(f"out at {100 * m['out_speed_ratio']:.0f}% of the speed in (< 97%)")
        return failed

    def suspects(self) -> list[str]:
        """The settings, changed from the defaults, that break a cradle, and how (the module
        docstring has the why at length)."""
        p = self.p
        base = {prm.name: prm.default for prm in self.all_params()}
        out = []
        if p["gap"] <= 0:
            out.append(f"gap {p['gap']:g}: touching balls, every contact solved at once")
        elif p["gap"] > 1.0:
            out.append(f"gap {p['gap']:g} px: each impact carries a ball across the gap")
        per, per0 = p["hertz"] * p["substeps"], base["hertz"] * base["substeps"]
        if per < per0:
            out.append(f"hertz x substeps {per} (default {per0}): balls found overlapping")
        if p["elasticity"] < base["elasticity"]:
            out.append(f"elasticity {p['elasticity']:g}: each impact loses energy")
        if p["damping"] < 1.0:
            out.append(f"damping {p['damping']:g}: air drag")
        if p["iterations"] < base["iterations"]:
            out.append(f"iterations {p['iterations']}: the solver stops short")
        return out

    # ----- drawing --------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, view) -> None:
        a, b = self.anchors[:, 0].min() - 2 * RADIUS, self.anchors[:, 0].max() + 2 * RADIUS
        D.draw_segment(surface, view, (a, ANCHOR_Y - 6), (b, ANCHOR_Y - 6), 4, D.STATIC)
        for (rx, ry) in self.rest:          # tick marks under the rest positions
            pygame.draw.line(surface, REST_COLOR, view.pt((rx, ry + RADIUS + 4)),
                             view.pt((rx, ry + RADIUS + 14)), px(3))
        lifted = set(self.groups()[0].tolist())
        for i, (body, string) in enumerate(zip(self.bodies, self.strings)):
            D.draw_pin_joint(surface, view, string, STRING_COLOR, dot=3)   # (the ball hides b's dot)
            # (px: the strings and ticks stay readable from the back row)
            color = LIFTED_COLOR if i in lifted else BALL_COLOR
            D.draw_circle(surface, view, body.position, body.angle, RADIUS, color)
        self.draw_mouse(surface, view)
