"""Two-way coupling of a Verlet cloth with rigid bodies: the cloth pushes a body, the body pushes
the cloth, and what one gains in momentum the other loses.

The cloth (app/physics/cloth.py) knows particles and rods; a rigid body (pymunk's) knows its
mass M, moment of inertia I, position c, velocity v and angular velocity w. They meet where a
particle is found inside the body's shape, after both have taken their step. Each step, for
each body:

1. **Find the particles inside the body** with the body's signed distance d(p) and outward
   normal n(p) (app/physics/obstacles.py: a Circle or a rotated Box at the body's pose).
2. **Share the way out by inverse masses**, as a rod shares its correction between its two ends.
   Particle i must get -d_i px out along n_i. Seen from that point along n_i, the body's inverse
   mass is w_body = 1/M + (r_i x n_i)^2 / I (r_i = p_i - c: a push off the centre also turns it);
   the particle's is w_p = 1/m_p. The k particles inside share the body, so each sees it k times
   heavier (k * w_body in place of w_body, as constraint averaging does). The particle moves its
   part of the way:

       dx_i = -d_i * w_p / (w_p + k w_body) * n_i

3. **Momentum.** The Verlet cloth's velocity is (x - x_prev)/h, so moving x by dx_i (x_prev
   stays) gives particle i the momentum m_p dx_i / h. The body receives the equal and opposite
   impulse at the contact point: J = -sum_i m_p dx_i / h and the angular impulse
   L = -sum_i r_i x (m_p dx_i / h). Its velocity changes by J/M and w by L/I, and it moves the rest
   of the way out now (c += h J/M, angle += h L/I), as a position-based step would. The pymunk
   step then carries the body on with its new velocity, the cloth's next step its particles.

Nothing is lost or made in the exchange: the cloth's momentum changes by sum m_p dx_i / h and
the body's by J, the negative of it, to the rounding of the cloth's float32 positions
(tests/test_trampoline.py checks a free cloth and a ball with gravity off). The coupling impulse
|J| of a step is what the scene reports (`coupling_impulse`); for a body at rest on the cloth it
is its weight times the step, M g h.

A heavy body (w_body << w_p) pushes the particles almost all the way out and barely slows; a
light one is pushed back as much as it pushes. What the method does not promise: particles that
pass between the body's steps (tunnelling: a body faster than its size per step), and the rods'
length after the projection (the next sweeps restore it, pulling the particles back against the
body: that pull, step after step, is the force the cloth carries the body with).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.physics.obstacles import Obstacle


@dataclass
class Body:
    """What the coupling reads of a rigid body: its shape at its pose (an obstacle), its mass M,
    its moment of inertia I about its centre of mass, and that centre (px)."""

    shape: Obstacle
    mass: float
    moment: float
    center: tuple[float, float]


@dataclass
class Exchange:
    """What one coupling step did between the cloth and one body: `impulse` (2,) the momentum
    the body received (kg px/s; the cloth received its negative), `angular` the angular impulse
    about its centre (kg px^2/s), `dv` and `dw` the velocity and angular velocity changes,
    `shift` and `turn` the body's position (px) and angle (rad) corrections, `contacts` the
    particles that were inside, `depth` the deepest of them before the projection (px)."""

    impulse: np.ndarray
    angular: float
    dv: np.ndarray
    dw: float
    shift: np.ndarray
    turn: float
    contacts: int
    depth: float

    @classmethod
    def none(cls) -> "Exchange":
        zero = np.zeros(2)
        return cls(zero, 0.0, zero, 0.0, zero, 0.0, 0, 0.0)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """2-D cross products a x b = ax by - ay bx, row by row."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def couple(points: np.ndarray, movable: np.ndarray, particle_mass: float, body: Body,
           h: float) -> Exchange:
    """One coupling step (module docstring, steps 1-3) between cloth particles `points` ((n, 2),
    a view into the cloth: written in place) and one body. `movable` (n,) is False for pinned or
    grabbed particles (they neither move nor push). Returns what was exchanged; the caller
    applies dv, dw, shift and turn to the body."""
    d, normal = body.shape.signed_distance(points)
    ids = np.flatnonzero((d < 0) & movable)
    if ids.size == 0:
        return Exchange.none()
    n = normal[ids]
    r = points[ids].astype(np.float64) - np.asarray(body.center)     # lever arms
    w_body = 1.0 / body.mass + cross(r, n) ** 2 / body.moment       # inverse mass along n
    w_p = 1.0 / particle_mass
    share = w_p / (w_p + ids.size * w_body)                          # the particle's part
    dx = (-d[ids] * share)[:, None] * n
    points[ids] += dx.astype(points.dtype, copy=False)
    j = particle_mass * dx / h                                       # momentum each one gained
    impulse = -j.sum(axis=0)
    angular = -float(cross(r, j).sum())
    dv, dw = impulse / body.mass, angular / body.moment
    return Exchange(impulse, angular, dv, dw, dv * h, dw * h, int(ids.size), float(-d[ids].min()))


def cloth_momentum(x: np.ndarray, x_prev: np.ndarray, particle_mass: float, h: float) -> np.ndarray:
    """The Verlet cloth's momentum, sum m_p (x - x_prev) / h over all particles (x, x_prev of
    shape (2, ...)): (2,) kg px/s. Pinned particles do not move, so they add nothing."""
    return particle_mass * (x.astype(np.float64) - x_prev).reshape(2, -1).sum(axis=1) / h


__all__ = ["Body", "Exchange", "couple", "cloth_momentum", "cross"]
