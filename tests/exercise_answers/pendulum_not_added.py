"""Wrong (fails 'built as asked'): bobs and rods made but never added to the space, so nothing
moves (and the energy and joint checks alone would pass a pendulum that hangs still)."""
import math

import pymunk


def build_double_pendulum(space, anchor, lengths, masses, angles):
    (l1, l2), (m1, m2), (t1, t2) = lengths, masses, angles
    p1 = (anchor[0] + l1 * math.sin(t1), anchor[1] + l1 * math.cos(t1))
    p2 = (p1[0] + l2 * math.sin(t2), p1[1] + l2 * math.cos(t2))
    bodies = []
    for m, p in ((m1, p1), (m2, p2)):
        body = pymunk.Body(m, pymunk.moment_for_circle(m, 0, 14))
        body.position = p
        bodies.append(body)
    rod1 = pymunk.PinJoint(space.static_body, bodies[0], anchor, (0, 0))
    rod2 = pymunk.PinJoint(bodies[0], bodies[1], (0, 0), (0, 0))
    rod1.error_bias = rod2.error_bias = 0.0
    return bodies[0], bodies[1]
