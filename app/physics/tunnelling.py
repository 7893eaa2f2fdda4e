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

from app.physics.obstacles import Box, Circle, HalfPlane, Obstacle, Segment

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0       # 0.618...: golden-section search's shrink factor
BISECTIONS = 20     # halvings that find a path's entry point: to 1e-6 of the path


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


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def dips_below(ob: Obstacle, p0: np.ndarray, p1: np.ndarray, depth: float
               ) -> tuple[np.ndarray, np.ndarray]:
    """(mask, t): whether each path p0 -> p1 reaches more than `depth` px inside the obstacle,
    and a place t (0..1) on it where it does. The points deeper than `depth` in a circle, box or
    capsule form the same shape shrunk by `depth`, so this is one exact intersection test per
    shape (closest point of the path to the centre; slab clipping; segment against segment);
    other shapes fall back on path_min_distance."""
    e = p1 - p0
    e2 = np.maximum((e * e).sum(1), 1e-300)
    if isinstance(ob, Circle):
        t = np.clip(((ob.cx - p0[:, 0]) * e[:, 0] + (ob.cy - p0[:, 1]) * e[:, 1]) / e2, 0, 1)
        q = p0 + t[:, None] * e
        return np.hypot(q[:, 0] - ob.cx, q[:, 1] - ob.cy) < ob.radius - depth, t
    if isinstance(ob, HalfPlane):
        d0, d1 = ob.signed_distance(p0)[0], ob.signed_distance(p1)[0]
        return np.minimum(d0, d1) < -depth, np.where(d0 < d1, 0.0, 1.0)
    if isinstance(ob, Box):
        (ux, uy), (vx, vy) = ob.axes()
        lo, hi = np.zeros(len(p0)), np.ones(len(p0))
        ok = np.ones(len(p0), bool)
        for (ax, ay), half in (((ux, uy), ob.half_w - depth), ((vx, vy), ob.half_h - depth)):
            if half <= 0:
                return np.zeros(len(p0), bool), lo
            s0 = (p0[:, 0] - ob.cx) * ax + (p0[:, 1] - ob.cy) * ay    # along this axis
            ds = e[:, 0] * ax + e[:, 1] * ay
            flat = np.abs(ds) < 1e-12
            ok &= ~flat | (np.abs(s0) < half)
            with np.errstate(divide="ignore", invalid="ignore"):
                t1, t2 = (-half - s0) / ds, (half - s0) / ds
            lo = np.where(flat, lo, np.maximum(lo, np.minimum(t1, t2)))
            hi = np.where(flat, hi, np.minimum(hi, np.maximum(t1, t2)))
        return ok & (lo < hi), np.clip((lo + hi) / 2, 0, 1)
    if isinstance(ob, Segment):
        a = np.array([ob.ax, ob.ay])
        f = np.array([ob.bx - ob.ax, ob.by - ob.ay])
        cands_d, cands_t = [], []
        for t in (np.zeros(len(p0)), np.ones(len(p0))):      # the path's ends to the core
            cx, cy = ob.closest(p0 + t[:, None] * e)
            q = p0 + t[:, None] * e
            cands_d.append(np.hypot(q[:, 0] - cx, q[:, 1] - cy))
            cands_t.append(t)
        for end in (a, a + f):                               # the core's ends to the path
            t = np.clip(((end[0] - p0[:, 0]) * e[:, 0] + (end[1] - p0[:, 1]) * e[:, 1]) / e2, 0, 1)
            q = p0 + t[:, None] * e
            cands_d.append(np.hypot(q[:, 0] - end[0], q[:, 1] - end[1]))
            cands_t.append(t)
        denom = _cross(e[:, 0], e[:, 1], f[0], f[1])          # the two segments cross: 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = _cross(a[0] - p0[:, 0], a[1] - p0[:, 1], f[0], f[1]) / denom
            u = _cross(a[0] - p0[:, 0], a[1] - p0[:, 1], e[:, 0], e[:, 1]) / denom
        cross = (denom != 0) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
        cands_d.append(np.where(cross, 0.0, np.inf))
        cands_t.append(np.where(cross, t, 0.0))
        d, ts = np.stack(cands_d), np.stack(cands_t)
        pick = d.argmin(0)
        cols = np.arange(len(p0))
        return d[pick, cols] < ob.thickness - depth, ts[pick, cols]
    dmin, t = path_min_distance(ob, p0, p1)
    return dmin < -depth, t


