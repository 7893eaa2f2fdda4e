"""The Verlet cloth's obstacle pass (the `collisions` effect of app/physics/cloth_contact.py, read
its docstring first): after the rod sweeps, each obstacle in turn, Jakobsen's projection with
the tunnelling test of app/physics/tunnelling.py in front of it.

    for each obstacle:
        candidates  the particles whose path this substep (from x_prev to x) has a box that
                    meets the obstacle's box (a floor: those below its line): no other particle
                    can touch it or have passed through it
        d, n        signed distance and outward normal of each candidate's end (computed once,
                    for both tests below)
        tunnelling  a path through the obstacle, or in from outside past its middle: the
                    particle is put back where it entered (tunnelling.through_one)
        projection  every candidate inside (d < margin): p += (margin - d) n

The rest is not doing what is not needed, without changing a single result:

* a floor that the whole cloth is clear of (the cloth hanging above it, or lying on a ball and a
  box) costs one max() over the particles, not a distance per particle (`_clear_of`);
* the tunnelling test looks for paths longer than the obstacle allows to go through (2 sqrt(2)
  tolerance for a box; a chord of a ball); when no path of the cloth is that long (the longest
  path is bounded by the path boxes, the same for every obstacle), the test is skipped, with
  the gathering of the paths' starts it needs (`_paths_too_short`);
* what touched is kept as lists (Touched), which friction reads as they are, not as arrays over
  every particle to be cleared each substep and gathered again by friction.

The box's distance (obstacles.Box.distance_xy) calls hypot only past its corners, and friction
and the ball measure lengths as sqrt(x^2 + y^2): hypot was the slowest NumPy call of the pass
(6.8 ns a point against 1.5). sqrt(x^2 + y^2) may differ from hypot in the last bit of a
float64; the cloth's positions are float32, and in every state compared against the pass as it
was (the bench's hanging and heap states, every card of cloth_collisions, the cloth scene on
each obstacle set: 16 runs of 60 to 300 steps) the positions, contacts, penetration_max and
tunneled counts came out identical to the last bit; the float64 depth and normal of the ball's
contacts differ in their last bits. (One more difference, by design: a point less than 1e-12 px
outside a box's face had a normal shorter than 1, its offset over 1e-12; it is now the face's.)

What it costs: the module docstring of app/physics/cloth_contact.py (`python -m app bench
cloth`, the share of a 64 x 64 cloth's step on a ball, a tilted box and the floor).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.physics.obstacles import NEAR_SLACK, Contacts, HalfPlane, near_bounds, project
from app.physics.tunnelling import shortest_dip, through_one


@dataclass
class Touched:
    """What the pass touched, listed: `mask` (n,) True where a particle touched an obstacle
    (was found within the margin of it and moved out); and for those particles, each once:
    their flat indices `ids`, the outward normal (nx, ny) of the obstacle each was pushed out
    of (the last, if two), how far it was pushed along it (`depth`, px: the sum, if two) and
    that obstacle's position in the list (`index`). Friction reads these lists as they are;
    `full()` is the same as the Contacts record of a projection (obstacles.project)."""

    mask: np.ndarray
    ids: np.ndarray
    nx: np.ndarray
    ny: np.ndarray
    depth: np.ndarray
    owners: tuple = ()          # (obstacle's position, how many) of each run of `ids`, in order
    listed_index: np.ndarray | None = None

    @property
    def count(self) -> int:
        return int(self.ids.size)

    @property
    def index(self) -> np.ndarray:
        """The obstacle each listed particle touched, made when first asked (friction asks
        only when an obstacle moves)."""
        if self.listed_index is None:
            self.listed_index = np.repeat(np.array([k for k, _ in self.owners], np.intp),
                                          [size for _, size in self.owners])
        return self.listed_index

    def full(self) -> Contacts:
        n = self.mask.size
        depth, normal, index = np.zeros(n), np.zeros((n, 2)), np.full(n, -1)
        depth[self.ids], normal[self.ids, 0], normal[self.ids, 1] = self.depth, self.nx, self.ny
        index[self.ids] = self.index
        return Contacts(self.mask, depth, normal, index)


def tunnel_and_project(st, start: np.ndarray, x: np.ndarray, movable: np.ndarray) -> Touched:
    """For each obstacle: (1) a broad phase: the particles whose path this substep (its box,
    grown by the margin) meets the obstacle's box: no other can touch it or pass through it
    (the floor: those below its line plus the margin); (2) the signed distance and normal of
    their ends, computed once, for both tests; (3) tunnelling (tunnelling.through_one): a path
    through the obstacle, or in from outside past its middle, puts the particle back where it
    entered (on the surface, on the side it came from: then projected out, it rests there;
    put back where it started the substep instead, it would hover a bar's width above a bar,
    the next step's g h^2 carrying it through again for ever); (4) Jakobsen's projection of
    those inside to the margin: p += (margin - d) n. Returns what touched (Touched).
    st: the contact state (cloth_contact.ContactState); start: (2, n); x: (n, 2), written into."""
    n, margin = len(x), st.margin
    hit = st.scratch.get("touched", n, bool)    # (kept: a fresh mask would cost page faults)
    hit.fill(False)
    touched = []                                # (ids, nx, ny, push, k) of each obstacle
    px, py = x[:, 0], x[:, 1]                   # views: writing into them moves the cloth
    ends_t = x.T                                # (2, n): x and y as rows (a view too)
    sx, sy = start[0], start[1]
    boxes, extremes = None, {}
    moved = 0.0                 # how far a particle may have moved since the boxes were made
    grow = margin + NEAR_SLACK                  # (float32 positions: nothing lost to rounding)
    for k, ob in enumerate(st.obstacles):
        if isinstance(ob, HalfPlane):           # nothing to pass through: where the ends are
            if _clear_of(ob, px, py, margin, extremes):
                continue
            ids = near_bounds(ob, px, py, margin, movable)
        else:
            if boxes is None:                   # each path's box, once for every obstacle
                boxes = [np.minimum(px, sx), np.maximum(px, sx), np.minimum(py, sy),
                         np.maximum(py, sy), None]
                moved = 0.0
            lo_x, hi_x, lo_y, hi_y, _ = boxes
            x0, y0, x1, y1 = ob.bounds()
            near = (hi_x > x0 - grow) & (lo_x < x1 + grow) & (hi_y > y0 - grow) & \
                (lo_y < y1 + grow) & movable
            ids = near.nonzero()[0]
        if ids.size == 0:
            continue
        ends = ends_t.take(ids, axis=1).astype(np.float64)      # (2, k): x and y rows at once
        ex, ey = ends[0], ends[1]
        d, nx, ny = ob.distance_xy(ex, ey)
        if not isinstance(ob, HalfPlane) and not _paths_too_short(ob, st.tolerance, boxes,
                                                                   moved):
            starts = start.take(ids, axis=1).astype(np.float64)
            ax, ay = starts[0], starts[1]
            vx, vy = ends - starts                              # each path, this substep
            back, t, bx, by, through = through_one(ob, ax, ay, vx, vy, d, nx, ny, st.tolerance)
            if back.size:                       # put back: on the surface, its normal there
                ib = ids[back]
                px[ib] = ax[back] + t * vx[back]
                py[ib] = ay[back] + t * vy[back]
                d[back], nx[back], ny[back] = 0.0, bx, by
                st.tunneled += through
                moved = math.inf                # (a path's end moved along it: no bound)
        inside = d < margin
        touching = int(np.count_nonzero(inside))
        if touching == 0:
            continue
        if touching < ids.size:                 # (compress: a mask's take, without nonzero)
            ids, d, nx, ny = (a.compress(inside) for a in (ids, d, nx, ny))
        push = margin - d                                      # Jakobsen: p += (margin - d) n
        px[ids] += (push * nx).astype(x.dtype, copy=False)
        py[ids] += (push * ny).astype(x.dtype, copy=False)
        if boxes is not None and moved < math.inf:
            moved += float(push.max())          # (|n| = 1: no particle moved further)
        hit[ids] = True
        touched.append((ids, nx, ny, push, k))
    return _listed(hit, touched)


def _listed(hit: np.ndarray, touched: list) -> Touched:
    """The Touched record of the obstacles' lists (ids, nx, ny, push, k), in their order. A
    particle found by two obstacles (where they meet, or put back by a tunnelling test after a
    projection) has the pushes added up and the last obstacle's normal, as project() gives it:
    then (only) the lists are merged through arrays over every particle."""
    if not touched:
        none = np.zeros(0)
        return Touched(hit, np.zeros(0, np.intp), none, none, none)
    owners = tuple((k, len(ids_k)) for ids_k, *_, k in touched)
    if len(touched) == 1 or sum(size for _, size in owners) == np.count_nonzero(hit):
        ids, nx, ny, depth = (np.concatenate(parts) if len(touched) > 1 else parts[0]
                              for parts in list(zip(*touched))[:4])
        return Touched(hit, ids, nx, ny, depth, owners)
    n = hit.size                                # a particle is listed twice: through arrays
    depth_all, normal, index_all = np.zeros(n), np.zeros((2, n)), np.full(n, -1)
    for ids_k, nx_k, ny_k, push, k in touched:
        depth_all[ids_k] += push
        normal[0][ids_k], normal[1][ids_k], index_all[ids_k] = nx_k, ny_k, k
    ids = hit.nonzero()[0]
    return Touched(hit, ids, normal[0][ids], normal[1][ids], depth_all[ids],
                   listed_index=index_all[ids])


def _clear_of(plane: HalfPlane, px: np.ndarray, py: np.ndarray, margin: float,
              extremes: dict) -> bool:
    """Whether the whole cloth lies further than the margin from the half-plane (a floor below
    a hanging cloth): then no particle needs its distance. The cloth's extreme x and y in the
    plane's direction (a max or a min: one pass over the particles each, kept in `extremes`
    for the substep) give the nearest any particle comes. (The slack covers the float32
    sums of near_bounds, which would find nothing then either.)"""
    nearest = slack = 0.0
    for coord, p0, n in ((px, plane.px, plane.nx), (py, plane.py, plane.ny)):
        if n:
            key = (id(coord), n < 0)            # towards the plane: the min if n > 0, else max
            if key not in extremes:
                extremes[key] = float(coord.max() if n < 0 else coord.min())
            nearest += (extremes[key] - p0) * n
            slack += 1e-6 * (abs(extremes[key]) + abs(p0) + 1.0)
    return nearest > margin + NEAR_SLACK + slack


def _paths_too_short(ob, tolerance: float, boxes: list, moved: float) -> bool:
    """Whether no path of the cloth this substep is long enough to pass through `ob` or past
    its middle (through_one would find nothing: it tests only paths longer than
    min(shortest_dip, half width)). The longest path is at most the diagonal of the largest
    path box, plus how far the obstacles before this one moved a particle since the boxes
    were made (`moved`); the diagonal is measured once a substep (boxes[4])."""
    reach = min(shortest_dip(ob, tolerance), ob.half_width())
    if moved >= reach:
        return False
    if boxes[4] is None:
        lo_x, hi_x, lo_y, hi_y, _ = boxes
        wide, tall = float((hi_x - lo_x).max()), float((hi_y - lo_y).max())
        boxes[4] = math.sqrt(wide * wide + tall * tall) * (1 + 1e-6)   # (float32 rounding)
    return boxes[4] + moved <= reach


def may_touch(st) -> bool:
    """obstacles_may_touch, asked again only when an obstacle has moved or turned."""
    key = tuple(tuple(vars(ob).values()) for ob in st.obstacles)   # every field of each
    if st.touch_key != key:
        st.touch_key, st.touch_value = key, obstacles_may_touch(st.obstacles, st.margin)
    return st.touch_value


def obstacles_may_touch(obstacles, margin: float = 0.0) -> bool:
    """Whether any two obstacles' bounds (grown by margin) meet (a half-plane: whether the other's
    bounds reach it): only then can a particle pushed out of one land in another."""
    grown = [ob.bounds() for ob in obstacles]
    for a in range(len(obstacles)):
        for b in range(a + 1, len(obstacles)):
            (ax0, ay0, ax1, ay1), (bx0, by0, bx1, by1) = grown[a], grown[b]
            plane = next((o for o in (obstacles[a], obstacles[b]) if isinstance(o, HalfPlane)),
                         None)
            if plane is not None:
                other = grown[b] if plane is obstacles[a] else grown[a]
                if math.isinf(other[0]):
                    return True                                 # two half-planes
                lowest = min((cx - plane.px) * plane.nx + (cy - plane.py) * plane.ny
                             for cx in (other[0], other[2]) for cy in (other[1], other[3]))
                if lowest < 2 * margin:
                    return True
            elif ax0 < bx1 + 2 * margin and bx0 < ax1 + 2 * margin and \
                    ay0 < by1 + 2 * margin and by0 < ay1 + 2 * margin:
                return True
    return False


def settle_corners(st, x: np.ndarray, passes: int = 3) -> None:
    """Where obstacles meet (a table's leg on the floor), a particle pushed out of one may sit
    in the next: project the touching particles again, a few passes (only those: cheap)."""
    ids = st.contacts.mask.nonzero()[0]
    for _ in range(passes):
        if ids.size == 0:
            return
        sub = x[ids].copy()
        again = project(st.obstacles, sub, st.margin)
        x[ids] = sub
        ids = ids[again.mask]
