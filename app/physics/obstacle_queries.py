"""Questions about several obstacles at once (app/physics/obstacles.py defines the shapes and
re-exports these): the nearest surface to each point, the obstacle a mouse press picks, and the
deepest point inside any of them. Each asks the shapes' own signed_distance, nothing else."""

from __future__ import annotations

import numpy as np


def nearest(obstacles, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(d, normal, index): for each point, the smallest signed distance over all obstacles (the
    nearest surface outside, the deepest obstacle inside), its outward normal (n, 2) and the
    obstacle's index in `obstacles` (-1, d = +inf, normal 0 if there are none)."""
    n = len(points)
    best = np.full(n, np.inf)
    normal = np.zeros((n, 2))
    index = np.full(n, -1)
    for k, ob in enumerate(obstacles):
        d, nrm = ob.signed_distance(points)
        closer = d < best
        best = np.where(closer, d, best)
        normal[closer] = nrm[closer]
        index[closer] = k
    return best, normal, index


PICK_THIN = 5.0          # px: a press this close to a thin rod picks it (the mouse's slack)


def obstacle_at(obstacles, pos: tuple[float, float], thin: float = PICK_THIN) -> int | None:
    """The index of the obstacle a mouse press at `pos` picks: the first it is inside (a thin
    rod, a Segment: within `thin` px of it), or None. Both cloths' scenes drag obstacles by it."""
    point = np.array([pos], float)
    for k, ob in enumerate(obstacles):
        slack = thin if ob.kind == "segment" else 0.0
        if ob.signed_distance(point)[0][0] < slack:
            return k
    return None


def penetration_max(obstacles, points: np.ndarray, mask: np.ndarray | None = None) -> float:
    """How deep the deepest point (among `mask`, if given) lies inside any obstacle, px; 0.0 if
    none is inside."""
    if len(obstacles) == 0 or len(points) == 0:
        return 0.0
    d = nearest(obstacles, points)[0]
    if mask is not None:
        d = d[np.asarray(mask, bool)]
    return float(max(0.0, -d.min())) if d.size else 0.0
