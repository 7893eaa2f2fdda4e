"""The usual mistakes of the `collisions` exercise, for the hints of its grader
(app/exercises/collisions/grader.py): each is computed here, in the parent, on the check's own
inputs, and a hint names a mistake only when what the student's code produced IS that mistake's
result (within 1e-6 px) and not the right one. A result that matches none gets a hint that says
what was measured (which particle, where it is, where it belongs).
"""

from __future__ import annotations

import numpy as np

MATCH = 1e-6            # px: a result "is" a mistake's when every coordinate is this close


def _normals(x, c, top=(0.0, -1.0)):
    """d = |x - c| and n = (x - c) / d, n = `top` where d = 0 (None: NaN there)."""
    off = x - c
    d = np.hypot(off[:, 0], off[:, 1])
    with np.errstate(all="ignore"):
        n = off / d[:, None]
    if top is not None:
        n[d == 0] = top
    return d, n


def push_with(kind: str, x, w, c, r):
    """(x', depth) of push_out with one mistake ('right': none)."""
    x = np.array(x, dtype=float)
    c = np.asarray(c, dtype=float)
    top = {"centre NaN": None, "centre kept": (0.0, 0.0), "centre down": (0.0, 1.0)}.get(
        kind, (0.0, -1.0))
    r_used = 100.0 if kind == "radius 100" else r
    d, n = _normals(x, c, top)
    inside = d < r_used
    if kind != "pins ignored":
        inside &= (np.asarray(w) == 1) if kind == "w is 1" else (np.asarray(w) > 0)
    if kind == "only first":                  # the first particle that is inside and free
        inside[np.flatnonzero(inside)[1:]] = False
    if kind == "outside too":
        inside = np.asarray(w) > 0
    depth = np.where(inside, r_used - d, 0.0)
    with np.errstate(all="ignore"):
        if kind == "to depth":
            x[inside] = c + depth[inside, None] * n[inside]
        elif kind != "new array":
            factor = {"half": 0.5, "twice": 2.0, "inward": -1.0}.get(kind, 1.0)
            x[inside] += factor * depth[inside, None] * n[inside]
    return x, depth


PUSH_HINTS = {
    "half": "the particles moved HALF the way out: (r - d) n, not (r - d) n / 2.",
    "twice": "the particles moved twice as far as the surface: x + (r - d) n, not 2 (r - d) n.",
    "inward": "the particles moved deeper IN: the shortest way out is +n = (x - c) / d, "
              "outward; x + (r - d) n.",
    "to depth": "the particles ended (r - d) px from the centre, not on the surface: "
                "x + (r - d) n (or c + r n), not c + (r - d) n.",
    "only first": "only the first particle inside was moved: every particle inside must be "
                  "(a boolean mask, x[inside] += ..., or a loop that does not stop early).",
    "new array": "x is unchanged: your push_out made a new array (x = x + ...) instead of "
                 "changing the caller's x in place (x[inside] += ..., x[...] = ...).",
    "outside too": "particles OUTSIDE the circle were pulled onto its surface: move only those "
                   "with d < r (inside).",
    "w is 1": "a particle with w = 0.5 was not moved: w is the inverse mass, and every w > 0 is "
              "free (only w = 0 is pinned): inside = (d < r) & (w > 0).",
    "pins ignored": "a pinned particle (w = 0) was moved: leave every particle with w = 0 where "
                    "it is (inside = (d < r) & (w > 0)).",
    "centre NaN": "the particle at the centre became NaN: there d = |x - c| = 0 and (x - c) / d "
                  "is 0 / 0. Give it the direction (0, -1) (out through the top).",
    "centre kept": "the particle at the centre stayed there: a guard like max(d, 1e-9) makes its "
                   "direction (0, 0). Give it (0, -1): out through the top.",
    "centre down": "the particle at the centre left through the BOTTOM: y points down, so out "
                   "through the top is n = (0, -1).",
    "radius 100": "the particles were pushed to a circle of radius 100 px whatever the radius: "
                  "use the `radius` argument (the first cases' circle has r = 100).",
}


def push_hint(x, depth, x0, w, c, r, kinds) -> str:
    """The hint of the first mistake of `kinds` whose result x is (and the right one is not);
    'new array' also needs the right depth (the push was computed, then lost)."""
    right, want = push_with("right", x0, w, c, r)
    for kind in kinds:
        if kind == "new array" and not np.allclose(depth, want, rtol=0, atol=MATCH):
            continue
        theirs = push_with(kind, x0, w, c, r)[0]
        if np.allclose(theirs, right, rtol=0, atol=MATCH, equal_nan=True):
            continue                    # this case cannot tell that mistake from the answer
        if np.allclose(x, theirs, rtol=0, atol=MATCH, equal_nan=True):
            return PUSH_HINTS[kind]
    return ""


