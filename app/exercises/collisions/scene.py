"""The `collisions` exercise's scene: `python -m app --scene exercise:collisions`.

A Verlet rope (a cloth seen edge-on: 25 particles joined by rods) dropped onto a ball, twice: on
the left the student's push_out and friction keep it out of the ball, on the right the lab's
(app/physics/circle_contact.py). Both ropes use the lab's Verlet step and rods
(app/physics/jakobsen.py); the mouse drags both balls at once.
"""

from __future__ import annotations

import math

import numpy as np
import pygame

from app.exercises.base import array_of
from app.exercises.live import FIXED, LINK, StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import InputEvent, Param

SHIFT = 420.0               # px between the two copies (yours left, the lab's right)
FLOOR = 600.0               # px: the ground under both (the lab's own projection)
G = np.array([0.0, 900.0])
COLS, SPACING, LEFT, TOP = 25, 12.0, 70.0, 120.0    # the rope: particles, px apart, its start
BALL, BALL_Y = 70.0, 380.0  # px: the ball's radius and its centre's height
MARGIN = 60.0               # px of room around what the view shows


class _Drop:
    """A rope (or a net: rows > 1) of cols x rows particles falling onto a ball, stepped by the
    lab's Verlet and rods, kept out of the ball by impl.push_out and impl.friction, then out of
    the floor by the lab's projection."""

    radius = 3.0
    ring = False                # the lab's rope falls beside yours

    def __init__(self, impl, shift: float, offset: float, mu: float, iterations: int,
                 cols: int = COLS, rows: int = 1, spacing: float = SPACING,
                 left: float = LEFT):
        self.push_out, self.friction = impl.push_out, impl.friction
        self.mu, self.iterations = mu, iterations
        r, c = np.mgrid[0:rows, 0:cols]
        idx = r * cols + c
        self.a = np.concatenate([idx[:, :-1].ravel(), idx[:-1, :].ravel()])
        self.b = np.concatenate([idx[:, 1:].ravel(), idx[1:, :].ravel()])
        self.links = list(zip(self.a.tolist(), self.b.tolist()))
        self.rest = np.full(len(self.a), spacing)
        self.x = np.stack([left + c.ravel() * spacing, TOP + r.ravel() * spacing],
                          axis=1).astype(float)
        self.x_prev = self.x.copy()
        self.w = np.ones(len(self.x))
        self.center = np.array([left + (cols - 1) * spacing / 2 + offset, BALL_Y])
        self.ball = BALL
        self.depth = np.zeros(len(self.x))
        self.fixed = np.empty((0, 2))
        self.shift = np.array([shift, 0.0])     # where it is drawn: both fall in one place

    def step(self, h: float) -> None:
        from app.physics.jakobsen import satisfy_rods, verlet_step
        from app.physics.obstacles import floor, project
        self.x, self.x_prev = verlet_step(self.x, self.x_prev, G, h, 0.01)
        self.x = satisfy_rods(self.x, self.a, self.b, self.rest, self.w, self.iterations)
        depth = self.push_out(self.x, self.w, self.center.copy(), self.ball)
        self.depth = array_of(depth, (len(self.x),), "push_out's depth")
        self.friction(self.x, self.x_prev, self.center.copy(), self.depth.copy(), self.mu)
        project([floor(FLOOR)], self.x)

    def contacts(self) -> int:
        return int(np.count_nonzero(self.depth > 0))

    def penetration(self) -> float:
        """How deep the deepest free particle is inside the ball after the step, px."""
        d = np.hypot(*(self.x - self.center).T)
        inside = self.ball - d[self.w > 0]
        return float(max(0.0, inside.max())) if inside.size else 0.0

    def points(self) -> np.ndarray:
        return self.x + self.shift


