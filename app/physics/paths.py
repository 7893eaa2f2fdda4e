"""Straight paths against the obstacles' shapes (app/physics/obstacles.py): where a path first
enters a disc or a box, solved exactly, and project()'s guard that puts a point that came in past
an obstacle's middle back where it entered. Kept apart so that obstacles.py stays readable; it
imports these (and the shapes' `entry` methods call them).

A path is a + t e, 0 <= t <= 1 (a: its start, e: its whole step), given by x and y columns.
"""

from __future__ import annotations

import numpy as np

TINY = 1e-12                                 # shortest length we divide by (no 0/0)


def circle_entry(fx, fy, ex, ey, r):
    """(t, hit): the first t in [0, 1] at which f + t e (f: the start relative to the centre)
    is r from the centre, i.e. the smaller root of |f + t e|^2 = r^2; t = 0 for a start
    inside; hit False where the path misses the disc."""
    a = np.maximum(ex * ex + ey * ey, TINY)
    b = fx * ex + fy * ey                                # half the linear coefficient
    c = fx * fx + fy * fy - r * r
    disc = b * b - a * c
    t = (-b - np.sqrt(np.maximum(disc, 0.0))) / a
    t = np.where(c <= 0, 0.0, t)
    return np.minimum(np.maximum(t, 0.0), 1.0), (disc >= 0) & (t <= 1) & ((c <= 0) | (t >= 0))


def slab_entry(sx, sy, ex, ey, half_x, half_y):
    """(t, hit): where the path s + t e (in a box's own frame) first enters |x| <= half_x,
    |y| <= half_y, by slab clipping: on each axis the path is between the two faces for t in
    [t_near, t_far]; it is inside the box where all those intervals overlap (and [0, 1])."""
    lo, hi = 0.0, 1.0
    for s0, ds, half in ((sx, ex, half_x), (sy, ey, half_y)):
        flat = np.abs(ds) < TINY                         # parallel to this axis' faces
        step = np.where(flat, 1.0, ds)                   # (no 0/0: flat paths are set below)
        t1, t2 = (-half - s0) / step, (half - s0) / step
        t_near, t_far = np.minimum(t1, t2), np.maximum(t1, t2)
        if flat.any():          # rare: between the faces for ever, or never
            t_near[flat] = np.where(np.abs(s0[flat]) <= half, -np.inf, np.inf)
            t_far[flat] = np.inf
        lo, hi = np.maximum(lo, t_near), np.minimum(hi, t_far)
    hit = lo <= hi
    return np.where(hit, lo, 0.0), hit


def back_to_entry(ob, ids, d, nx, ny, px, py, start):
    """project()'s guard against popping out of the far side: the points `ids` (inside `ob`,
    at distance d with normal (nx, ny)) whose start was outside with a normal against theirs
    are moved to where the straight path start -> now met the surface (Obstacle.entry);
    returns their new d and normal (the others' unchanged). Only points that travelled more
    than the obstacle's half width can have crossed its middle: the others are not looked at."""
    sx, sy = start[0][ids].astype(np.float64), start[1][ids].astype(np.float64)
    tx, ty = px[ids] - sx, py[ids] - sy
    far = (tx * tx + ty * ty > ob.half_width() ** 2).nonzero()[0]
    if far.size == 0:
        return d, nx, ny
    d0, n0x, n0y = ob.distance_xy(sx[far], sy[far])
    c = far[(d0 >= 0) & (n0x * nx[far] + n0y * ny[far] < 0)]     # it crossed the middle
    if c.size == 0:
        return d, nx, ny
    ax, ay = sx[c], sy[c]
    ex, ey = px[ids[c]] - ax, py[ids[c]] - ay
    t = ob.entry(ax, ay, ex, ey)
    qx, qy = ax + t * ex, ay + t * ey
    px[ids[c]], py[ids[c]] = qx, qy
    dq, nqx, nqy = ob.distance_xy(qx, qy)
    d, nx, ny = d.copy(), nx.copy(), ny.copy()
    d[c], nx[c], ny[c] = dq, nqx, nqy
    return d, nx, ny


__all__ = ["circle_entry", "slab_entry", "back_to_entry"]
