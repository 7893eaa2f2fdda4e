"""Tunnelling: did a particle pass *through* an obstacle during one step?

Projection (app/physics/obstacles.py) only looks at where a particle ends a step. A particle
that moves further in one step than an obstacle is thick can start on one side and end on the
other, outside, untouched: it tunnelled (falling_balls shows pymunk's balls doing the same).
To see it, look at the whole path p0 -> p1 of the step, a straight line for a Verlet step.

Two facts make that cheap for the lab's convex obstacles (circle, box, half-plane, capsule):

* the signed distance d to a convex shape is a convex function of position, so along the path
  d(t) = d(p0 + t (p1 - p0)), 0 <= t <= 1, has a single minimum: golden-section search finds it
  (each round keeps the part of [lo, hi] that must hold the minimum, 0.618 of it), for all the
  suspicious paths at once;
* |grad d| = 1, so d cannot fall faster than 1 px per px travelled: a path of length L between
  ends at distances d0 and d1 never dips below (d0 + d1 - L) / 2. Paths that pass this bound
  (resting and slow particles: nearly all) need no search.

A path that dips more than `tolerance` px inside while both its ends are outside went through.
`swept` returns those paths and, for each, the entry point (where it first met the surface, by
bisection between the start and the deepest point), where a simulation can stop the particle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.physics.obstacles import Obstacle

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0       # 0.618...: golden-section search's shrink factor


def path_min_distance(obstacle: Obstacle, p0: np.ndarray, p1: np.ndarray,
                      iterations: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """(d_min, t_min): the smallest signed distance along each straight path p0 -> p1 ((n, 2)
    each) and where on it (0..1). The signed distance to a convex shape is convex along a line,
    so golden-section search finds its one minimum; 40 rounds narrow t to 1e-8 of the path."""
    p0 = np.asarray(p0, np.float64)
    p1 = np.asarray(p1, np.float64)
    step = p1 - p0

    def at(t):
        return obstacle.signed_distance(p0 + t[:, None] * step)[0]

    lo, hi = np.zeros(len(p0)), np.ones(len(p0))
    a, b = hi - GOLDEN * (hi - lo), lo + GOLDEN * (hi - lo)    # two probes inside [lo, hi]
    fa, fb = at(a), at(b)
    for _ in range(iterations):
        left = fa < fb              # the minimum lies in [lo, b]: keep it, else keep [a, hi]
        hi = np.where(left, b, hi)
        lo = np.where(left, lo, a)
        # one probe carries over (the old a becomes the new b, or the old b the new a), one is new
        new = np.where(left, hi - GOLDEN * (hi - lo), lo + GOLDEN * (hi - lo))
        f_new = at(new)
        a, b, fa, fb = (np.where(left, new, b), np.where(left, a, new),
                        np.where(left, f_new, fb), np.where(left, fa, f_new))
    t = (lo + hi) / 2
    # the ends too: the minimum of a convex function on [0, 1] may sit at an end
    cand = np.stack([at(t), at(np.zeros_like(t)), at(np.ones_like(t))])
    pick = cand.argmin(0)
    return cand.min(0), np.choose(pick, [t, np.zeros_like(t), np.ones_like(t)])


@dataclass
class Sweep:
    """Paths that passed through an obstacle in one step: `mask` per point, and for those, the
    first point of the path on the obstacle's surface (`entry`, (n, 2), NaN elsewhere) and the
    obstacle's index."""

    mask: np.ndarray
    entry: np.ndarray
    index: np.ndarray

    @property
    def count(self) -> int:
        return int(np.count_nonzero(self.mask))


def swept(obstacles, p0: np.ndarray, p1: np.ndarray, tolerance: float = 0.5,
          movable: np.ndarray | None = None) -> Sweep:
    """Which paths p0 -> p1 ((n, 2)) start outside every obstacle's tolerance, end outside, and
    pass more than `tolerance` px deep through an obstacle on the way: tunnelling, which a
    projection at the end of the step cannot see. Only paths failing the bound (d0 + d1 - L)/2
    >= -tolerance are searched (see the module docstring), so resting and slow particles cost a
    distance each. Returns a Sweep with each such path's entry point (where it first reached
    the surface)."""
    p0 = np.asarray(p0, np.float64)
    p1 = np.asarray(p1, np.float64)
    n = len(p0)
    mask = np.zeros(n, bool)
    entry = np.full((n, 2), np.nan)
    index = np.full(n, -1)
    length = np.hypot(*(p1 - p0).T)
    for k, ob in enumerate(obstacles):
        d0, d1 = ob.signed_distance(p0)[0], ob.signed_distance(p1)[0]
        suspect = (d0 >= -tolerance) & (d1 >= -tolerance) & \
                  ((d0 + d1 - length) / 2 < -tolerance) & ~mask
        if movable is not None:
            suspect &= movable
        ids = np.flatnonzero(suspect)
        if ids.size == 0:
            continue
        dmin, tmin = path_min_distance(ob, p0[ids], p1[ids])
        through = dmin < -tolerance
        ids, tmin = ids[through], tmin[through]
        if ids.size == 0:
            continue
        # the entry: where d first reaches 0 on [0, t_min] (d decreases there), by bisection
        lo, hi = np.zeros(ids.size), tmin.copy()
        step = p1[ids] - p0[ids]
        for _ in range(40):
            mid = (lo + hi) / 2
            outside = ob.signed_distance(p0[ids] + mid[:, None] * step)[0] >= 0
            lo = np.where(outside, mid, lo)
            hi = np.where(outside, hi, mid)
        mask[ids] = True
        entry[ids] = p0[ids] + lo[:, None] * step
        index[ids] = k
    return Sweep(mask, entry, index)


__all__ = ["path_min_distance", "Sweep", "swept", "GOLDEN"]
