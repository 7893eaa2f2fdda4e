"""Wrong (fails 'energy kept'): pymunk's default (soft) PinJoints, which bleed energy."""
import math

import pymunk


def build_double_pendulum(space, anchor, lengths, masses, angles):
    (l1, l2), (t1, t2) = lengths, angles
    p1 = (anchor[0] + l1 * math.sin(t1), anchor[1] + l1 * math.cos(t1))
    p2 = (p1[0] + l2 * math.sin(t2), p1[1] + l2 * math.cos(t2))
    bodies = []
    for m, p in zip(masses, (p1, p2)):
        body = pymunk.Body(m, pymunk.moment_for_circle(m, 0, 14))
        body.position = p
        shape = pymunk.Circle(body, 14)
        shape.filter = pymunk.ShapeFilter(group=1)
        space.add(body, shape)
        bodies.append(body)
    space.add(pymunk.PinJoint(space.static_body, bodies[0], anchor, (0, 0)),
              pymunk.PinJoint(bodies[0], bodies[1], (0, 0), (0, 0)))
    return bodies[0], bodies[1]
