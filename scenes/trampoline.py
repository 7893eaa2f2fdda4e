"""Trampoline: pymunk bodies fall onto a Verlet cloth, and the cloth pushes back.

What it shows: a band of Verlet cloth (app/physics/cloth.py) held at both ends, and a pymunk body
(a ball or a box) dropped onto it. The cloth catches the body, stretches, and throws it back up;
a box laid in a slack band is carried, the cloth holding its weight. Neither engine knows the
other: the lab couples them, and the momentum each one loses, the other gains.

The method, every substep h (app/physics/coupling.py has it in full):
  1. pymunk steps the bodies (gravity, the floor); the cloth takes its Verlet step and its
     `iterations` sweeps over the rods;
  2. cloth particles found inside a body are projected out along the body's surface normal,
     their part of the way by inverse masses: dx_i = -d_i * w_p / (w_p + k w_body) * n_i
     (w_p = 1/m_p, w_body = 1/M + (r_i x n_i)^2 / I as seen from that point, shared by the k
     particles inside);
  3. moving x by dx_i gives particle i the momentum m_p dx_i / h (the Verlet velocity is
     (x - x_prev)/h); the body receives the equal and opposite impulse at the contact points,
     J = -sum m_p dx_i / h and L = -sum r_i x m_p dx_i / h: its velocity changes by J/M, its
     angular velocity by L/I, and it moves the rest of the way out (h J/M, h L/I). pymunk's next
     step carries the body on from there.
`coupling_impulse` is |J| summed over the step's substeps and bodies (kg px/s): for a body
resting on the cloth it is its weight times dt, M g dt. Total momentum (cloth + bodies,
`momentum_x`, `momentum_y`) changes only by gravity, the cloth's drag, the pins and the floor: with
gravity and drag off and no pins it stays constant through every bounce, to the rounding of the
cloth's float32 positions (the card: within 1e-5 of the ball's 400 kg px/s; a test checks 1e-4).
That rounding is the cloth's own step's, and it grows with the cloth's mass, the hertz and the
iterations: a 0.05 kg box thrown at 3000 px/s into a 50 kg band of 16 x 2 particles at 1000 Hz,
100 iterations, gets 12% of its momentum wrong in 40 steps; with float64 positions the same run
keeps it to 1e-8 of it (measured 3e-10; a test).
`coupling` = one-way shows the other half: the cloth is pushed out of the body but the body feels
nothing, so nothing stops it.

Energy bars (E): the body's kinetic (with its spin) and potential energy, the cloth's (its free
particles, v = (x - x_prev)/h), potentials zero on the pins' line; and what three causes took out
since the bars were first shown (the account starts then, and costs nothing before), each
measured where it acts: the cloth's drag (1/2 m v^2 (1 - k^2) a step), the
rods' sweeps (the change of the cloth's energy across them), the coupling (the change of cloth +
body across it). The rods are hard constraints and store no energy, so there is no elastic part.
The coupling and the rods trade energy every step the body touches the band, the ball resting on
it too: the coupling's bar keeps growing and the rods' goes below zero by nearly as much (at the
defaults, after 10 s: about +1.9e6 and -1.6e6 kg px^2/s^2); their sum is what the contact took out.
What is left (`other`: the floor, pymunk's own integration, the mouse) may be below zero: put in.

Only particles collide, never the rods between them: a heavy body on a stiff band pushes the
particles aside and slips between them (card "Stiff band lets it through", comparison "Heavy
ball: soft vs stiff").

The trampoline's spring is the cloth's stretch: Jakobsen's rods are rigid only after enough
sweeps, and at a few iterations per substep the band stretches under the ball and snaps back.
More iterations, a stiffer band, a harder bounce (and more ms a step).

Controls: drag a body with the left mouse button. Parameters: body (ball or box), body_mass,
cloth_mass (the whole band's), drop_height, throw_speed (downwards, at the start), slack (how much longer the band is than the gap
between its pins), iterations (the cloth's sweeps per substep), pins (ends or none), coupling
(two-way or one-way), g. Effects: gravity, drag (the cloth's), collisions (off: the body falls
through the cloth onto the floor, and the coupling costs nothing).
"""

