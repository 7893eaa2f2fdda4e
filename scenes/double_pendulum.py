"""Double pendulum (the lecture's exercise): two bobs on pin joints, released high, beside a
ghost of the same pendulum integrated from its equations of motion. Watch the engine and the exact
solution part ways.

What it shows.
  * Chaos: released high, the double pendulum is so sensitive to its state that pymunk's tiny
    per-step errors (a first-order integrator with an iterative joint solver) grow exponentially.
    The ghost (orange) is the reference, app/physics/double_pendulum_ode.py: Lagrange's equations
    of two point masses on massless rods, integrated with RK4 at a step that adapts to the motion
    so that its own energy stays within 1e-8 per simulated second (`reference_energy_drift`, under
    1e-6 over a minute at every corner of the sliders, tested). Both start identical; after a few
    seconds they part. The moment the tips are more than 10 px apart is marked on screen (a cross
    where it happened) and reported as `divergence_time`. Released low (angles of ~10 degrees) the
    motion is regular and the two stay together for good.
  * Energy: a pendulum without friction keeps its energy. An engine that loses or gains energy
    shows it in the HUD (`energy_drift`, relative to the energy at release). When the drift passes
    5% either way the HUD says "the engine blew up" (or "bled its energy", for a loss) and
    `engine_blowup_t` records when (seconds after the release): that is a numerical failure of
    the engine, not chaos, and the parting that follows proves nothing about chaos.
  * error_bias: pymunk's pin joint is "soft" by default: it corrects only part of the length error
    each step (error_bias = fraction of the error left after one second, 0.0018 by default). Which
    setting wins depends on the masses. At moderate mass ratios (the default 1 : 1) the lazy
    correction bleeds energy away, about 17% in a minute at hertz 120 x substeps 10, while
    `error_bias` 0 (correct all of it each step, the default here) keeps the drift under 0.1% over
    a minute. With a light upper bob under a heavy one (mass1 0.2, mass2 20) neither holds:
    correcting everything at once kicks the light bob and the energy grows about 1400-fold within
    10 s (the engine blows up), while pymunk's 0.0018 loses about half of it in the first second
    and then holds what is left. The soft default fails gently, the stiff one violently. Try both.
  * Why point masses match pymunk's round bobs: the pins hold each bob at its centre of mass, so
    no joint force turns a bob; its spin stays zero and drops out of the energy.

Effects: `reference` (the ghost; off = not integrated at all), `trail` (a fading trail of the
tip, and of the ghost's tip), `gravity` (off: legal but odd, the pendulum spins at constant energy;
the number is the param `g`).

If the reference cannot follow (its step would have to shrink below 1e-8 s, or one physics step
would cost it more than 200,000 RK4 steps; no setting within the ranges was seen to do it: this
guards the unexpected), the ghost is frozen and hidden, the HUD says "reference blew up at t =
...", and the engine's run goes on: the ghost's failure is not the engine's, so it never makes the
scene's state non-finite. Drag a bob to restart the ghost.

Metrics (DESIGN.md): `energy_drift` ((E - E0) / E0 now, E measured from the lowest configuration),
`reference_divergence` (px between the pymunk tip and the ghost's tip now; null with the
reference off or blown up), `divergence_time` (simulated seconds from release until the tips
first part by more than 10 px; null while they have not, and with the reference off). Also
`energy_drift_max` (largest |drift| seen), `engine_blowup_t` (seconds from release until |drift|
first passed 5%; null while it has not), `pin_error` (largest rod length error now, px),
`reference_energy_drift` (the ghost's own relative energy error since the release) and
`reference_blowup_t` (simulated time at which the reference could not follow; null while it has
not). On screen a value that does not exist yet is "-".

Mouse: drag a bob with the left button. When you let go, the ghost restarts from the dragged
state (positions and velocities), the energy baseline is the energy at that moment, and the
divergence clock starts again from zero: a new release. Changing g (or gravity) while it runs
re-baselines the energy (the potential energy depends on g; the ghost switches g with the engine).
"""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np
import pygame
import pymunk

