"""Right, with settings the scene overrides: a good cradle whose builder also sets the space's
gravity, damping and iterations. The scene sets those itself (its g, damping and iterations), so
every check passes, and 'lifted as asked' (and the live scene's HUD) says they were overridden."""
import math

import pymunk

CENTRE_X, BAR_Y, STRING, LIFT_ANGLE = 480.0, 230.0, 280.0, math.radians(30.0)


def build_cradle(space, balls, radius, lifted):
    space.gravity = (0.0, 500.0)
    space.damping = 0.9
    space.iterations = 5
    pitch = 2 * radius + 0.02
    bodies = []
    for i in range(balls):
        ax = CENTRE_X + (i - (balls - 1) / 2) * pitch
        th = -LIFT_ANGLE if i < lifted else 0.0
        body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0, radius))
        body.position = (ax + STRING * math.sin(th), BAR_Y + STRING * math.cos(th))
        ball = pymunk.Circle(body, radius)
        ball.elasticity = 0.9999999
        ball.friction = 0.0
        string = pymunk.PinJoint(space.static_body, body, (ax, BAR_Y), (0, 0))
        string.error_bias = 0.0
        space.add(body, ball, string)
        bodies.append(body)
    return bodies