def swept(obstacles, p0: np.ndarray, p1: np.ndarray, tolerance: float = 0.5,
          movable: np.ndarray | None = None, find_entry: bool = True) -> Sweep:
    """Which paths p0 -> p1 ((n, 2)) start and end no more than `tolerance` inside every
    obstacle, and pass more than `tolerance` px deep through one on the way: tunnelling, which
    a projection at the end of the step cannot see. Only paths whose bounding box meets the
    obstacle's and that fail the bound (d0 + d1 - L)/2 >= -tolerance are tested (see the module
    docstring), so resting and slow particles cost almost nothing. Returns a Sweep with each
    such path's entry point (where it first reached the surface, by bisection; NaN with
    find_entry=False, for a caller that only needs which paths went through)."""
    p0 = np.asarray(p0, np.float64)
    p1 = np.asarray(p1, np.float64)
    n = len(p0)
    mask = np.zeros(n, bool)
    entry = np.full((n, 2), np.nan)
    index = np.full(n, -1)
    # a path that ends outside yet dips `tolerance` deep is at least 2 x tolerance long (|grad d|
    # = 1: it must go down and come back up): the short ones, nearly all, are done at once
    step = p1 - p0
    moving = step[:, 0] ** 2 + step[:, 1] ** 2 > (2 * tolerance) ** 2
    if movable is not None:
        moving &= movable
    fast = np.flatnonzero(moving)
    if fast.size == 0:
        return Sweep(mask, entry, index)
    q0, q1 = p0[fast], p1[fast]
    lo_x, hi_x = np.minimum(q0[:, 0], q1[:, 0]), np.maximum(q0[:, 0], q1[:, 0])
    lo_y, hi_y = np.minimum(q0[:, 1], q1[:, 1]), np.maximum(q0[:, 1], q1[:, 1])
    for k, ob in enumerate(obstacles):
        x0, y0, x1, y1 = ob.bounds()
        near = (hi_x > x0) & (lo_x < x1) & (hi_y > y0) & (lo_y < y1) & ~mask[fast]
        ids = fast[near]
        if ids.size == 0:
            continue
        a, b = p0[ids], p1[ids]
        d0, d1 = ob.distance_xy(a[:, 0], a[:, 1])[0], ob.distance_xy(b[:, 0], b[:, 1])[0]
        length = np.hypot(*(b - a).T)
        suspect = (d0 >= -tolerance) & (d1 >= -tolerance) & ((d0 + d1 - length) / 2 < -tolerance)
        ids, a, b = ids[suspect], a[suspect], b[suspect]
        if ids.size == 0:
            continue
        through, t_in = dips_below(ob, a, b, tolerance)
        ids, a, b, t_in = ids[through], a[through], b[through], t_in[through]
        if ids.size == 0:
            continue
        mask[ids] = True
        index[ids] = k
        if not find_entry:
            continue
        # the entry: where d first reaches 0 on [0, t_in] (d < 0 at t_in), by bisection
        lo, hi = np.zeros(ids.size), t_in
        step = b - a
        for _ in range(BISECTIONS):
            mid = (lo + hi) / 2
            outside = ob.distance_xy(a[:, 0] + mid * step[:, 0], a[:, 1] + mid * step[:, 1])[0] >= 0
            lo = np.where(outside, mid, lo)
            hi = np.where(outside, hi, mid)
        entry[ids] = a + lo[:, None] * step
    return Sweep(mask, entry, index)


__all__ = ["path_min_distance", "dips_below", "Sweep", "swept", "GOLDEN"]
