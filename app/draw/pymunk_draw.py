"""The project's own drawing of pymunk worlds: fast, readable, and through `view` only.

`space.debug_draw` (pymunk.pygame_util.DrawOptions) is handy but slow for a classroom: it calls back
into Python once per shape, builds Vec2d and colour objects for each call, and draws every contact
point. Here
  * many equal circles (balls) are drawn from ONE batch of positions and angles (pymunk.batch): a
    ball is a pre-rendered sprite (anti-aliased disc with its rotation tick, one sprite per angle
    step), and all sprites go to the screen in a single `Surface.fblits` call;
  * the few other shapes (segments with their thickness and round caps, polygons, single circles)
    and the joints (pin joint: the rod and its anchor dots; slide joint: the rod plus its min..max
    range; the mouse's pivot joint) are drawn one by one;
  * sleeping bodies are drawn dimmer (`dim`).

Every function takes the target surface and the `View` (app/draw/view.py) that maps world to screen.

    draw_circles(surface, view, xy, angles, radius, BALL)           # many balls at once
    draw_circles(surface, view, xy, angles, radius, BALL, asleep)   # sleeping ones dimmer
    draw_shape(surface, view, shape, color)                          # one segment, poly or circle
    draw_pin_joint(surface, view, joint)                             # a rod and its anchors
"""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np
import pygame
import pymunk

from app.draw.text import px

Color = tuple[int, int, int]

BALL: Color = (86, 180, 233)
STATIC: Color = (200, 200, 210)
DYNAMIC: Color = (240, 200, 70)
PIN: Color = (235, 235, 235)
SLIDE: Color = (120, 220, 120)
OUTLINE: Color = (10, 12, 16)     # around what must stand out among bodies (the slide joint)
SLIDE_LIMIT: Color = (230, 97, 76)
MOUSE: Color = (255, 120, 200)
TICK: Color = (20, 22, 28)

ANGLE_STEPS = 48          # rotation ticks are drawn to the nearest 7.5 degrees
_MAX_SPRITES = 4096       # the sprite cache is cleared when it grows past this


def dim(color: Color, factor: float = 0.45) -> Color:
    """The colour of a sleeping body: the same hue, darker."""
    return (int(color[0] * factor), int(color[1] * factor), int(color[2] * factor))


# ----- many circles at once ---------------------------------------------------------------------
_sprites: dict[tuple[int, Color, int], pygame.Surface] = {}


def _circle_sprite(r2: int, color: Color, step: int) -> pygame.Surface:
    """A disc of radius r2/2 screen pixels with a tick from the centre to the rim at angle
    step * 360/ANGLE_STEPS degrees (y down, like the world), cached."""
    key = (r2, color, step)
    sprite = _sprites.get(key)
    if sprite is None:
        if len(_sprites) > _MAX_SPRITES:
            _sprites.clear()
        r = r2 / 2
        size = int(math.ceil(2 * r)) + 2
        c = size / 2
        sprite = pygame.Surface((size, size), pygame.SRCALPHA)
        pygame.draw.aacircle(sprite, color, (c, c), r)
        pygame.draw.circle(sprite, color, (c, c), max(r - 0.5, 0.5))
        if r >= 3:
            a = step * 2 * math.pi / ANGLE_STEPS
            tip = (c + (r - 1) * math.cos(a), c + (r - 1) * math.sin(a))
            pygame.draw.line(sprite, TICK, (c, c), tip, 2 if r > 12 else 1)
        _sprites[key] = sprite
    return sprite


def draw_circles(surface: pygame.Surface, view, xy: np.ndarray, angles: np.ndarray | None,
                 radius: float, color: Color = BALL, asleep: np.ndarray | None = None) -> None:
    """Draw n circles of one radius: centres xy (n, 2) in world units, body angles (n,) for the
    rotation tick (None: no tick needed, all drawn at angle 0), and an optional bool mask (n,) of
    sleeping bodies, drawn dimmer. One sprite blit per circle, all in one fblits call."""
    n = len(xy)
    if n == 0:
        return
    r2 = max(2, int(round(2 * view.len(radius))))
    size = _circle_sprite(r2, color, 0).get_width()
    corner = np.floor(view.pts(xy) - size / 2 + 0.5).astype(np.int64).tolist()
    if angles is None:
        steps = np.zeros(n, dtype=np.int64)
    else:
        # the angle as a whole number of ticks, 0..ANGLE_STEPS-1 (for each: round(a / step) % N);
        # a non-finite angle (a blown-up body) is drawn at tick 0, not cast to garbage
        with np.errstate(invalid="ignore"):
            turns = np.nan_to_num(np.remainder(np.asarray(angles, dtype=float), 2 * math.pi))
        steps = np.rint(turns * (ANGLE_STEPS / (2 * math.pi))).astype(np.int64)
        steps %= ANGLE_STEPS
    awake = [_circle_sprite(r2, color, k) for k in range(ANGLE_STEPS)]
    if asleep is None or not asleep.any():
        sprites = [awake[k] for k in steps.tolist()]
    else:
        sleepy = [_circle_sprite(r2, dim(color), k) for k in range(ANGLE_STEPS)]
        table = awake + sleepy
        # index into [awake sprites..., sleeping sprites...]: step + N for a sleeping body
        sprites = [table[k] for k in (steps + ANGLE_STEPS * asleep).tolist()]
    surface.fblits(zip(sprites, corner))


