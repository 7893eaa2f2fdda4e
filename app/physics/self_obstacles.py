"""The obstacles projected before each sweep of the cloth's self-collision, looked at only where
a point may be near one.

Self-collision (app/physics/cloth_contact.py) projects the obstacles before each of its sweeps,
so that a pair resting on the floor is parted by moving the upper particle.
obstacles.near_bounds finds the points within a margin of an obstacle's bounds: some 8 passes
over the points (and a list of indices) even when none is near, as while a crumpled cloth falls
towards the floor. `clear_of` tells "none is near" from the points' extremes (a half-plane: the
smallest or largest x, y or both, as its normal points: one reduction for a floor; an obstacle
with bounds: all four, the smallest and largest x and y): near_bounds's test at the corner of
the points' box nearest the obstacle (for bounds: the points' box beyond one side of them). Each
operation of that test is monotone in a coordinate (rounding too), so where the corner does not
pass it, no point does. The corner is computed in double precision with 1e-5 of the numbers'
size to spare for float32's rounding (the positions', and the obstacle's numbers rounded to
them: at most ~3e-7 of that size), so a positive answer is never wrong; near the bounds it is
not positive and near_bounds decides, as before. It is a distance: points that then move by at
most that much are still clear (what a sweep can move a particle: cloth_contact.self_collide).

Measured and not kept (2026-11-27, the self-collision pass over the bench's 15 steps against the
code before, in turns in one process, 31-101 rounds, medians, load 0.1-0.4): before the first
sweep, the extremes the search has just taken for its grid (neighbours.fine_grid) handed to
clear_of instead of reducing the points again (nothing moved since: the same numbers, the same
positions to the last bit in the bench's five states). The pass 0.987-0.999 x crumpled (four
runs), hanging 0.98, fold card 1.00 x: under 1 %, where ~15 us of the look was hoped for.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.obstacles import NEAR_SLACK, HalfPlane, near_bounds, project

SPARE = 1e-5      # of the numbers' size: the float32 rounding of the test (~3e-7) and more


def push_out(st, points: np.ndarray, movable: np.ndarray) -> float:
    """project(st.obstacles, points, st.margin, movable), without the contacts it returns and
    with nothing made while no point is near an obstacle's bounds (a sweep above the floor:
    told from the points' extremes, clear_of, unless the last call found some near: a cloth
    lying on the floor asks near_bounds at once). st: the cloth's ContactState. Returns how far
    every point is from every obstacle's bounds (> 0), or -inf."""
    obstacles, margin, px, py = st.obstacles, st.margin, points[:, 0], points[:, 1]
    clear = math.inf
    for k, ob in enumerate(obstacles):
        gap = -math.inf if st.pushed else clear_of(ob, px, py, margin)
        if gap > 0:
            clear = min(clear, gap)
        elif near_bounds(ob, px, py, margin, movable).size:
            project(obstacles[k:], points, margin, movable)     # (it skips those before k)
            st.pushed = True
            return -math.inf
        else:
            clear = -math.inf
    st.pushed = False
    return clear


def clear_of(ob, px: np.ndarray, py: np.ndarray, margin: float) -> float:
    """How far (px) every point lies beyond near_bounds(ob, px, py, margin)'s reach (whatever
    `movable`), less the spare: > 0 if it finds no point; <= 0 or NaN if it may find some."""
    margin += NEAR_SLACK                        # (what near_bounds adds)
    if isinstance(ob, HalfPlane):   # (a normal's zero component adds 0 or NaN: no reduction)
        dot, size = 0.0, abs(margin)
        for p, o, nk in ((px, ob.px, ob.nx), (py, ob.py, ob.ny)):
            if nk != 0:                         # the point furthest against the normal
                e = float((np.minimum if nk > 0 else np.maximum).reduce(p))
                dot, size = dot + (e - o) * nk, size + abs(e) + abs(o)
        return dot - SPARE * size - margin      # (the normal is a unit vector)
    x0, y0, x1, y1 = ob.bounds()
    lo_x, hi_x = float(np.minimum.reduce(px)), float(np.maximum.reduce(px))
    lo_y, hi_y = float(np.minimum.reduce(py)), float(np.maximum.reduce(py))
    spare = SPARE * (abs(x0) + abs(x1) + abs(y0) + abs(y1) + abs(lo_x) + abs(hi_x) + abs(lo_y)
                     + abs(hi_y) + abs(margin))
    # clear of one side of the bounds is enough (NaN: never clear; a side's NaN is left out)
    gaps = (x0 - margin - hi_x, lo_x - x1 - margin, y0 - margin - hi_y, lo_y - y1 - margin)
    return max((g for g in gaps if g == g), default=math.nan) - spare


__all__ = ["push_out", "clear_of", "SPARE"]