from app.draw import pymunk_draw as D
from app.draw.ring import PendingRing, Ring
from app.physics.double_pendulum_ode import DoublePendulumODE
from app.pymunk_scene import PYMUNK_EFFECTS, PYMUNK_PARAMS, PymunkScene
from app.draw.text import px
from app.scene import Effect, Param, Try, Unit, common

PIVOT = (480.0, 350.0)
BOB_RADIUS = 14.0
PART_PX = 10.0           # tips further apart than this: the engine and the reference have parted
BLOWUP_DRIFT = 0.05      # |energy drift| beyond this: the engine blew up (not chaos)

PENDULUM_PARAMS: tuple[Param, ...] = (
    common("hertz", default=120),
    common("substeps", default=10, help="sub-steps per step (pin joints are stiffer with more)"),
    Param("angle1", 120.0, float, -180.0, 180.0, help="release angle of the upper rod, degrees "
          "from straight down"),
    Param("angle2", 150.0, float, -180.0, 180.0, help="release angle of the lower rod, degrees"),
    Param("length1", 160.0, float, 20.0, 170.0, help="upper rod length, px"),
    Param("length2", 160.0, float, 20.0, 170.0, help="lower rod length, px"),
    Param("mass1", 1.0, float, 0.05, 20.0, help="upper bob mass"),
    Param("mass2", 1.0, float, 0.05, 20.0, help="lower bob mass"),
    Param("error_bias", 0.0, float, 0.0, 1.0, help="pin joints: fraction of the length error left "
          "after 1 s (pymunk's default 0.0018; 0 = fix it all each step: better at moderate "
          "mass ratios, worse with a light upper bob)", rebuild=False),
    Param("trail_seconds", 3.0, float, 0.1, 30.0, help="length of the tip's trail, seconds"),
)

ROD_COLOR = (235, 235, 235)
BOB_COLOR = (86, 180, 233)
GHOST_COLOR = (230, 159, 0)
TRAIL_COLOR = (86, 180, 233)
MARK_COLOR = (230, 97, 76)


def relative_drift(energy: float, energy0: float) -> float:
    """(E - E0) / E0, the energy drift since the release; 0 while E0 is about 0 (released at
    rest, hanging straight down: no drift to measure against)."""
    return (energy - energy0) / energy0 if energy0 > 1e-9 else 0.0


def build_double_pendulum(space: pymunk.Space, anchor: tuple[float, float],
                          lengths: tuple[float, float], masses: tuple[float, float],
                          angles: tuple[float, float]) -> tuple[pymunk.Body, pymunk.Body]:
    """The lecture's exercise (and the reference answer of exercises/double_pendulum.py): two
    bobs on PinJoint rods from `anchor`, at `angles` (radians from straight down, y down), the
    joints correcting their whole length error every step (error_bias 0). Returns the bobs."""
    (l1, l2), (t1, t2) = lengths, angles
    p1 = (anchor[0] + l1 * math.sin(t1), anchor[1] + l1 * math.cos(t1))
    p2 = (p1[0] + l2 * math.sin(t2), p1[1] + l2 * math.cos(t2))
    bobs = []
    for mass, pos in zip(masses, (p1, p2)):
        body = pymunk.Body(mass, pymunk.moment_for_circle(mass, 0, BOB_RADIUS))
        body.position = pos
        shape = pymunk.Circle(body, BOB_RADIUS)       # for grabbing; bobs never collide
        shape.filter = pymunk.ShapeFilter(group=1)
        space.add(body, shape)
        bobs.append(body)
    joints = [pymunk.PinJoint(space.static_body, bobs[0], anchor, (0, 0)),
              pymunk.PinJoint(bobs[0], bobs[1], (0, 0), (0, 0))]
    for joint in joints:
        joint.error_bias = 0.0
    space.add(*joints)
    return bobs[0], bobs[1]


