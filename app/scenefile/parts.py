"""pymunk pieces from a scene file's checked data, and what the metrics read from them: shapes
and their areas (a body's mass is spread over its shapes by area), a joint's distance, error
and impulse, a body's position, angle, speed and turn.
"""

from __future__ import annotations

import math

import pymunk

from app.draw.pymunk_draw import anchors, length


def joint_measure(kind: str, c: pymunk.Constraint) -> float:
    if kind == "joint_impulse":
        return float(c.impulse)
    a, b = anchors(c) if hasattr(c, "anchor_a") else (c.a.position, c.b.position)
    d = length(a - b)
    if kind == "joint_distance":
        return d
    if isinstance(c, pymunk.PinJoint):
        return abs(d - c.distance)
    if isinstance(c, pymunk.PivotJoint):
        return d
    if isinstance(c, pymunk.SlideJoint):
        return max(0.0, c.min - d, d - c.max)
    if isinstance(c, pymunk.GrooveJoint):
        ga, gb = c.a.local_to_world(c.groove_a), c.a.local_to_world(c.groove_b)
        p = c.b.local_to_world(c.anchor_b)
        u = gb - ga
        t = min(1.0, max(0.0, (p - ga).dot(u) / u.dot(u)))
        return length(p - (ga + u * t))
    return 0.0


def body_measure(kind: str, b: pymunk.Body) -> float:
    if kind == "x":
        return float(b.local_to_world(b.center_of_gravity).x)
    if kind == "y":
        return float(b.local_to_world(b.center_of_gravity).y)
    if kind == "angle":
        return math.degrees(b.angle)
    if kind == "speed":
        return length(b.velocity)
    return math.degrees(b.angular_velocity)


def shape_area(s: dict) -> float:
    if s["kind"] == "circle":
        return math.pi * s["radius"] ** 2
    if s["kind"] == "box":
        return s["size"][0] * s["size"][1]
    if s["kind"] == "polygon":
        return pymunk.area_for_poly([tuple(p) for p in s["points"]], s["radius"])
    return pymunk.area_for_segment(tuple(s["a"]), tuple(s["b"]), s["radius"])


def area_of(shapes: list[dict]) -> float:
    return sum(shape_area(s) for s in shapes)


def make_shape(body: pymunk.Body, s: dict) -> pymunk.Shape:
    kind = s["kind"]
    if kind == "circle":
        shape = pymunk.Circle(body, s["radius"], tuple(s["offset"]))
    elif kind == "box":
        w, h = s["size"]
        ox, oy = s["offset"]
        pts = [(ox - w / 2, oy - h / 2), (ox + w / 2, oy - h / 2), (ox + w / 2, oy + h / 2),
               (ox - w / 2, oy + h / 2)]
        shape = pymunk.Poly(body, pts, radius=s["radius"])
    elif kind == "polygon":
        shape = pymunk.Poly(body, [tuple(p) for p in s["points"]], radius=s["radius"])
    else:
        shape = pymunk.Segment(body, tuple(s["a"]), tuple(s["b"]), s["radius"])
    shape.friction = s["friction"]
    shape.elasticity = s["elasticity"]
    if s["group"]:
        shape.filter = pymunk.ShapeFilter(group=s["group"])
    return shape
