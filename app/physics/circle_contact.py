"""One circle and many particles: the lab's answer to the `collisions` exercise
(exercises/collisions.py), in the exercise's words, made of the lab's own pieces.

    push_out   Jakobsen's projection: every particle found inside the circle (|x - c| < r) and
               not pinned (w > 0) is moved to its surface along the outward normal
               n = (x - c) / |x - c| (a particle exactly at the centre leaves through the top,
               n = (0, -1): y points down). Returns how far each was moved (depth, px).
    friction   Coulomb friction on the particles that touched it (depth > 0): the part of this
               step's travel x - x_prev along the surface loses at most mu * depth: all of it if
               it is smaller (static friction: the particle sticks), else mu * depth of it
               (kinetic: it slides, slower). x moves back along the surface.

They are app/physics/obstacles.py's `project` on one `Circle` and app/physics/friction.py's
`verlet_friction`, the very code the lab's Verlet cloth runs on its obstacles
(app/physics/cloth_contact.py), called with the exercise's arguments. Both change x in place.
"""

from __future__ import annotations

import numpy as np

from app.physics.friction import Contacts, verlet_friction
from app.physics.obstacles import Circle, project


def push_out(x: np.ndarray, w: np.ndarray, center: np.ndarray, radius: float) -> np.ndarray:
    """Move every unpinned particle inside the circle to its surface, in place; return the
    depth (n,): the distance each particle was moved (0 where it was not)."""
    circle = Circle(float(center[0]), float(center[1]), float(radius))
    return project([circle], x, 0.0, movable=np.asarray(w) > 0).depth


def friction(x: np.ndarray, x_prev: np.ndarray, center: np.ndarray, depth: np.ndarray,
             mu: float) -> None:
    """Coulomb friction on the particles push_out moved (depth > 0), in place on x."""
    depth = np.asarray(depth, dtype=float)
    circle = Circle(float(center[0]), float(center[1]), 0.0)
    normal = circle.signed_distance(x)[1]       # (x - c) / |x - c|; (0, -1) at the centre
    touching = depth > 0
    verlet_friction(x, x_prev, Contacts(touching, depth, normal, np.zeros(len(x), int)), mu)


__all__ = ["push_out", "friction"]
