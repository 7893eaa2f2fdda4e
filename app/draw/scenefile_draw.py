"""Drawing a scene file's joints: pins, slide joints and pivots as the lecture scenes draw them
(app/draw/pymunk_draw.py), a damped spring as a zigzag, a groove as its line, a motor or a
rotary joint as a ring on its second body.
"""

from __future__ import annotations

import numpy as np
import pygame
import pymunk

from app.draw import pymunk_draw as D

SPRING_COLOR = (150, 210, 255)
MOTOR_COLOR = (255, 160, 90)


def draw_joint(surface: pygame.Surface, view, kind: str, c: pymunk.Constraint) -> None:
    if kind == "pin":
        D.draw_pin_joint(surface, view, c, dot=3)
    elif kind == "slide":
        D.draw_slide_joint(surface, view, c)
    elif kind == "pivot":
        D.draw_pivot_joint(surface, view, c, D.PIN)
    elif kind == "damped_spring":
        draw_spring(surface, view, *D.anchors(c))
    elif kind == "groove":
        ga, gb = c.a.local_to_world(c.groove_a), c.a.local_to_world(c.groove_b)
        pygame.draw.line(surface, D.SLIDE, view.pt(ga), view.pt(gb), 3)
    elif kind in ("motor", "damped_rotary_spring", "rotary_limit"):
        color = MOTOR_COLOR if kind == "motor" else SPRING_COLOR
        centre = view.pt(c.b.local_to_world(c.b.center_of_gravity))
        pygame.draw.circle(surface, color, centre, max(3.0, view.len(6)), 2)


def draw_spring(surface: pygame.Surface, view, a, b, coils: int = 8) -> None:
    """A zigzag from a to b (its width does not change with the length)."""
    pa, pb = np.array(view.pt(a), float), np.array(view.pt(b), float)
    d = pb - pa
    n = float(np.hypot(*d))
    if n < 1e-6:
        return
    normal = np.array([-d[1], d[0]]) / n * max(4.0, view.len(6))
    t = np.linspace(0, 1, 2 * coils + 1)
    side = np.zeros(len(t))
    side[1:-1:2], side[2:-1:2] = 1, -1
    pts = pa + t[:, None] * d + side[:, None] * normal
    pygame.draw.lines(surface, SPRING_COLOR, False, pts.tolist(), 2)
