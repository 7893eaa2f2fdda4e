"""Right: the pin and the slide joint hold on to space.static_body (static, its local
coordinates the world's) instead of two static bodies of their own."""
import pymunk

S = 1.5
ORIGIN = (400.0, 440.0)
LONG = ((-150 * S, 0.0), (255 * S, 0.0))
LIP = ((-150 * S, 0.0), (-150 * S, -50 * S))
RADIUS, MASS, MOMENT = 5 * S, 10.0, 10000 * S * S
SLIDE_ANCHOR, SLIDE_MAX = (-100 * S, 0.0), 25 * S


def add_L(space):
    body = pymunk.Body(MASS, MOMENT)
    body.position = ORIGIN
    arms = [pymunk.Segment(body, *LONG, RADIUS), pymunk.Segment(body, *LIP, RADIUS)]
    world = space.static_body
    pin = pymunk.PinJoint(body, world, (0, 0), ORIGIN)
    limit = (ORIGIN[0] + SLIDE_ANCHOR[0], ORIGIN[1] + SLIDE_ANCHOR[1])
    slide = pymunk.SlideJoint(body, world, SLIDE_ANCHOR, limit, 0, SLIDE_MAX)
    space.add(body, *arms, pin, slide)
    return body