# ----- single shapes ----------------------------------------------------------------------------
def draw_segment(surface: pygame.Surface, view, a, b, radius: float, color: Color) -> None:
    """A segment from world point a to b with thickness 2*radius and round caps."""
    pa, pb = view.pt(a), view.pt(b)
    r = view.len(radius)
    if r < 1:
        pygame.draw.aaline(surface, color, pa, pb)
        return
    dx, dy = pb[0] - pa[0], pb[1] - pa[1]
    length = math.hypot(dx, dy)
    if length > 0:
        nx, ny = -dy / length * r, dx / length * r      # the side offset, r pixels long
        pygame.draw.polygon(surface, color, [(pa[0] + nx, pa[1] + ny), (pb[0] + nx, pb[1] + ny),
                                             (pb[0] - nx, pb[1] - ny), (pa[0] - nx, pa[1] - ny)])
    pygame.draw.circle(surface, color, pa, r)
    pygame.draw.circle(surface, color, pb, r)


def draw_circle(surface: pygame.Surface, view, center, angle: float, radius: float,
                color: Color) -> None:
    """One circle with its rotation tick (for the few big ones: a pendulum bob, a cradle ball)."""
    c = view.pt(center)
    r = view.len(radius)
    pygame.draw.circle(surface, color, c, max(r, 1))
    pygame.draw.aacircle(surface, color, c, max(r, 1))
    if r >= 3 and math.isfinite(angle):
        tip = view.pt((center[0] + radius * math.cos(angle), center[1] + radius * math.sin(angle)))
        pygame.draw.line(surface, TICK, c, tip, 2 if r > 12 else 1)


def draw_poly(surface: pygame.Surface, view, points: Sequence, color: Color) -> None:
    """A filled polygon through world points."""
    pygame.draw.polygon(surface, color, [view.pt(p) for p in points])
    pygame.draw.aalines(surface, color, True, [view.pt(p) for p in points])


def draw_shape(surface: pygame.Surface, view, shape: pymunk.Shape, color: Color) -> None:
    """Draw one pymunk shape (Segment, Circle or Poly) where its body is now."""
    body = shape.body
    if isinstance(shape, pymunk.Segment):
        draw_segment(surface, view, body.local_to_world(shape.a), body.local_to_world(shape.b),
                     shape.radius, color)
    elif isinstance(shape, pymunk.Circle):
        draw_circle(surface, view, body.local_to_world(shape.offset), body.angle, shape.radius,
                    color)
    elif isinstance(shape, pymunk.Poly):
        draw_poly(surface, view, [body.local_to_world(v) for v in shape.get_vertices()], color)


def draw_shapes(surface: pygame.Surface, view, shapes: Iterable[pymunk.Shape], color: Color,
                sleeping_dim: bool = True) -> None:
    """Draw a few shapes in one colour (dimmer where the body sleeps)."""
    for shape in shapes:
        asleep = sleeping_dim and shape.body.body_type == pymunk.Body.DYNAMIC \
            and shape.body.is_sleeping
        draw_shape(surface, view, shape, dim(color) if asleep else color)


_AA_WIDTH = "width" in (pygame.draw.aaline.__doc__ or "")   # aaline(..., width) exists


def rod(surface: pygame.Surface, color: Color, pa, pb, width: int) -> None:
    """A straight line `width` screen pixels thick, anti-aliased: pygame-ce's thick aaline where
    it has one (2.5.8 has), else a filled quad with anti-aliased long edges (pygame's thick
    lines, and a filled polygon's edges alone, show stair-steps on a slanting string)."""
    dx, dy = pb[0] - pa[0], pb[1] - pa[1]
    length = math.hypot(dx, dy)
    if width <= 1 or length == 0:
        pygame.draw.aaline(surface, color, pa, pb)
        return
    if _AA_WIDTH:
        pygame.draw.aaline(surface, color, pa, pb, width + 1)   # (its edges fade: +1 px keeps
        return                                                   # the weight of a solid line)
    nx, ny = -dy / length * (width - 1) / 2, dx / length * (width - 1) / 2
    quad = [(pa[0] + nx, pa[1] + ny), (pb[0] + nx, pb[1] + ny), (pb[0] - nx, pb[1] - ny),
            (pa[0] - nx, pa[1] - ny)]
    pygame.draw.polygon(surface, color, quad)
    pygame.draw.aaline(surface, color, quad[0], quad[1])
    pygame.draw.aaline(surface, color, quad[2], quad[3])


