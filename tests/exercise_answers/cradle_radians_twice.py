"""Wrong (fails 'lifted as asked'): LIFT_ANGLE converted to radians a second time: the balls are
lifted 0.52 degrees, not 30 (and still give k in, k out)."""
import math

import pymunk

LIFT_ANGLE = math.radians(30.0)


def build_cradle(space, balls, radius, lifted):
    bodies = []
    for i in range(balls):
        ax, ay = 480.0 + (i - (balls - 1) / 2) * (2 * radius + 0.02), 230.0
        th = -math.radians(LIFT_ANGLE) if i < lifted else 0.0
        body = pymunk.Body(1, pymunk.moment_for_circle(1, 0, radius))
        body.position = (ax + 280 * math.sin(th), ay + 280 * math.cos(th))
        ball = pymunk.Circle(body, radius)
        ball.elasticity = 0.9999999
        ball.friction = 0.0
        string = pymunk.PinJoint(space.static_body, body, (ax, ay), (0, 0))
        string.error_bias = 0.0
        space.add(body, ball, string)
        bodies.append(body)
    return bodies
