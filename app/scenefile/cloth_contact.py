"""A scene file's cloth meets solids: its `[[cloth.obstacle]]`s and the bodies it is coupled with.

Obstacles (app/physics/obstacles.py) are handed to the cloth once, at build: the cloth's own
`collisions` pass projects every particle found inside one back to its surface after the
Verlet step and after the sweeps (Jakobsen), and its `friction` pass (only with friction > 0)
applies Coulomb's law there. A `body` obstacle is a static body of the file, each of its
circles, boxes and segments the same solid for the cloth as for the balls.

Coupling (app/physics/coupling.py) runs after the cloth's step, once per substep, for each
coupled body and each of its shapes: particles inside the shape (a Circle or a rotated Box at
the body's pose) are projected out by inverse masses, and the body takes the opposite impulse
(two-way), or nothing (one-way), as the trampoline scene does.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pymunk

from app.physics.coupling import Body, couple
from app.physics.obstacles import Box, Circle, Obstacle, Segment, floor, penetration_max


def obstacles_of(spec: dict, named: dict[str, pymunk.Body]) -> list[Obstacle]:
    """The cloth's obstacles, in the file's order (a body obstacle: each of its shapes)."""
    out: list[Obstacle] = []
    for ob in spec["obstacle"]:
        kind = ob["kind"]
        if kind == "circle":
            out.append(Circle(*ob["position"], ob["radius"]))
        elif kind == "box":
            out.append(Box(*ob["position"], ob["size"][0] / 2, ob["size"][1] / 2,
                           math.radians(ob["angle"])))
        elif kind == "segment":
            out.append(Segment(*ob["a"], *ob["b"], ob["thickness"]))
        elif kind == "floor":
            out.append(floor(ob["y"]))
        else:
            out += [shape_obstacle(s) for s in named[ob["body"]].shapes]
    return out


def shape_obstacle(shape: pymunk.Shape) -> Obstacle:
    """A pymunk circle, box (a 4-cornered Poly made by a file's box) or segment at its body's
    pose, as an obstacle."""
    body = shape.body
    if isinstance(shape, pymunk.Circle):
        c = body.local_to_world(shape.offset)
        return Circle(c.x, c.y, shape.radius)
    if isinstance(shape, pymunk.Segment):
        a, b = body.local_to_world(shape.a), body.local_to_world(shape.b)
        return Segment(a.x, a.y, b.x, b.y, shape.radius)
    pts = shape.get_vertices()             # a box: 4 corners round its centre, in body space
    cx, cy = sum(p.x for p in pts) / 4, sum(p.y for p in pts) / 4
    w = (pts[1] - pts[0]).length
    h = (pts[2] - pts[1]).length
    edge = pts[1] - pts[0]
    c = body.local_to_world((cx, cy))
    return Box(c.x, c.y, w / 2, h / 2, body.angle + math.atan2(edge.y, edge.x))


def couple_step(scene: Any, h: float) -> None:
    """One coupling substep between the file's cloth and its coupled bodies (module
    docstring); the impulse and the contacts are added to scene.track["coupling"]."""
    c, data = scene.cloth, scene.data["cloth"]
    points = c.x.reshape(2, -1).T                # a view: writing moves the cloth
    movable = (c.w > 0).ravel()
    mass = data["mass"] / (c.rows * c.cols)
    two_way = data["coupling"] == "two-way"
    tally = scene.track["coupling"]
    tally["contacts_last"] = 0                   # this substep's
    for name in scene.coupled:
        b = scene.named[name]
        for shape in b.shapes:
            center = b.local_to_world(b.center_of_gravity)
            ex = couple(points, movable, mass, Body(shape_obstacle(shape), b.mass, b.moment,
                                                    (center.x, center.y)), h)
            if not ex.contacts:
                continue
            tally["impulse"] += float(np.hypot(*ex.impulse))     # summed over the step
            tally["contacts_last"] += ex.contacts
            if not two_way:
                continue
            if not (np.isfinite(ex.dv).all() and math.isfinite(ex.dw)):
                raise FloatingPointError("the coupling produced a non-finite impulse")
            b.velocity = (b.velocity.x + ex.dv[0], b.velocity.y + ex.dv[1])
            b.angular_velocity += ex.dw
            b.angle += ex.turn                   # about the centre of gravity, then shifted
            moved = b.local_to_world(b.center_of_gravity)
            b.position = (b.position.x + center.x - moved.x + ex.shift[0],
                          b.position.y + center.y - moved.y + ex.shift[1])


def deepest(scene: Any) -> float:
    """penetration_max: the deepest movable particle inside an obstacle or a coupled body's
    shape, px (0 if none)."""
    c = scene.cloth
    solids = list(c.contact.obstacles) + [shape_obstacle(s) for n in scene.coupled
                                          for s in scene.named[n].shapes]
    if not solids:
        return 0.0
    return penetration_max(solids, c.x.reshape(2, -1).T, (c.w > 0).ravel())


def touching(scene: Any) -> int:
    """contacts: particles that touched an obstacle in the last substep plus those the last
    coupling pass found inside a coupled body."""
    st = scene.cloth.contact
    obstacles = int(st.touching.sum()) if st.touching is not None else 0
    return obstacles + scene.track["coupling"]["contacts_last"]
