"""Coulomb friction for particles in contact, the rule of app/physics/obstacles.py's step 2 (read
its docstring first): the sliding of a touching particle loses at most mu times the normal
correction its contact made. obstacles.py re-exports both functions and the Contacts record a
projection returns (import them from there).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

TINY = 1e-12                                 # shortest length we divide by (no 0/0)


@dataclass
class Contacts:
    """What a projection did, per point: `mask` True where the point touched an obstacle (was
    found within `margin` of it and moved); `depth` the distance it was moved along the normal
    (px, 0 where no contact: the normal correction friction is measured against); `normal` (n, 2)
    the outward normal of the obstacle it was pushed out of (the last one, if several);
    `index` that obstacle's position in the list (-1: none)."""

    mask: np.ndarray
    depth: np.ndarray
    normal: np.ndarray
    index: np.ndarray

    @property
    def count(self) -> int:
        return int(np.count_nonzero(self.mask))


def coulomb_friction(motion: np.ndarray, normal: np.ndarray, normal_change: np.ndarray,
                     mask: np.ndarray, mu: float) -> np.ndarray:
    """Coulomb's law on a motion (a displacement per step, or a velocity), for the points in
    `mask`: the tangential part m_t = m - (m . n) n shrinks by mu * normal_change (what the
    contact removed along the normal, >= 0), and to zero if it is smaller (static friction).
    Returns the change to add to `motion` (n, 2): minus the removed tangential part; zero
    outside the mask. It never reverses the sliding: the factor applied to m_t is in [0, 1]."""
    change = np.zeros(motion.shape, np.float64)
    ids = mask.nonzero()[0]
    if ids.size == 0 or mu <= 0:
        return change
    m = motion[ids].astype(np.float64)
    nrm = normal[ids]
    along = (m * nrm).sum(1, keepdims=True)
    tangent = m - along * nrm
    speed = np.hypot(tangent[:, 0], tangent[:, 1])
    removable = mu * np.maximum(normal_change[ids], 0.0)
    keep = np.where(speed > removable, 1.0 - removable / np.maximum(speed, TINY), 0.0)
    change[ids] = -(1.0 - keep)[:, None] * tangent
    return change


def verlet_friction(x: np.ndarray, x_prev: np.ndarray, contacts: Contacts, mu: float,
                    obstacles=(), h: float = 0.0) -> None:
    """Coulomb friction for the Verlet cloth (see the module docstring, step 2): for each
    particle in contact, the sliding x - x_prev (minus the surface's own motion, velocity * h,
    of the obstacle it touches) loses at most mu * depth along the surface, by moving x back
    along it. Writes into x ((n, 2) arrays, views welcome)."""
    ids = contacts.mask.nonzero()[0]
    if ids.size == 0 or mu <= 0:
        return
    normal = contacts.normal
    slide_back(x, x_prev, ids, normal[:, 0].take(ids), normal[:, 1].take(ids),
               contacts.depth.take(ids), lambda: contacts.index[ids], mu, obstacles, h)


def slide_back(x: np.ndarray, x_prev: np.ndarray, ids: np.ndarray, nx: np.ndarray,
               ny: np.ndarray, depth: np.ndarray, index, mu: float, obstacles=(),
               h: float = 0.0) -> None:
    """verlet_friction for the particles `ids` (each once), given the outward normal (nx, ny)
    and the depth of each one's contact; index() gives the obstacle each touches (asked only
    if an obstacle moves). Reads its arguments, writes x alone."""
    xs, ys = x[:, 0], x[:, 1]                  # column views: writing into them moves x
    now = x.T.take(ids, axis=1)                # (2, k): the touching particles' x and y rows
    # the travel of this step, in float64 (NumPy casts both ends before subtracting)...
    travel = np.subtract(now, x_prev.T.take(ids, axis=1), dtype=np.float64)
    mx, my = travel                            # (its rows: views)
    if h and any(ob.velocity[0] or ob.velocity[1] for ob in obstacles):
        # ...relative to the surface it touches (a moving obstacle: the sliding is relative)
        carry = np.array([ob.velocity for ob in obstacles], np.float64) * h
        mx -= carry[index(), 0]
        my -= carry[index(), 1]
    along = mx * nx
    along += my * ny                                          # m . n
    mx -= nx * along                                          # t = m - (m . n) n: its part
    my -= ny * along                                          # along the surface
    # the share of the tangential travel removed: all of it (it sticks: mu * depth >= |t|) or
    # mu * depth / |t| of it (it slides); min(., 1) is that choice in one call
    removable = depth * mu
    slide = np.square(mx)                                     # |t| = sqrt(tx^2 + ty^2)
    slide += np.square(my, out=along)
    gone = np.divide(removable, np.maximum(np.sqrt(slide, out=slide), TINY), out=removable)
    np.minimum(gone, 1.0, out=gone)
    mx *= gone
    my *= gone
    now -= travel.astype(x.dtype)                             # less travel: x moves back
    xs[ids], ys[ids] = now


__all__ = ["Contacts", "coulomb_friction", "verlet_friction", "slide_back"]
