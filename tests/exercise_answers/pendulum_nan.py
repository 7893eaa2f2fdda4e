"""Wrong (fails 'energy kept': NaN never passes): the second bob's mass is given as 0 * inf, so
pymunk's state turns NaN; the energy drift NaN once passed as 'largest energy drift 0.000%'."""
import math

import pymunk


def build_double_pendulum(space, anchor, lengths, masses, angles):
    (ax, ay), (l1, l2), (m1, m2), (t1, t2) = anchor, lengths, masses, angles
    p1 = (ax + l1 * math.sin(t1), ay + l1 * math.cos(t1))
    p2 = (p1[0] + l2 * math.sin(t2), p1[1] + l2 * math.cos(t2))
    bodies = []
    for m, p in ((m1, p1), (m2, p2)):
        body = pymunk.Body(m, pymunk.moment_for_circle(m, 0, 14))
        body.position = p
        shape = pymunk.Circle(body, 14)
        shape.filter = pymunk.ShapeFilter(group=1)
        space.add(body, shape)
        bodies.append(body)
    bodies[1].velocity = (0.0 * math.inf, 0.0)
    for a, b, pa in ((space.static_body, bodies[0], anchor), (bodies[0], bodies[1], (0, 0))):
        joint = pymunk.PinJoint(a, b, pa, (0, 0))
        joint.error_bias = 0.0
        space.add(joint)
    return bodies[0], bodies[1]
