"""Right: balls that cannot spin (infinite moment), touching exactly (no gap) with elasticity 1:
unusual, and it passes (the starter warns it hangs on rounding)."""
import math

import pymunk

CENTRE_X, BAR_Y, STRING, LIFT_ANGLE = 480.0, 230.0, 280.0, math.radians(30.0)


def build_cradle(space, balls, radius, lifted):
    bodies = []
    for i in range(balls):
        ax = CENTRE_X + (i - (balls - 1) / 2) * (2 * radius)
        th = -LIFT_ANGLE if i < lifted else 0.0
        body = pymunk.Body(1.0, float("inf"))
        body.position = (ax + STRING * math.sin(th), BAR_Y + STRING * math.cos(th))
        ball = pymunk.Circle(body, radius)
        ball.elasticity = 1.0
        ball.friction = 0.0
        string = pymunk.PinJoint(space.static_body, body, (ax, BAR_Y), (0, 0))
        string.error_bias = 0.0
        space.add(body, ball, string)
        bodies.append(body)
    return bodies
