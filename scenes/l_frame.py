"""The L's frame (falling_balls, pivoting_l): its pose read from Chipmunk, and a point's
coordinates in it (ball_checks.py's tunneling test: is a centre within the arm's extent?)."""

from __future__ import annotations

import math

import numpy as np
import pymunk

from app.pymunk_reader import _lib


def body_pose(body: pymunk.Body) -> tuple[float, float, float]:
    """(x, y, angle) of a body, with Chipmunk's own getters (what Body.position and Body.angle
    call, without making a Vec2d: 0.28 us, not 0.83)."""
    if _lib is None:
        x, y = body.position
        return (x, y, body.angle)
    p = _lib.cpBodyGetPosition(body._body)
    return (p.x, p.y, _lib.cpBodyGetAngle(body._body))


def local_x(p: list[float], pose: tuple[float, float, float]) -> float:
    """to_local's x for one point, in plain Python."""
    x, y, a = pose
    c, s = cos_sin(a)
    return c * (p[0] - x) + s * (p[1] - y)


def to_local(xy: np.ndarray, pose: tuple[float, float, float]) -> np.ndarray:
    """World points (n, 2) -> the frame of a body at pose (x, y, angle): rotate by -angle."""
    x, y, a = pose
    c, s = cos_sin(a)
    # (x', y') = (c dx + s dy, -s dx + c dy) for every row at once: one 2x2 product
    return (xy - (x, y)) @ np.array(((c, -s), (s, c)))


def cos_sin(a: float) -> tuple[float, float]:
    """(cos a, sin a); NaN for an infinite angle (math raises): the runner reports the L."""
    try:
        return math.cos(a), math.sin(a)
    except ValueError:
        return math.nan, math.nan