# ----- joints -----------------------------------------------------------------------------------
def length(v: pymunk.Vec2d) -> float:
    """|v| by math.hypot: Vec2d.length squares with **, which raises OverflowError past ~1e154
    (a blown-up body's measure is then huge or inf, reported, not a crash)."""
    return math.hypot(v.x, v.y)


def anchors(joint: pymunk.Constraint) -> tuple[pymunk.Vec2d, pymunk.Vec2d]:
    """The joint's two anchor points in world coordinates (their distance is what a pin or
    slide joint holds)."""
    return joint.a.local_to_world(joint.anchor_a), joint.b.local_to_world(joint.anchor_b)


def _dot(surface: pygame.Surface, view, p, color: Color, r: float = 4) -> None:
    c = view.pt(p)
    pygame.draw.circle(surface, color, c, max(2.0, view.len(r)))


def draw_pin_joint(surface: pygame.Surface, view, joint: pymunk.PinJoint,
                   color: Color = PIN, dot: float = 6) -> None:
    """The pin joint's rod between its two anchors, with a dot on each anchor (one dot when the
    anchors coincide, as for a pin at a rotation centre); `dot`: radius of anchor a's dot."""
    a, b = anchors(joint)
    rod(surface, color, view.pt(a), view.pt(b), px(3))     # 3 px: readable from the back row
    _dot(surface, view, a, color, dot)
    _dot(surface, view, b, color, 3)


def draw_slide_joint(surface: pygame.Surface, view, joint: pymunk.SlideJoint,
                     color: Color = SLIDE, limit_color: Color = SLIDE_LIMIT) -> None:
    """The slide joint: a thin line between the anchors, and from anchor b a thick band along
    that line from distance `min` to distance `max`: the range the joint allows. The anchor dot
    on body a turns red when the joint sits at a limit. Everything has a dark outline: the
    joint sits among the balls that land on the L (a plain green line between blue balls was
    lost among them)."""
    a, b = anchors(joint)
    d = length(a - b)
    u = (a - b) / d if d > 1e-9 else pymunk.Vec2d(1, 0)
    lo, hi = b + u * joint.min, b + u * joint.max
    band = max(px(5), int(view.len(7)))
    n = pymunk.Vec2d(-u.y, u.x) * 9            # the range's end marks, across the line
    edge = px(2)
    rod(surface, OUTLINE, view.pt(b), view.pt(a), px(2) + 2 * edge)
    pygame.draw.line(surface, OUTLINE, view.pt(lo), view.pt(hi), band + 2 * edge)
    for end in (lo, hi):
        pygame.draw.line(surface, OUTLINE, view.pt(end - n), view.pt(end + n), px(3) + 2 * edge)
    rod(surface, color, view.pt(b), view.pt(a), px(2))
    pygame.draw.line(surface, color, view.pt(lo), view.pt(hi), band)
    for end in (lo, hi):
        pygame.draw.line(surface, color, view.pt(end - n), view.pt(end + n), px(3))
    at_limit = d <= joint.min + 0.5 or d >= joint.max - 0.5
    _dot(surface, view, a, OUTLINE, 8)
    _dot(surface, view, a, limit_color if at_limit else color, 6)
    _dot(surface, view, b, color, 4)


def draw_pivot_joint(surface: pygame.Surface, view, joint: pymunk.PivotJoint,
                     color: Color = MOUSE) -> None:
    """A pivot joint: both anchors (they drift apart while the mouse pulls hard)."""
    a, b = anchors(joint)
    pygame.draw.aaline(surface, color, view.pt(a), view.pt(b))
    _dot(surface, view, a, color, 3)
    _dot(surface, view, b, color, 3)


__all__ = ["draw_circles", "draw_circle", "draw_segment", "draw_poly", "draw_shape",
           "draw_shapes", "draw_pin_joint", "draw_slide_joint", "draw_pivot_joint", "anchors",
           "dim", "BALL", "STATIC", "DYNAMIC", "PIN", "SLIDE", "SLIDE_LIMIT", "MOUSE", "TICK",
           "ANGLE_STEPS"]
