"""Right: each rod's PinJoint with its bodies the other way round (bob first), the bobs' masses
given to their shapes, and the two bobs kept apart by a sensor-free category mask."""
import math

import pymunk


def build_double_pendulum(space, anchor, lengths, masses, angles):
    (l1, l2), (m1, m2), (t1, t2) = lengths, masses, angles
    p1 = (anchor[0] + l1 * math.sin(t1), anchor[1] + l1 * math.cos(t1))
    p2 = (p1[0] + l2 * math.sin(t2), p1[1] + l2 * math.cos(t2))
    bobs = []
    for p, m in ((p1, m1), (p2, m2)):
        body = pymunk.Body()
        body.position = p
        shape = pymunk.Circle(body, 14)
        shape.mass = m
        shape.filter = pymunk.ShapeFilter(categories=0b10,
                                          mask=pymunk.ShapeFilter.ALL_MASKS() ^ 0b10)
        space.add(body, shape)
        bobs.append(body)
    rod1 = pymunk.PinJoint(bobs[0], space.static_body, (0, 0), anchor)
    rod2 = pymunk.PinJoint(bobs[1], bobs[0], (0, 0), (0, 0))
    for rod in (rod1, rod2):
        rod.error_bias = 0.0
    space.add(rod1, rod2)
    return bobs[0], bobs[1]
