"""Right: bobs of infinite moment (they cannot spin; the rods hold their centres), built in one
loop. Its energy once read NaN (inf x 0 spin)."""
import math

import pymunk


def build_double_pendulum(space, anchor, lengths, masses, angles):
    bodies, last = [], anchor
    for length, mass, angle in zip(lengths, masses, angles):
        p = (last[0] + length * math.sin(angle), last[1] + length * math.cos(angle))
        body = pymunk.Body(mass, math.inf)
        body.position = p
        shape = pymunk.Circle(body, 14)
        shape.filter = pymunk.ShapeFilter(group=1)
        if bodies:
            rod = pymunk.PinJoint(bodies[-1], body, (0, 0), (0, 0))
        else:
            rod = pymunk.PinJoint(space.static_body, body, anchor, (0, 0))
        rod.error_bias = 0.0
        space.add(body, shape, rod)
        bodies.append(body)
        last = p
    return bodies[0], bodies[1]
