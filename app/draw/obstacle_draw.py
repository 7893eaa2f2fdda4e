"""Drawing the obstacles of app/physics/obstacles.py: filled shapes with an outline, the one
under the mouse or being dragged outlined brighter."""

from __future__ import annotations

import numpy as np
import pygame

from app.draw.text import px
from app.physics.obstacles import Box, Circle, HalfPlane, Segment

FILL = (58, 64, 80)
EDGE = (140, 150, 175)
ACTIVE = (250, 210, 120)
FAR = 1e5           # px: how far a half-plane is drawn (the view clamps screen points)


def _outline(ob, view) -> list[tuple[float, float]] | None:
    """The screen polygon of a box or a half-plane (None for the round ones)."""
    if isinstance(ob, Box):
        return view.pts(ob.corners()).tolist()
    if isinstance(ob, HalfPlane):
        p = np.array([ob.px, ob.py])
        n = np.array([ob.nx, ob.ny])
        t = np.array([-n[1], n[0]])
        world = np.array([p - FAR * t, p + FAR * t, p + FAR * t - FAR * n, p - FAR * t - FAR * n])
        return view.pts(world).tolist()
    return None


def draw_obstacles(surface: pygame.Surface, view, obstacles, active: int | None = None) -> None:
    """Draw every obstacle; `active` (an index) is outlined in ACTIVE."""
    width = px(2)
    for k, ob in enumerate(obstacles):
        edge = ACTIVE if k == active else EDGE
        if isinstance(ob, Circle):
            c, r = view.pt(ob.center), max(1, int(round(view.len(ob.radius))))
            pygame.draw.circle(surface, FILL, c, r)
            pygame.draw.circle(surface, edge, c, r, width)
        elif isinstance(ob, Segment):
            a, b = view.pt((ob.ax, ob.ay)), view.pt((ob.bx, ob.by))
            r = max(1, int(round(view.len(ob.thickness))))
            pygame.draw.line(surface, edge, a, b, 2 * r)
            pygame.draw.circle(surface, edge, a, r)
            pygame.draw.circle(surface, edge, b, r)
        else:
            poly = _outline(ob, view)
            pygame.draw.polygon(surface, FILL, poly)
            pygame.draw.polygon(surface, edge, poly, width)
