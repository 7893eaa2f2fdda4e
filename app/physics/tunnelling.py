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
`swept` returns those paths and, for each, the entry point (where it first met the surface,
solved exactly per shape: Obstacle.entry), where a simulation can stop the particle. A half-plane
is never tunnelled through: d is linear along a path, so a path with both ends outside never
dips in (swept skips it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.physics.obstacles import Box, Circle, HalfPlane, Obstacle, Segment
from app.physics.paths import TINY

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


def shortest_dip(ob: Obstacle, depth: float) -> float:
    """The length of the shortest straight path that starts and ends outside `ob` and yet
    reaches more than `depth` px inside it: a shorter path cannot have gone through, and the
    sweep test skips it. A ball of radius r: the chord (r - depth) from its centre,
    2 sqrt(2 r depth - depth^2), and a capsule the same at its end discs; a box: a cut across
    a corner at 45 degrees, 2 sqrt(2) depth, or straight across its thinner side; a half-plane:
    none (d is linear along a path: both ends outside, so is all of it)."""
    w = ob.half_width()
    if isinstance(ob, HalfPlane) or depth >= w > 0:
        return math.inf
    if isinstance(ob, (Circle, Segment)):
        return 2.0 * math.sqrt(max(2.0 * w * depth - depth * depth, 0.0))
    if isinstance(ob, Box):
        return min(2.0 * math.sqrt(2.0) * depth, 2.0 * w)
    return 2.0 * depth


@dataclass
class Sweep:
    """Paths that passed through an obstacle in one step: `mask` per point, and for those, the
    first point of the path on the obstacle's surface (`entry`, (n, 2), NaN elsewhere) and the
    obstacle's index. With swept(past_middle=True), `deep` marks the paths that came in from
    outside and end inside, longer than its half width (their entry is given too; not in
    `count`)."""

    mask: np.ndarray
    entry: np.ndarray
    index: np.ndarray
    deep: np.ndarray | None = None

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


NOTHING_BACK = (np.zeros(0, np.intp), np.zeros(0), np.zeros(0), np.zeros(0), 0)  # (read-only)
for _empty in NOTHING_BACK[:4]:
    _empty.flags.writeable = False


def through_one(ob: Obstacle, ax: np.ndarray, ay: np.ndarray, vx: np.ndarray, vy: np.ndarray,
                d1: np.ndarray, n1x: np.ndarray, n1y: np.ndarray, tolerance: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, int]:
    """swept(past_middle=True) against one obstacle, for paths a -> a + v whose end's signed
    distance d1 and outward normal n1 the caller has already (the projection needs them too):
    (back, t, nx, ny, through). `back`: the indices of the paths to put back where they
    entered: those with both ends outside that went more than `tolerance` deep (`through`
    counts them), and those that came in from outside past the middle (end inside, longer
    than the half width); t: where each of them first met the surface (Obstacle.entry), 0..1
    along v, and (nx, ny) the outward normal there (entry_normal).

    A third bound joins the two of the module docstring: d is convex, so along the path it lies
    above its tangent at the end, d(t) >= d1 - (1 - t) n1 . v; a path whose end is outside can
    only dip below -tolerance if d1 - n1 . v does. A particle sliding along a surface (n1 . v
    about 0) is dismissed by it; the length bound alone let every sliding particle longer than
    2 sqrt(2) tolerance through to the exact test (most of a cloth heaped on a tilted box)."""
    none = NOTHING_BACK
    shortest = shortest_dip(ob, tolerance)
    if isinstance(ob, HalfPlane):
        return none                                      # d linear along a path: nothing
    half = ob.half_width()
    length2 = vx * vx + vy * vy
    reach = min(shortest, half)
    longest2 = length2.max(initial=0.0)
    if longest2 <= reach * reach:
        return none                     # every path too short for either test (resting cloth)
    outside = d1 >= 0
    maybe = (length2 > shortest * shortest) & (d1 - (n1x * vx + n1y * vy) < -tolerance)
    if longest2 > half * half:          # (a path that ends inside: past the middle?)
        maybe = np.where(outside, maybe, length2 > half * half)
    else:
        maybe &= outside
    k = maybe.nonzero()[0]
    if k.size == 0:
        return none
    d0 = ob.distance(ax[k], ay[k])
    length, out = np.sqrt(length2[k]), outside[k]
    back = (d0 >= 0) & ~out & (length > half)            # came in from outside, past the middle
    through, t_in = 0, None
    if out.any():
        dips = (d0 >= 0) & out & ((d0 + d1[k] - length) / 2 < -tolerance)
        if dips.any():                                   # the exact test, for the few left
            ids = dips.nonzero()[0]
            p0 = np.column_stack((ax[k[ids]], ay[k[ids]]))
            p1 = p0 + np.column_stack((vx[k[ids]], vy[k[ids]]))
            exact, t_dip = dips_below(ob, p0, p1, tolerance)
            dips[ids[~exact]] = False
            t_in = np.ones(k.size)
            t_in[ids] = t_dip
            through = int(np.count_nonzero(dips))
            back |= dips
    back = back.nonzero()[0]
    if back.size == 0:
        return none
    kb = k[back]
    # where the path first met the surface (before its deepest point), and the normal there
    t, nx, ny = entry_normal(ob, ax[kb], ay[kb], vx[kb], vy[kb])
    return kb, (t if t_in is None else np.minimum(t, t_in[back])), nx, ny, through


def entry_normal(ob: Obstacle, ax: np.ndarray, ay: np.ndarray, ex: np.ndarray, ey: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, nx, ny): Obstacle.entry's t for paths a + t e that start outside and reach inside,
    and the outward normal where they meet the surface. A ball's and a box's come with the
    entry, written for such paths alone (often one particle: the NumPy calls are the cost):
    a ball's is the smaller root of |a + t e - c| = r and the radius through it; a box's the
    last face its slabs were entered by (slab clipping, the far faces not needed). Other
    shapes ask Obstacle.entry and distance_xy at the entry point."""
    if isinstance(ob, Circle):
        fx, fy = ax - ob.cx, ay - ob.cy
        a = np.maximum(ex * ex + ey * ey, TINY)
        b = fx * ex + fy * ey
        c = fx * fx + fy * fy - ob.radius * ob.radius       # >= 0: the start is outside
        t = np.clip((-b - np.sqrt(np.maximum(b * b - a * c, 0.0))) / a, 0.0, 1.0)
        return t, (fx + t * ex) / ob.radius, (fy + t * ey) / ob.radius
    if isinstance(ob, Box):
        (ux, uy), (wx, wy) = ob.axes()
        dx, dy = ax - ob.cx, ay - ob.cy                   # the path in the box's own frame
        near = []
        for s0, ds, half in ((dx * ux + dy * uy, ex * ux + ey * uy, ob.half_w),
                             (dx * wx + dy * wy, ex * wx + ey * wy, ob.half_h)):
            # where it crosses the nearer face of this slab (parallel: +-1e300, never/always)
            ds = np.copysign(np.maximum(np.abs(ds), 1e-300), ds)
            near.append(np.minimum((-half - s0) / ds, (half - s0) / ds))
        face_x = near[0] >= near[1]
        t = np.clip(np.maximum(near[0], near[1]), 0.0, 1.0)
        # entering a face: the normal points back along the path's motion across it
        g = np.sign(np.where(face_x, ex * ux + ey * uy, ex * wx + ey * wy))
        gx, gy = -g * face_x, -g * ~face_x
        return t, gx * ux + gy * wx, gx * uy + gy * wy
    t = ob.entry(ax, ay, ex, ey)
    _, nx, ny = ob.distance_xy(ax + t * ex, ay + t * ey)
    return t, nx, ny


def swept(obstacles, p0: np.ndarray, p1: np.ndarray, tolerance: float = 0.5,
          movable: np.ndarray | None = None, find_entry: bool = True,
          past_middle: bool = False) -> Sweep:
    """Which paths p0 -> p1 ((n, 2)) start and end outside an obstacle (a path that ends
    inside is the projection's), and pass more than `tolerance` px deep through it on the way:
    tunnelling, which a projection at the end of the step cannot see. Only paths whose
    bounding box meets the obstacle's, that are longer than `shortest_dip` and that fail the
    bound (d0 + d1 - L)/2 >= -tolerance are tested (see the module docstring), so resting and
    slow particles cost almost nothing. Returns a Sweep with each
    such path's entry point (where it first reached the surface: Obstacle.entry; NaN with
    find_entry=False, for a caller that only needs which paths went through).

    past_middle: also find the paths that came in from outside and end inside, and that are
    longer than the obstacle's half width: only they can have crossed its middle (a 6 px step
    into a 10 px table top), where the shortest way out is through the far side. They are in
    `deep`, with their entry, so that the caller puts them back on the side they came from
    before projecting (a shorter path is pushed out the near side by the projection alone)."""
    p0 = np.asarray(p0, np.float64)
    p1 = np.asarray(p1, np.float64)
    return swept_xy(obstacles, p0[:, 0], p0[:, 1], p1[:, 0], p1[:, 1], tolerance, movable,
                    find_entry, past_middle)


def swept_xy(obstacles, ax_: np.ndarray, ay_: np.ndarray, bx_: np.ndarray, by_: np.ndarray,
             tolerance: float = 0.5, movable: np.ndarray | None = None, find_entry: bool = True,
             past_middle: bool = False) -> Sweep:
    """swept() for paths given by the x and y columns of their starts (ax, ay) and ends
    (bx, by): the same test, without building (n, 2) arrays (the cloth hands over its rows)."""
    n = len(ax_)
    mask = np.zeros(n, bool)
    deep = np.zeros(n, bool) if past_middle else None
    entry = np.full((n, 2), np.nan)
    index = np.full(n, -1)
    # a path that ends outside yet dips `tolerance` deep is at least 2 x tolerance long (|grad d|
    # = 1: it must go down and come back up): the short ones, nearly all, are done at once
    ex_, ey_ = bx_ - ax_, by_ - ay_
    length2 = ex_ * ex_ + ey_ * ey_
    moving = length2 > (0.0 if past_middle else (2 * tolerance) ** 2)
    if movable is not None:
        moving &= movable
    if moving.all():                               # (a caller that picked the paths already)
        fast = np.arange(n)
    else:
        fast = moving.nonzero()[0]
        if fast.size == 0:
            return Sweep(mask, entry, index, deep)
        ax_, ay_, ex_, ey_, length2 = ax_[fast], ay_[fast], ex_[fast], ey_[fast], length2[fast]
    lo_x, hi_x = np.minimum(ax_, ax_ + ex_), np.maximum(ax_, ax_ + ex_)
    lo_y, hi_y = np.minimum(ay_, ay_ + ey_), np.maximum(ay_, ay_ + ey_)
    done = np.zeros(fast.size, bool)               # caught by an earlier obstacle
    any_done = False
    for k, ob in enumerate(obstacles):
        shortest = shortest_dip(ob, tolerance)
        if past_middle:
            shortest = min(shortest, ob.half_width())
        if math.isinf(shortest):
            continue                                  # a half-plane: never gone through
        x0, y0, x1, y1 = ob.bounds()
        near = (hi_x > x0) & (lo_x < x1) & (hi_y > y0) & (lo_y < y1)
        near &= length2 > shortest * shortest         # too short to have gone through
        if any_done:
            near &= ~done
        sel = near.nonzero()[0]
        if sel.size == 0:
            continue
        ax, ay, ex, ey = ax_[sel], ay_[sel], ex_[sel], ey_[sel]
        # the end first: a path from outside (d0 >= 0) can only dip `tolerance` deep if
        # d1 < L - 2 tolerance, and only cross the middle if it is longer than the half width;
        # the start's distance is needed for the others only
        d1, length = ob.distance(ax + ex, ay + ey), np.sqrt(length2[sel])
        wanted = (d1 >= 0) & (d1 < length - 2 * tolerance)
        if past_middle:
            wanted |= (d1 < 0) & (length > ob.half_width())
        keep = wanted.nonzero()[0]
        if keep.size == 0:
            continue
        sel, ax, ay, ex, ey, d1, length = (sel[keep], ax[keep], ay[keep], ex[keep], ey[keep],
                                           d1[keep], length[keep])
        d0 = ob.distance(ax, ay)
        hit = (d0 >= 0) & (d1 >= 0) & ((d0 + d1 - length) / 2 < -tolerance)   # suspects
        t_in = None
        if hit.any():
            ids = hit.nonzero()[0]
            a, b = np.column_stack((ax[ids], ay[ids])), np.column_stack((ax[ids] + ex[ids],
                                                                         ay[ids] + ey[ids]))
            through, t = dips_below(ob, a, b, tolerance)
            hit[ids[~through]] = False
            t_in = np.ones(sel.size)
            t_in[ids[through]] = t[through]
            mask[fast[sel[ids[through]]]] = True
        if past_middle:
            # every such path is stopped where it came in (what a continuous collision test does
            # at its time of impact); a path shorter than the half width cannot have crossed
            # the middle, and the projection pushes it out the near side anyway
            crossed = (d0 >= 0) & (d1 < 0) & (length > ob.half_width())
            deep[fast[sel[crossed]]] = True
            hit |= crossed
        hits = hit.nonzero()[0]
        if hits.size == 0:
            continue
        sel, ax, ay, ex, ey = sel[hits], ax[hits], ay[hits], ex[hits], ey[hits]
        done[sel] = True
        any_done = True
        index[fast[sel]] = k
        if not find_entry:
            continue
        # the entry: where the path first meets the surface (the shape's exact `entry`; convex,
        # so it is the one crossing before the deepest point t_in)
        t = ob.entry(ax, ay, ex, ey)
        if t_in is not None:
            t = np.minimum(t, t_in[hits])
        entry[fast[sel], 0] = ax + t * ex
        entry[fast[sel], 1] = ay + t * ey
    return Sweep(mask, entry, index, deep)


__all__ = ["path_min_distance", "dips_below", "shortest_dip", "Sweep", "swept", "swept_xy",
           "through_one", "entry_normal",
           "GOLDEN"]