from __future__ import annotations

import math

import numpy as np
import pymunk

from app.draw import pymunk_draw as D
from app.physics.cloth import DRAG, Cloth
from app.physics.coupling import Body, Exchange, cloth_momentum, couple
from app.physics.obstacles import Box, Circle, penetration_max
from app.pymunk_scene import PYMUNK_EFFECTS, PymunkScene
from app.scene import Effect, Param, Try, Unit, common

GAP = 640.0                  # px between the two pinned ends
PIN_Y = 440.0                # the pins' height (y down)
LEFT = (960.0 - GAP) / 2
FLOOR_Y = 700.0              # pymunk's floor: what a body falls onto through a cloth it misses
BOX_ASPECT = 1.6             # a box is this many times wider than high


class TrampolineScene(PymunkScene):
    """Trampoline: a pymunk ball or box falls onto a Verlet cloth band; the cloth catches it and
    throws it up, the momentum each loses the other gains (coupling_impulse).

    LMB: drag the body. Parameters: body, body_mass, cloth_mass, drop_height, slack, iterations,
    pins, coupling (two-way or one-way). Effects: gravity, drag, collisions.
    """

    name = "trampoline"
    title = "Trampoline: pymunk bodies on a Verlet cloth"
    category = "Cloth"
    arrow_name = "body"
    params = (
        Param("g", 900.0, float, 0.0, 5000.0, help="gravity, px/s^2 (downwards), both engines",
              rebuild=False),
        Param("iterations", 4, int, 1, 100,
              help="the cloth's relaxation sweeps per substep (few: a stretchy, springy band)",
              rebuild=False),
        common("substeps", default=4),
        Param("body", "ball", str, choices=("ball", "box"), help="what falls onto the cloth"),
        Param("size", 30.0, float, 8.0, 80.0, help="ball radius or box half height, px"),
        Param("body_mass", 1.0, float, 0.05, 50.0, help="the body's mass, kg"),
        Param("cloth_mass", 1.0, float, 0.05, 50.0, help="the whole band's mass, kg"),
        Param("drop_height", 250.0, float, 0.0, 400.0,
              help="how far above the pins the body's lowest point starts, px"),
        Param("throw_speed", 0.0, float, 0.0, 3000.0,
              help="the body's downward speed at the start, px/s"),
        Param("slack", 0.0, float, 0.0, 0.3,
              help="how much longer the band is than the gap between its pins (0.1: 10%)"),
        Param("cols", 41, int, 8, 128, help="particles along the band"),
        Param("rows", 3, int, 2, 8, help="particles across the band"),
        Param("pins", "ends", str, choices=("ends", "none"),
              help="ends: both ends of the band are pinned; none: a free cloth"),
        Param("coupling", "two-way", str, choices=("two-way", "one-way"),
              help="two-way: the cloth pushes the body back; one-way: only the body pushes"),
    )
    effects = PYMUNK_EFFECTS + (
        Effect("drag", True, "the cloth's velocity damping (Verlet 2 -> 1.99)"),
        Effect("collisions", True, "cloth and body push each other (off: it falls through)"),
    )
    world_keys = ("space", "body", "shape", "floor", "cloth", "last", "account")
    error_metric, error_label = "penetration_max", "deepest particle in a body"
    metric_units = {"penetration_max": Unit("px", resolution=0.01),
                    "coupling_impulse": Unit("kg px/s", resolution=1e-3)}
    tries = (
        Try("Catch and throw a ball", {},
            "the band stretches under the ball and throws it back up; coupling_impulse peaks "
            "as it turns"),
        Try("A box in a hammock", {"body": "box", "slack": 0.15, "drop_height": 80,
                                   "body_mass": 2.0},
            "the slack band catches the box and carries it: at rest coupling_impulse is its "
            "weight times dt, M g dt"),
        Try("Stiff band lets it through", {"body_mass": 5.0, "cloth_mass": 0.5,
                                           "iterations": 20},
            "the taut band does not sag under the ball: the ball pushes two particles apart, "
            "the rod between them opens to its width (273% stretched for a moment) and the "
            "ball slips between them: only particles collide, never the rods between them"),
        Try("Zero g: momentum kept", {"gravity": False, "pins": "none", "drag": False,
                                      "drop_height": 120, "throw_speed": 400},
            "no gravity, no pins, no drag: the ball is thrown into a free cloth and carries it "
            "along; momentum_y stays 400 kg px/s until they reach the floor"),
    )

    comparisons = (
        Try("Heavy ball: soft vs stiff", {"body_mass": 5.0, "cloth_mass": 0.5},
            "a 5 kg ball on a 0.5 kg band: at 4 iterations (A) the band stretches past 50% and "
            "the floor stops the ball; at 20 (B) the band stays taut, the ball pushes two "
            "particles apart (their rod 273% stretched for a moment) and slips through",
            compare=({"iterations": 4}, {"iterations": 20})),
        Try("Two-way vs one-way", {},
            "the same drop: in A the cloth pushes back and throws the ball up; in B only the "
            "ball pushes, and it falls through to the floor",
            compare=({"coupling": "two-way"}, {"coupling": "one-way"})),
    )

    # ----- world ---------------------------------------------------------------------------------
    def build_space(self, space: pymunk.Space) -> None:
        p = self.p
        floor = pymunk.Segment(space.static_body, (0.0, FLOOR_Y), (960.0, FLOOR_Y), 4.0)
        floor.friction, floor.elasticity = 0.8, 0.3
        space.add(floor)
        self.floor = floor
        size, mass = p["size"], p["body_mass"]
        if p["body"] == "ball":
            moment = pymunk.moment_for_circle(mass, 0.0, size)
            lowest = size
        else:
            half_w = BOX_ASPECT * size
            moment = pymunk.moment_for_box(mass, (2 * half_w, 2 * size))
            lowest = size
        self.body = pymunk.Body(mass, moment)
        self.body.position = (480.0, PIN_Y - p["drop_height"] - lowest)
        self.body.velocity = (0.0, p["throw_speed"])
        if p["body"] == "ball":
            self.shape = pymunk.Circle(self.body, size)
        else:
            self.shape = pymunk.Poly.create_box(self.body, (2 * half_w, 2 * size))
        self.shape.friction, self.shape.elasticity = 0.8, 0.3
        space.add(self.body, self.shape)
        self.cloth = self.make_cloth()
        self.last = {"impulse": 0.0, "contacts": 0, "depth": 0.0}
        self.account: dict[str, float] | None = None     # the energy account: from the bars' first look

    def make_cloth(self) -> Cloth:
        """A band of rows x cols particles whose rods are (1 + slack) times the gap between its
        pins: it starts hanging as a parabola of that length, its end columns pinned."""
        p = self.p
        rows, cols, slack = p["rows"], p["cols"], p["slack"]
        spacing = GAP * (1 + slack) / (cols - 1)
        cloth = Cloth(rows, cols, spacing, (LEFT, PIN_Y), "none", self.cloth_effects())
        # a parabola of span GAP and sag f has length ~ GAP (1 + 8/3 (f/GAP)^2)
        sag = GAP * math.sqrt(3 * slack / 8)
        u = np.linspace(0.0, 1.0, cols)
        x = LEFT + GAP * u
        y = PIN_Y + 4 * sag * u * (1 - u)
        cloth.x[0] = x[None, :]
        cloth.x[1] = y[None, :] + spacing * np.arange(rows)[:, None]
        cloth.x_prev[...] = cloth.x
        if p["pins"] == "ends":
            ends = [(r, c) for r in range(rows) for c in (0, cols - 1)]
            cloth.lock_cells(ends)
        cloth.world = tuple(float(v) for v in self.world_size)
        self.sync_cloth(cloth)
        return cloth

    def cloth_effects(self) -> set[str]:
        return {name for name in ("gravity", "drag") if name in self.on}

    def sync_cloth(self, cloth: Cloth | None = None) -> None:
        """Hand the live settings to the cloth: its sweeps and the gravity both engines share."""
        c = cloth or self.cloth
        c.iterations = self.p["iterations"]
        c.gravity = self.gravity()
        c.drag = DRAG

    def settings_changed(self, names: set[str]) -> None:
        super().settings_changed(names)
        self.cloth.set_effects(self.cloth_effects())
        self.sync_cloth()

    @property
    def particle_mass(self) -> float:
        return self.p["cloth_mass"] / (self.p["rows"] * self.p["cols"])

    # ----- the step ------------------------------------------------------------------------------
    def step(self, h: float) -> None:
        super().step(h)                                   # pymunk: the body moves
        self.sync_cloth()
        if self.account is None:                          # no bars asked for: nothing measured
            self.cloth.step(h)
            if self.coupled:
                self.couple(h)
            return
        before = self.cloth_energy()
        self.cloth.step(h)                                # Verlet step and the rods' sweeps
        after = self.cloth_energy()
        self.account_cloth_step(h, before, after)
        if self.coupled:                                  # off: nothing computed at all
            self.couple(h, after)

    @property
    def coupled(self) -> bool:
        return "collisions" in self.on

    def rigid(self) -> Body:
        """The body as the coupling sees it: its shape at its pose, mass, moment, centre."""
        b, size = self.body, self.p["size"]
        x, y = b.position
        if self.p["body"] == "ball":
            shape = Circle(x, y, size)
        else:
            shape = Box(x, y, BOX_ASPECT * size, size, b.angle)
        return Body(shape, b.mass, b.moment, (x, y))

    def couple(self, h: float, cloth_before: tuple[float, float] | None = None) -> None:
        """Project the particles out of the body and give the body the opposite impulse
        (app/physics/coupling.py); one-way: the body is left as it was."""
        c = self.cloth
        points = c.x.reshape(2, -1).T                     # a view: writing moves the cloth
        movable = (c.w > 0).ravel()
        counting = self.account is not None and cloth_before is not None
        body_before = self.body_energy() if counting else (0.0, 0.0)   # for the energy account
        ex: Exchange = couple(points, movable, self.particle_mass, self.rigid(), h)
        if self.p["coupling"] == "two-way" and ex.contacts:
            if not (np.isfinite(ex.dv).all() and math.isfinite(ex.dw)):
                raise FloatingPointError("the coupling produced a non-finite impulse")
            b = self.body
            b.velocity = (b.velocity.x + ex.dv[0], b.velocity.y + ex.dv[1])
            b.angular_velocity += ex.dw
            b.position = (b.position.x + ex.shift[0], b.position.y + ex.shift[1])
            b.angle += ex.turn
        self.last["impulse"] += float(np.hypot(*ex.impulse))
        self.last["contacts"] = ex.contacts
        if ex.contacts and counting:      # what the exchange took out of the two (< 0: put in)
            self.account["coupling"] += (sum(cloth_before) + sum(body_before)
                                         - sum(self.cloth_energy()) - sum(self.body_energy()))

    def advance(self) -> None:
        self.last["impulse"] = 0.0                        # summed over this step's substeps
        super().advance()

    # ----- energy --------------------------------------------------------------------------------
    # kg px^2/s^2; potentials m g (PIN_Y - y), zero on the pins' line (y points down)
    def body_energy(self) -> tuple[float, float]:
        """The body's (kinetic, with its spin; potential in gravity)."""
        b = self.body
        # (products, not Vec2d.length_squared and **, which raise OverflowError past ~1e154: a
        # blown-up body's energy is inf, reported, not a crash)
        (vx, vy), w = b.velocity, b.angular_velocity
        kinetic = 0.5 * b.mass * (vx * vx + vy * vy) + 0.5 * b.moment * (w * w)
        return kinetic, b.mass * self.gravity() * (PIN_Y - b.position.y)

    def cloth_energy(self) -> tuple[float, float]:
        """The cloth's (kinetic, potential): its free particles only (a pinned one never moves),
        mass cloth_mass / particles each, v = (x - x_prev)/h."""
        c = self.cloth
        x = c.x
        h = c.travelled_in(self.dt / self.p["substeps"])   # (substeps or hertz set since)
        free = c.w > 0
        v = (x.astype(np.float64) - c.x_prev) / h
        m = self.particle_mass
        kinetic = 0.5 * m * float(np.sum(free * (v[0] * v[0] + v[1] * v[1])))
        return kinetic, m * self.gravity() * float(np.sum(free * (PIN_Y - x[1].astype(np.float64))))

    def energy(self) -> float:
        return sum(self.body_energy()) + sum(self.cloth_energy())

    def fresh_account(self) -> dict[str, float]:
        """The energy now as the start, nothing taken out yet."""
        return {"start": self.energy(), "drag": 0.0, "rods": 0.0, "coupling": 0.0}

    def account_cloth_step(self, h: float, before: tuple[float, float],
                           after: tuple[float, float]) -> None:
        """What the cloth's step took out of its energy, split: the drag scales every velocity
        by k = (1 - drag)^(60 h) (app/physics/cloth.py), so it takes 1/2 m v^2 (1 - k^2) of
        each particle's kinetic energy; the rest of the change is the rods' projection (and
        Verlet's own drift, 1/2 m g^2 h^2 a particle a substep: a few 0.1 % of a bounce)."""
        drag = 0.0
        if "drag" in self.cloth.on:
            k = (1.0 - self.cloth.drag) ** (h * 60.0)
            drag = before[0] * (1.0 - k * k)
        self.account["drag"] += drag
        self.account["rods"] += sum(before) - sum(after) - drag

    def gravity_changed(self) -> None:
        """A new g changes every potential: the account starts again from the energy now."""
        if getattr(self, "account", None) is not None:
            self.account = self.fresh_account()

    def energies(self):
        """Energy bars: the body's and the cloth's kinetic and potential energy, and what the
        cloth's drag, its rods and the coupling took out since the bars were first shown (the
        account starts then: until the bars are asked for, the step measures nothing)."""
        from app.energy import Energies
        if self.account is None:
            self.account = self.fresh_account()
        body = self.p["body"]
        (bk, bg), (ck, cg) = self.body_energy(), self.cloth_energy()
        a = self.account
        return Energies(
            ((f"KE {body}", bk), (f"PE {body}", bg), ("KE band", ck), ("PE band", cg)),
            a["start"],
            zero=f"KE (kinetic): at rest; PE (gravity): on the pins' line (y = {PIN_Y:g} px); drag, rods, "
                 "coupling: what each has taken out since the bars were first shown (< 0: put "
                 "in). The rods are hard constraints: they store no energy, so the band has no elastic part. "
                 f"While the {body} touches the band, the coupling's projection takes energy "
                 "out and the rods' puts nearly as much back (its bar below zero), every step: "
                 "their sum is what the contact took out",
            losses="other: the floor, pymunk's own integration, the mouse (< 0: put in)",
            unit="kg px^2/s^2",
            removed=tuple((k, a[k]) for k in ("drag", "rods", "coupling")))

    # ----- reports -------------------------------------------------------------------------------
    def momentum(self) -> np.ndarray:
        """Total momentum, cloth + body (kg px/s)."""
        h = self.cloth.travelled_in(self.dt / self.p["substeps"])
        cloth = cloth_momentum(self.cloth.x, self.cloth.x_prev, self.particle_mass, h)
        return cloth + self.body.mass * np.array(self.body.velocity)

    def metrics(self) -> dict[str, float]:
        c = self.cloth
        points = c.x.reshape(2, -1).T
        pen = penetration_max([self.rigid().shape], points, (c.w > 0).ravel()) \
            if self.coupled else 0.0
        horizontal, _ = c.sets["structural"].families
        p = self.momentum()
        return {
            "coupling_impulse": self.last["impulse"],
            "contacts": self.last["contacts"] if self.coupled else 0,
            "penetration_max": pen,
            "momentum_x": float(p[0]),
            "momentum_y": float(p[1]),
            "body_vy": float(self.body.velocity.y),
            "body_y": float(self.body.position.y),
            "max_stretch": float(c.stretch(horizontal).max()),
        }

    def hud_lines(self) -> list[str]:
        m = self.metrics()
        mode = self.p["coupling"] if self.coupled else "collisions off"
        n = m["contacts"]
        # phrases parted by '  |  ', each short enough for a row at 1024x768 with F2 (a row
        # breaks between them: never "... 14.87 kg px/s" / "this step")
        return [f"{mode}: {n} particle{'' if n == 1 else 's'} touching  |  coupling impulse "
                f"{self.shown('coupling_impulse', m['coupling_impulse'])} a step",
                f"{self.p['body']} {-m['body_vy']:+.0f} px/s (up +)  |  band stretch "
                f"{100 * m['max_stretch']:.1f}%  |  momentum ({m['momentum_x']:.1f}, "
                f"{m['momentum_y']:.1f}) kg px/s"]

    def hud_details(self) -> list[str]:
        weight = self.p["body_mass"] * self.gravity() * self.dt
        return [f"{self.p['body']} {self.p['body_mass']:g} kg, band {self.p['cloth_mass']:g} kg"
                "  |  LMB: drag the body  |  the coupling: app/physics/coupling.py",
                f"at rest on the cloth, coupling impulse = M g dt = {weight:.3g} kg px/s"]

    # ----- drawing -------------------------------------------------------------------------------
    def content_bounds(self) -> tuple[float, float, float, float]:
        """The band between its pins (as long as it is, lying flat if free), the body's way
        down from where it is dropped, and the floor: not the world's empty sides and sky
        (the band was a 330 px strip under a blank band at 1024x768 with F2)."""
        p = self.p
        half = (GAP if p["pins"] == "ends" else GAP * (1 + p["slack"])) / 2 + 40
        body = p["size"] * (BOX_ASPECT if p["body"] == "box" else 1.0)
        half = max(half, body + 20)
        top = min(PIN_Y - p["drop_height"] - 2 * p["size"] - 30, PIN_Y - 60)
        bottom = FLOOR_Y + 12
        return (480.0 - half, top, 2 * half, bottom - top)

    def draw(self, surface, view) -> None:
        from app.draw.cloth_draw import draw_cloth
        D.draw_shape(surface, view, self.floor, D.STATIC)
        draw_cloth(surface, view, self.cloth)
        D.draw_shape(surface, view, self.shape, D.BALL)
        self.draw_mouse(surface, view)

    @property
    def color_key(self) -> tuple:
        from app.draw.cloth_draw import strain_key
        return strain_key()

    # ----- state ---------------------------------------------------------------------------------
    def state_arrays(self):
        return [self.body_state()] + self.cloth.state_arrays()

    def is_finite(self) -> bool:
        """The body (PymunkScene's check) and the cloth's positions."""
        c = self.cloth
        return super().is_finite() and bool(np.isfinite(c.x).all() and np.isfinite(c.x_prev).all())