class CollisionsExercise(StudentCode, ParticleExercise):
    """Exercise `collisions`: a Verlet rope (a cloth seen edge-on) dropped onto a ball, a little
    off its middle. Left: YOUR push_out and friction keep it out of the ball (blue); right: the
    lab's (orange). Both use the lab's Verlet step and rods. At the default offset (30 px) and mu
    0.5 the rope stays draped over the ball; at mu 0.3 it slides off its longer side to the floor
    (the mu that holds it depends on the offset: 0.34 at 30 px, 0.01 centred, 0.65 at 60). Drag a
    ball with the mouse: both move.

    HUD: contacts (particles your push_out moved this step) and the deepest particle left inside
    the ball after the step, yours and the lab's, and the largest distance between your rope and
    the lab's.
    """

    exercise = "collisions"
    title = "Exercise: collisions and friction"
    params = (Param("mu", 0.5, float, 0.0, 2.0, help="Coulomb friction coefficient: static "
                    "where |v_t| <= mu * depth", rebuild=False),
              Param("offset", 30.0, float, -80.0, 80.0, help="px the ball sits right of the "
                    "rope's middle"),
              Param("iterations", 10, int, 1, 50, help="rod relaxation sweeps per step",
                    rebuild=False))
    live = ("mu", "iterations")
    dragging: tuple[float, float] | None = None     # the grip: ball centre - mouse

    def make(self, impl):
        self.dragging = None
        mine = impl is self.impl
        shift = 0.0 if mine or self.is_demo else SHIFT     # the demo: the lab's copy alone
        return _Drop(impl, shift, self.p["offset"], self.p["mu"],
                     self.p["iterations"])

    def measure(self) -> dict[str, float]:
        return {"apart_px": self.apart(), "contacts": self.mine.contacts(),
                "contacts_lab": self.lab.contacts(), "penetration_max": self.mine.penetration(),
                "penetration_max_lab": self.lab.penetration()}

    def live_line(self, m: dict[str, float]) -> str:
        return (f"contacts: yours {m['contacts']}, the lab's {m['contacts_lab']}; deepest "
                f"inside: yours {m['penetration_max']:.3g} px, the lab's "
                f"{m['penetration_max_lab']:.3g} px\nyours vs the lab's: {m['apart_px']:.3g} px "
                "apart; drag a ball with the mouse")

    def rest_bounds(self, seconds: float = 3.0) -> tuple[float, float, float, float]:
        """Both ropes, both balls wherever the offset slider can put them, and the floor, with
        MARGIN around the rope's ends (the demo beside an error: the lab's copy alone, on the
        left): x, y, width, height."""
        rope = LEFT, LEFT + (COLS - 1) * SPACING
        offset = next(q for q in self.params if q.name == "offset")
        reach = max(-offset.lo, offset.hi) + BALL       # the ball's farthest edge from the middle
        x0 = min(rope[0], (rope[0] + rope[1]) / 2 - reach) - MARGIN
        x1 = max(rope[1], (rope[0] + rope[1]) / 2 + reach) + MARGIN
        y0 = TOP - MARGIN
        return (x0, y0, x1 - x0 + (0.0 if self.is_demo else SHIFT), FLOOR + MARGIN / 2 - y0)

    def handle_event(self, event: InputEvent) -> None:
        if self.error:
            return
        if event.kind == "mouse_down" and event.button == 1:
            for sim in (self.mine, self.lab):       # either ball picks both (they share a place)
                pos = np.asarray(event.pos, float) - sim.shift
                if math.dist(pos, sim.center) < sim.ball:
                    self.dragging = tuple(sim.center - pos)
                    self.grip_shift = sim.shift
                    self.target = sim.center.copy()
        elif self.dragging is not None and event.kind == "mouse_move":
            self.target = np.asarray(event.pos, float) - self.grip_shift + self.dragging
        elif event.kind == "mouse_up" and event.button == 1:
            self.dragging = None

    def step(self, h: float) -> None:
        if self.dragging is not None:   # the balls follow the mouse, at most half a radius a step
            move = np.asarray(self.target, float) - self.mine.center
            dist = float(np.hypot(*move))
            cap = self.mine.ball / 2
            if dist > cap:
                move *= cap / dist
            self.mine.center = self.mine.center + move
            self.lab.center = self.lab.center + move
        for sim in (self.lab,) if self.is_demo else (self.mine, self.lab):   # the demo draws
            sim.mu, sim.iterations = self.p["mu"], self.p["iterations"]      # the lab's alone
            sim.step(h)

    def draw(self, surface, view) -> None:
        if self.error:                  # the message and the demo (StudentCode.draw)
            super().draw(surface, view)
            return
        sims = (self.lab,) if self.is_demo else (self.mine, self.lab)
        for sim in sims:
            pygame.draw.circle(surface, FIXED, view.pt(tuple(sim.center + sim.shift)),
                               max(2.0, view.len(sim.ball)), 2)
        x0, _, w, _ = self.rest_bounds()
        left, right = view.pt((x0, FLOOR)), view.pt((x0 + w, FLOOR))
        pygame.draw.line(surface, LINK, left, right, 1)
        super().draw(surface, view)


SCENE = CollisionsExercise
__all__ = ["SCENE"]