class DoublePendulumScene(PymunkScene):
    """Double pendulum: pymunk's bobs on pin joints beside an orange ghost integrated from the
    equations of motion with RK4 at a step that keeps its energy exact. Released high, the motion is chaotic and the two
    part after a few seconds (marked on screen); released low they stay together. The HUD shows
    the energy drift.

    Mouse: drag a bob; letting go restarts the ghost from the dragged state. Effects: reference
    (the ghost), trail. Try error_bias 0.0018 (pymunk's default) or substeps 1.
    """

    name = "double_pendulum"
    arrow_name = "bob"
    error_metric, error_label = "reference_divergence", "off the RK4 reference"
    title = "Double pendulum vs. its equations"
    category = "Rigid bodies (pymunk)"
    blowup_reach = 1e6      # px beyond the world: a body held by rods out there has blown up
    _energy_terms = None    # (bobs, each bob's terms of energy()): made for these bobs and g
    params = PYMUNK_PARAMS + PENDULUM_PARAMS
    effects = PYMUNK_EFFECTS + (
        Effect("reference", True, "the ghost: the same pendulum integrated with RK4"),
        Effect("trail", True, "a fading trail of the tip (and of the ghost's tip)"))
    world_keys = ("space", "bobs", "joints", "ode", "trail", "ghost_trail", "track")
    color_key = (((230, 159, 0), "ghost: the exact equations (RK4)"),
                 ((86, 180, 233), "pymunk"),
                 ((230, 97, 76), f"x: parted by {PART_PX:g} px"))   # (short: with pymunk,
    # one row of the key at 1024x768 with F2)
    metric_units = {"energy_drift": Unit("%", 100.0, resolution=1e-4),
                    "energy_drift_max": Unit("%", 100.0, resolution=1e-4),
                    "reference_energy_drift": Unit("%", 100.0, resolution=1e-6),
                    "reference_divergence": Unit("px", resolution=0.01),
                    "divergence_time": Unit("s"), "engine_blowup_t": Unit("s"),
                    "reference_blowup_t": Unit("s"), "pin_error": Unit("px", resolution=1e-3)}
    tries = (
        Try("Released low", {"angle1": 20, "angle2": 20},
            "small swings are not chaotic: the ghost and the bobs stay within a few px"),
        Try("Released high: chaos", {"angle1": 120, "angle2": 150},
            "within about 10 s (8 s at the other defaults) the bobs leave the ghost; the X "
            "marks where they parted"),
        Try("pymunk's error_bias", {"error_bias": 0.0018},
            "the pins let the rods stretch a little, so energy drift grows (HUD)"),
        Try("One substep", {"substeps": 1},
            "bigger steps for pymunk: the energy drift in the HUD grows"),
    )
    comparisons = (     # "try this" cards that run variants side by side (--compare)
        Try("1 vs 10 substeps", {},
            "pymunk at 1 substep (A) and 10 (B), each beside the RK4 reference: B stays with its "
            "ghost longer and drifts less in energy, for more ms per step; chaos parts both in "
            "the end", compare=({"substeps": 1}, {"substeps": 10})),
    )

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The square the two rods can reach around the pivot."""
        r = self.p["length1"] + self.p["length2"] + BOB_RADIUS + 12
        return (PIVOT[0] - r, PIVOT[1] - r, 2 * r, 2 * r)

    # ----- building -------------------------------------------------------------------------
    def build_space(self, space: pymunk.Space) -> None:
        p = self.p
        t1, t2 = math.radians(p["angle1"]), math.radians(p["angle2"])
        l1, l2 = p["length1"], p["length2"]
        self.bobs: list[pymunk.Body] = list(self.add_bobs(space, (l1, l2), (t1, t2)))
        self.joints: list[pymunk.Constraint] = list(space.constraints)   # the two rods
        self.ode = DoublePendulumODE(l1, l2, p["mass1"], p["mass2"], self.gravity(),
                                     (t1, t2, 0, 0))
        n = max(2, round(p["trail_seconds"] * p["hertz"]))
        # the tip's last positions, one per physics step (put into the array when drawn)
        self.trail = PendingRing(n, 2)
        self.ghost_trail = PendingRing(n, 2)
        self.new_release()

    def add_bobs(self, space: pymunk.Space, lengths: tuple[float, float],
                 angles: tuple[float, float]) -> tuple[pymunk.Body, pymunk.Body]:
        """The two bobs on their rods (the exercise scene replaces this with the student's
        build_double_pendulum)."""
        return build_double_pendulum(space, PIVOT, lengths, (self.p["mass1"], self.p["mass2"]),
                                     angles)

    def new_release(self) -> None:
        """Start comparing from the engine's state now: the ghost takes it over, the energy now is
        the baseline, the divergence clock restarts, the trails are cleared."""
        b1, b2 = self.bobs
        self.ode.set_from_cartesian(PIVOT, b1.position, b1.velocity, b2.position, b2.velocity)
        self.ode.g = self.gravity()
        self.track = {"energy0": self.energy(), "start": self.time, "divergence_time": None,
                      "mark": None, "energy_drift_max": 0.0, "ref_blowup": None,
                      "engine_blowup": None}
        self.trail.clear()
        self.ghost_trail.clear()

    # ----- stepping -------------------------------------------------------------------------
    def apply_settings(self) -> None:
        super().apply_settings()
        for joint in self.joints:
            joint.error_bias = self.p["error_bias"]

    def after_step(self) -> None:
        if self.mouse_joint is not None:       # held by the mouse: nothing to compare yet
            return
        t = self.track
        rows = self.rows_list(self.bobs, guard=True)   # (x, y, angle, vx, vy, w) of each bob
        drift = abs(relative_drift(self.energy(rows), t["energy0"]))
        if drift > t["energy_drift_max"]:          # (max(seen, drift): a NaN leaves it)
            t["energy_drift_max"] = drift
        if t["engine_blowup"] is None and not drift <= BLOWUP_DRIFT:   # (NaN counts)
            t["engine_blowup"] = self.time - t["start"]
        tip = rows[1][0], rows[1][1]               # (the batch read's copy of bobs[1].position)
        on = self.on
        if self.ghost_alive():
            if not self.ode.advance(self.dt):
                t["ref_blowup"] = self.time     # frozen at its last finite state, hidden
                return
            ghost_tip = self.ode.tip(PIVOT)
            if t["divergence_time"] is None and math.dist(tip, ghost_tip) > PART_PX:
                t["divergence_time"] = self.time - t["start"]
                t["mark"] = (float(tip[0]), float(tip[1]))
            if "trail" in on:
                self.ghost_trail.append(ghost_tip)
        if "trail" in on:
            self.trail.append(tip)

    def ghost_alive(self) -> bool:
        """The reference is on and has not blown up since the release."""
        return "reference" in self.on and self.track["ref_blowup"] is None

    def gravity_changed(self) -> None:
        """g (or the gravity effect) changed: the ghost switches g with the engine, and the energy
        now, with the new g, is the baseline."""
        self.ode.g = self.gravity()
        self.ode.set_state(self.ode.state)      # the ghost's energy baseline moves with g too
        self._energy_terms = None               # (the bobs' weights: made again with this g)
        self.track["energy0"] = self.energy()

    def settings_changed(self, names: set[str]) -> None:
        super().settings_changed(names)
        if "reference" in names and "reference" in self.on:   # the ghost restarts from the engine
            self.new_release()
        if "trail" in names and "trail" not in self.on:
            self.trail.clear()
            self.ghost_trail.clear()

    # ----- mouse ----------------------------------------------------------------------------
    def dropped(self) -> None:
        self.new_release()

    # ----- measuring ------------------------------------------------------------------------
    def energy(self, rows: Sequence | None = None) -> float:
        """Kinetic (incl. spin) + potential energy of the bobs, zero when both hang straight down
        at rest (y is down, so a bob's height above its lowest point is lowest_y - y). rows: the
        bobs' rows as Python floats (rows_list), if already read."""
        # the terms are made again for new bobs (a build: the lengths are rebuild params; a
        # restore) and for a new g (gravity_changed forgets them)
        cache = self._energy_terms
        if cache is None or cache[0] is not self.bobs:
            g = self.gravity()
            l1, l2 = self.p["length1"], self.p["length2"]
            lowest = (PIVOT[1] + l1, PIVOT[1] + l1 + l2)
            # per bob: (mass, half its moment: 0 for a bob of infinite moment, which cannot
            # spin (inf * 0 is NaN), its weight, the height of its lowest point)
            cache = self._energy_terms = (self.bobs, [
                (0.5 * mass, 0.5 * moment if math.isfinite(moment) else 0.0, mass * g, y0)
                for (mass, moment), y0 in zip(self.bob_masses(), lowest)])
        terms = cache[1]
        if rows is not None and len(terms) == 2:   # (after_step's: the loop below, written out)
            (_, y, _, vx, vy, w), (_, y2, _, vx2, vy2, w2) = rows
            (m, j, g, y0), (m2, j2, g2, y02) = terms
            return 0.0 + (m * (vx * vx + vy * vy) + (j * w * w if j else 0.0) + g * (y0 - y)) \
                + (m2 * (vx2 * vx2 + vy2 * vy2) + (j2 * w2 * w2 if j2 else 0.0) + g2 * (y02 - y2))
        e = 0.0
        # each bob's (x, y, angle, vx, vy, w) from the step's one batch read
        for (_, y, _, vx, vy, w), (half_mass, half_moment, weight, y0) in zip(
                self.rows_of(self.bobs).tolist() if rows is None else rows, cache[1]):
            # x * x, not x ** 2: a float ** overflows with an exception, * gives inf
            e += half_mass * (vx * vx + vy * vy) + (half_moment * w * w if half_moment
                                                      else 0.0) + weight * (y0 - y)
        return e

    def bob_masses(self) -> list[tuple[float, float]]:
        """(mass, moment) of each bob, read from pymunk once per bobs list."""
        cache = getattr(self, "_bob_masses", None)
        if cache is None or cache[0] is not self.bobs:
            cache = self._bob_masses = (self.bobs, [(b.mass, b.moment) for b in self.bobs])
        return cache[1]

    def energy_drift(self, rows: Sequence | None = None) -> float:
        return relative_drift(self.energy(rows), self.track["energy0"])

    def pin_error(self) -> float:
        b1, b2 = self.bobs
        return max(abs(math.dist(PIVOT, b1.position) - self.p["length1"]),
                   abs(math.dist(b1.position, b2.position) - self.p["length2"]))

    def divergence(self) -> float | None:
        """Distance between the engine's tip and the ghost's tip now, px (None: no reference, or
        it blew up)."""
        if not self.ghost_alive():
            return None
        return math.dist(self.bobs[1].position, self.ode.positions(PIVOT)[1])

    # ----- state ----------------------------------------------------------------------------
    def state_arrays(self) -> Iterable[np.ndarray]:
        return (self.body_state(), np.array(self.ode.state))

    # ----- reporting ------------------------------------------------------------------------
    def energies(self):
        """Energy bars: kinetic (with spin) and potential of the bobs, as `energy()`, against
        the energy at release."""
        from app.energy import Energies
        g, l1, l2 = self.gravity(), self.p["length1"], self.p["length2"]
        lowest = (PIVOT[1] + l1, PIVOT[1] + l1 + l2)
        potential = sum(b.mass * g * (y0 - b.position.y) for b, y0 in zip(self.bobs, lowest))
        return Energies((("kinetic", self.energy() - potential), ("gravity", potential)),
                        self.track["energy0"], zero="both bobs hanging straight down, at rest",
                        losses="pymunk's joints and step (the exact pendulum loses none); a drag "
                               "with the mouse puts energy in", unit="kg px^2/s^2")

    def metrics(self) -> dict[str, float | None]:
        on = "reference" in self.on
        t = self.track
        return {"energy_drift": self.energy_drift(),
                "reference_divergence": self.divergence(),
                "divergence_time": t["divergence_time"] if on else None,
                # the worst includes now (a drift read between steps, e.g. while held)
                "energy_drift_max": max(t["energy_drift_max"], abs(self.energy_drift())),
                "engine_blowup_t": t["engine_blowup"],
                "pin_error": self.pin_error(),
                "reference_energy_drift": self.ode.energy_drift() if self.ghost_alive() else None,
                "reference_blowup_t": t["ref_blowup"] if on else None}

    def hud_lines(self) -> list[str]:
        m = self.metrics()
        # phrases parted by '  |  ', each short enough for a row at 1024x768 with F2 (a row
        # breaks between them: never "0.67 px apart" / "after 4.5 s")
        lines = [f"energy drift {100 * m['energy_drift']:+.3f}%  |  "
                 f"worst {100 * m['energy_drift_max']:.3f}%"]
        if m["engine_blowup_t"] is not None:
            what = "blew up" if m["energy_drift"] > 0 else "bled its energy"
            lines.append(f"the engine {what} at {m['engine_blowup_t']:.2f} s  |  drift past "
                         f"{100 * BLOWUP_DRIFT:.0f}%: numerics, not chaos")
        if self.mouse_joint is not None:
            lines.append("held by the mouse  |  the ghost restarts when you let go")
        elif "reference" not in self.on:
            lines.append("reference off (the ghost is not integrated)")
        elif m["reference_blowup_t"] is not None:
            lines.append(f"reference blew up at t = {m['reference_blowup_t']:.2f} s  |  its "
                         f"adaptive step could not follow")
            lines.append("ghost hidden, the engine runs on; drag a bob to restart it")
        elif m["divergence_time"] is not None:
            lines.append(f"parted from the exact solution  |  after {m['divergence_time']:.2f} "
                         f"s, at the X  |  now {m['reference_divergence']:.0f} px apart")
        else:
            lines.append(f"still with the exact solution  |  {m['reference_divergence']:.2f} px "
                         f"apart after {self.time - self.track['start']:.1f} s")
        return lines

    def hud_details(self) -> list[str]:
        m = self.metrics()
        return ["LMB: drag a bob (the ghost restarts from there when you let go)",
                f"rods stretched by {self.shown('pin_error', m['pin_error'])} (pin error); the "
                f"ghost's own energy drift {self.shown('reference_energy_drift', m['reference_energy_drift'])}"]

    # ----- drawing --------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, view) -> None:
        if "trail" in self.on:
            if self.ghost_alive():
                draw_trail(surface, view, self.ghost_trail, GHOST_COLOR)
            draw_trail(surface, view, self.trail, TRAIL_COLOR)
        if self.ghost_alive() and self.mouse_joint is None:
            g1, g2 = self.ode.positions(PIVOT)
            pygame.draw.lines(surface, GHOST_COLOR, False, [view.pt(PIVOT), view.pt(g1),
                                                            view.pt(g2)], px(2))
            for g in (g1, g2):
                pygame.draw.circle(surface, GHOST_COLOR, view.pt(g), max(2.0, view.len(BOB_RADIUS)),
                                   2)
        for joint in self.joints:                 # the rods (the bobs hide the dots on them)
            D.draw_pin_joint(surface, view, joint, ROD_COLOR, dot=4)
        for body in self.bobs:
            D.draw_circle(surface, view, body.position, body.angle, BOB_RADIUS, BOB_COLOR)
        mark = self.track["mark"]
        if mark is not None and "reference" in self.on:
            c, r = view.pt(mark), max(4.0, view.len(9))
            pygame.draw.line(surface, MARK_COLOR, (c[0] - r, c[1] - r), (c[0] + r, c[1] + r), px(3))
            pygame.draw.line(surface, MARK_COLOR, (c[0] - r, c[1] + r), (c[0] + r, c[1] - r), px(3))
            # (the time is in the HUD: a label here lay across the rods swinging past it)
        self.draw_mouse(surface, view)


def draw_trail(surface: pygame.Surface, view, trail: Ring, color, pieces: int = 12) -> None:
    """A trail (positions oldest first) in `pieces` stretches, the older the darker (a fade
    without per-pixel alpha)."""
    pts = view.pts(trail.values())
    if len(pts) < 2:
        return
    edges = np.linspace(0, len(pts) - 1, pieces + 1).astype(int)
    for i in range(pieces):
        a, b = edges[i], edges[i + 1]
        if b - a < 1:
            continue
        fade = 0.35 + 0.65 * (i + 1) / pieces     # the oldest still seen on a projector
        pygame.draw.lines(surface, D.dim(color, fade), False, pts[a:b + 1].tolist(), px(3))
