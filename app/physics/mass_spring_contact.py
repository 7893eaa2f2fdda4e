"""Contact for the mass-spring cloth: obstacles by a penalty force or by projection, and Coulomb
friction. The obstacles and their signed distances are the Verlet cloth's (app/physics/
obstacles.py); what differs is how a particle that has gone in is brought back out.

**Penalty** (`contact` = penalty): a stiff spring pushes every particle that is inside an
obstacle back along the normal, f = k_c (-d) n for d < 0 (d the signed distance, n the outward
normal), a force like the others, seen by every integrator at every evaluation. It needs no
special step, but it is a spring: a particle of mass m in contact oscillates at
omega_c = sqrt(k_c / m), and the cloth's highest frequency rises to at most
sqrt(omega_max^2 + k_c / m) (the two stiffnesses add on that particle's diagonal). An explicit
step must stay below 2 / that (symplectic Euler, undamped): a stiffer contact, a smaller step.
This lab leaves the penalty out of implicit Euler's matrix (its Jacobian k_c n n^T is one block
per particle, not per spring), so implicit Euler steps the contact explicitly too and is held to
the same limit, h < 2 sqrt(m / k_c) (`contact_limit`; tests/test_mass_spring_contact.py
measures it: a particle pressed into a penalty floor oscillates there at 0.9x the limit and is
thrown out at 1.1x). Below the limit a bouncing contact still gains energy, as every switch of
a force within a step does (the integrator lab's `bounce`): measured with symplectic Euler, a
particle dropped 5 px onto the floor bounced 6 px high at 0.3x the limit, 92 px at 0.9x. And a
soft spring lets the cloth sink in: at rest a particle hangs m g / k_c deep.

**Projection** (`contact` = projection, the default): after the integrator's step, a particle
found inside an obstacle is moved to its surface (Jakobsen; first back to where its step
entered the obstacle, so that a thin one is left by the side it came in by), and its velocity is *filtered* as
Baraff & Witkin constrain a particle ("Large Steps in Cloth Simulation", section 5.3: a
constrained particle's velocity change is kept out of the constrained direction): the part of v
along n that points into the obstacle is removed, v -= min(v . n, 0) n, the part along the
surface is kept. No stiffness, so no limit on the step, and nothing stays inside (the only
penetration left is where two obstacles overlap around a particle). Only particles collide, not
the springs between them: where the strip's two rows end up on both sides of the table top
(9 px thick, its rows 10 px apart), the springs between them pass through it and stretch (seen:
up to 57 % for a moment as the cards' strip settles on the table). For Verlet, whose velocity
is its memory x - x_prev, the memory is rewritten to match: x_prev = x - h v.

**Coulomb friction** (effect `friction`, coefficient mu): the sliding velocity along the surface
(relative to the obstacle's own motion) loses at most mu times what the contact took from the
normal velocity in this step, and stops if that is more (static friction): obstacles.
coulomb_friction. With projection, what the contact took is the filtered normal velocity; with
a penalty, the normal velocity its force adds in a step, h k_c (-d) / m. The velocity change is
applied to the step's motion too (x += h dv, as x' = x + h v' would have moved it): changing v
alone left the step's own slide, and a strip that should stick crept down a 20 degree slope at
~5 px/s (g h^2 sin 20 deg a step).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.obstacles import Contacts, Obstacle, coulomb_friction, nearest, project
from app.physics.tunnelling import swept

CONTACT_METHODS = ("projection", "penalty")
ARRIVED = 0.5       # px: a particle that starts its step farther out than this and ends inside
#                     is put back where it entered (back_to_entry); nearer, it rests on it


class PenaltyContact:
    """A force: f = k_c (-d) n on every particle inside an obstacle (d < 0), nothing outside.
    Left out of implicit Euler's matrix (no stiffness_blocks): see the module docstring."""

    def __init__(self, obstacles: list[Obstacle], k: float):
        if not (math.isfinite(k) and k > 0):
            raise ValueError(f"contact stiffness must be finite and > 0, got {k!r}")
        self.obstacles, self.k = obstacles, float(k)

    def accumulate(self, ps, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        d, n, _ = nearest(self.obstacles, x)
        ids = np.flatnonzero(d < 0)               # usually few: add only to those
        f[ids] -= (self.k * d[ids])[:, None] * n[ids]

    def jacobian(self, ps, x: np.ndarray, v: np.ndarray):
        return None, None                          # stepped explicitly (module docstring)


def contact_limit(k: float, mass: np.ndarray) -> float:
    """The penalty's own limit on the step, 2 sqrt(m / k_c) for the lightest particle (s): past
    it a particle in contact is stepped unstably (symplectic Euler, and implicit Euler here)."""
    return 2.0 * math.sqrt(float(np.min(mass)) / k)


def _obstacle_velocity(obstacles: list[Obstacle], index: np.ndarray) -> np.ndarray:
    """Each contact's obstacle velocity (px/s), (m, 2)."""
    vel = np.array([ob.velocity for ob in obstacles], float).reshape(-1, 2)
    return vel[index]


def back_to_entry(obstacles: list[Obstacle], start: np.ndarray, x: np.ndarray,
                  movable: np.ndarray) -> int:
    """A particle whose step start -> x entered an obstacle from more than ARRIVED px outside
    is put back where it entered (the
    first point of the path on the surface, by bisection), so that the projection pushes it out
    the side it came in by: a step 5 px into a table top 9 px thick ends past its middle, and
    the nearest face is then the one below. Paths right through it (start and end outside) are
    caught too (app/physics/tunnelling.py). Writes into x; returns how many were put back."""
    moved = 0
    through = swept(obstacles, start, x, 0.0, movable)
    if through.count:
        x[through.mask] = through.entry[through.mask]
        moved += through.count
    for ob in obstacles:
        d0, d1 = ob.signed_distance(start)[0], ob.signed_distance(x)[0]
        # from outside (more than ARRIVED px away): one resting on the surface slides on it
        ids = np.flatnonzero((d0 > ARRIVED) & (d1 < 0) & movable)
        if ids.size == 0:
            continue
        a, step = start[ids], x[ids] - start[ids]
        lo, hi = np.zeros(ids.size), np.ones(ids.size)
        for _ in range(30):                      # d(a) >= 0 at lo, < 0 at hi
            mid = (lo + hi) / 2
            outside = ob.signed_distance(a + mid[:, None] * step)[0] >= 0
            lo, hi = np.where(outside, mid, lo), np.where(outside, hi, mid)
        x[ids] = a + hi[:, None] * step          # just inside (2^-30 of the step): the
        moved += ids.size                        # projection then counts it as a contact
    return moved


def project_and_filter(ps, obstacles: list[Obstacle], h: float, mu: float | None,
                       start: np.ndarray | None = None) -> Contacts:
    """Projection with Baraff & Witkin's velocity filter (module docstring), then Coulomb
    friction with coefficient mu (None: friction off). start: the positions before the step
    (particles that entered an obstacle are first put back where they entered: back_to_entry).
    Writes into ps.x, ps.v (and Verlet's ps.x_prev). Returns the contacts."""
    movable = ps.free[:, 0] > 0
    if start is not None:
        back_to_entry(obstacles, start, ps.x, movable)
    contacts = project(obstacles, ps.x, 0.0, movable)
    ids = np.flatnonzero(contacts.mask)
    if ids.size == 0:
        return contacts
    n = contacts.normal[ids]
    v = ps.v[ids]
    into = np.minimum(np.sum(v * n, axis=1), 0.0)          # normal speed into the surface (<= 0)
    v = v - into[:, None] * n                               # filtered: none of it left
    if mu is not None:
        moving = _obstacle_velocity(obstacles, contacts.index[ids])
        change = coulomb_friction(v - moving, n, -into, np.ones(ids.size, bool), mu)
        v = v + change
        ps.x[ids] += h * change                  # and this step's slide: x' = x + h v'
    ps.v[ids] = v
    if ps.x_prev is not None:                               # Verlet's memory: x - x_prev = h v
        ps.x_prev[ids] = ps.x[ids] - h * v
    return contacts


def penalty_friction(ps, obstacles: list[Obstacle], k: float, h: float, mu: float) -> None:
    """Coulomb friction for the penalty contact: particles inside an obstacle after the step lose
    sliding speed up to mu times the normal speed the penalty force adds in a step."""
    d, n, index = nearest(obstacles, ps.x)
    ids = np.flatnonzero((d < 0) & (ps.free[:, 0] > 0))
    if ids.size == 0:
        return
    normal_change = h * k * (-d[ids]) / ps.mass[ids]
    rel = ps.v[ids] - _obstacle_velocity(obstacles, index[ids])
    change = coulomb_friction(rel, n[ids], normal_change, np.ones(ids.size, bool), mu)
    ps.v[ids] += change
    ps.x[ids] += h * change                      # and this step's slide: x' = x + h v'
    if ps.x_prev is not None:
        ps.x_prev[ids] = ps.x[ids] - h * ps.v[ids]


def touching(obstacles: list[Obstacle], x: np.ndarray, movable: np.ndarray,
             within: float = 0.0) -> np.ndarray:
    """Which movable particles are inside an obstacle (or within `within` px of its surface)."""
    if not obstacles:
        return np.zeros(len(x), bool)
    return (nearest(obstacles, x)[0] < within) & movable


__all__ = ["CONTACT_METHODS", "PenaltyContact", "contact_limit", "back_to_entry", "project_and_filter",
           "penalty_friction", "touching"]
