"""Wrong (fails 'lifted as asked'): the LAST `lifted` balls pulled out to the left."""
import math

import pymunk

CENTRE_X = 480.0       # the middle of the bar, px
BAR_Y = 230.0          # height of the bar (y down), px
STRING = 280.0         # string length, anchor to ball centre, px
LIFT_ANGLE = math.radians(30.0)


def build_cradle(space: pymunk.Space, balls: int, radius: float,
                 lifted: int) -> list[pymunk.Body]:
    pitch = 2 * radius + 0.02
    bodies = []
    for i in range(balls):
        ax = CENTRE_X + (i - (balls - 1) / 2) * pitch
        th = -LIFT_ANGLE if i >= balls - lifted else 0.0
        body = pymunk.Body(1, pymunk.moment_for_circle(1, 0, radius))
        body.position = (ax + STRING * math.sin(th), BAR_Y + STRING * math.cos(th))
        shape = pymunk.Circle(body, radius)
        shape.elasticity = 0.9999999
        shape.friction = 0
        string = pymunk.PinJoint(space.static_body, body, (ax, BAR_Y), (0, 0))
        string.error_bias = 0
        space.add(body, shape, string)
        bodies.append(body)
    return bodies