def depth_hint(depth, moved, want) -> str:
    """What is wrong with a depth whose x was right."""
    if np.allclose(depth, -want, atol=MATCH):
        return "depth is negative: return r - d (how far each particle was moved), not d - r."
    if not np.any(depth) and np.any(want):
        return "depth is 0 everywhere: return how far each particle was moved, r - d."
    return ("depth must be how far each particle was moved (r - d where it was pushed, 0 "
            f"elsewhere); you returned {np.round(depth, 3).tolist()} for moves of "
            f"{np.round(moved, 3).tolist()} px.")


def friction_with(kind: str, x, x_prev, c, depth, mu):
    """x' of friction with one mistake ('right': none)."""
    x = np.array(x, dtype=float)
    depth = np.asarray(depth, dtype=float)
    mu = min(mu, 1.0) if kind == "mu capped" else mu
    _, n = _normals(x, np.asarray(c, dtype=float))
    v = x if kind == "position" else x - x_prev
    along = (v * n).sum(axis=1, keepdims=True)
    vt = v if kind == "whole travel" else v - along * n
    speed = np.hypot(vt[:, 0], vt[:, 1])
    cap = mu * depth
    with np.errstate(all="ignore"):
        unit = np.where(speed[:, None] > 0, vt / np.where(speed > 0, speed, 1.0)[:, None], 0.0)
        if kind == "reverses":
            change = cap[:, None] * unit
        elif kind == "fraction":
            change = mu * vt
        elif kind == "never slides":
            change = np.where((speed <= cap)[:, None], vt, 0.0)
        else:
            change = np.where((speed <= cap)[:, None], vt, cap[:, None] * unit)
    touching = depth > (1e-3 if kind == "skips shallow" else 0.0)
    if kind == "drag everywhere":
        x -= mu * vt
    elif kind not in ("new array", "x_prev moved"):
        x[touching] -= change[touching]
    return x


FRICTION_HINTS = {
    "reverses": "the slide REVERSED: where |v_t| <= mu * depth friction removes v_t itself "
                "(the particle sticks), never more; mu * depth * v_t / |v_t| only where "
                "|v_t| > mu * depth.",
    "position": "friction was computed from the position x, not from the travel v = x - x_prev "
                "(Verlet's velocity times h).",
    "whole travel": "friction took travel along the NORMAL too (the particle left the surface): "
                    "take only v_t = v - (v . n) n, the part along the surface.",
    "drag everywhere": "particles that did not touch the circle (depth 0) were slowed: friction "
                       "acts only where depth > 0, and removes at most mu * depth.",
    "fraction": "the slide lost mu |v_t| (a fraction of it), not min(|v_t|, mu * depth): "
                "Coulomb's friction removes a fixed amount, mu times the normal push (depth), "
                "or all of a slide shorter than that.",
    "never slides": "a fast slide (|v_t| > mu * depth) was not slowed at all: there friction "
                    "removes mu * depth of it (x -= mu * depth * v_t / |v_t|).",
    "new array": "x is unchanged: your friction made a new array (x = x - ...) instead of "
                 "changing the caller's x in place (x[touching] -= ...).",
    "x_prev moved": "x is unchanged and x_prev was changed: friction moves x back along the "
                    "surface (the next Verlet step reads x - x_prev); x_prev stays.",
    "mu capped": "the result is the right one for mu capped at 1: a Coulomb coefficient can be "
                 "above 1 (rubber on rubber), use mu as given.",
    "skips shallow": "a particle that touched only a little (depth 1e-4 px) was left sliding: "
                     "friction acts wherever depth > 0, however small (a cloth resting on a "
                     "surface at 1000 Hz is pushed out only g h^2 = 0.001 px a step).",
}


def friction_hint(x, x0, x_prev, c, depth, mu, kinds, x_prev_after=None, returned=None) -> str:
    right = friction_with("right", x0, x_prev, c, depth, mu)
    if returned is not None and np.allclose(returned, right, atol=MATCH) and \
            np.array_equal(x, x0) and not np.array_equal(x0, right):
        return FRICTION_HINTS["new array"]
    if x_prev_after is not None and not np.array_equal(x_prev_after, x_prev) and \
            np.array_equal(x, x0):
        return FRICTION_HINTS["x_prev moved"]
    for kind in kinds:
        if kind == "drag everywhere" and np.all(depth > 0):
            continue                    # nothing here that does not touch: it is 'fraction'
        theirs = friction_with(kind, x0, x_prev, c, depth, mu)
        if np.allclose(theirs, right, rtol=0, atol=MATCH, equal_nan=True):
            continue
        if np.allclose(x, theirs, rtol=0, atol=MATCH, equal_nan=True):
            return FRICTION_HINTS[kind]
    return ""


__all__ = ["push_with", "push_hint", "depth_hint", "friction_with", "friction_hint",
           "PUSH_HINTS", "FRICTION_HINTS"]
