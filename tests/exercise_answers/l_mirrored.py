"""Wrong (fails 'the L'): the L mirrored, its long arm to the left."""
import pymunk

S = 1.5
ORIGIN = (400.0, 440.0)


def add_L(space):
    center = pymunk.Body(body_type=pymunk.Body.STATIC)
    center.position = ORIGIN
    limit = pymunk.Body(body_type=pymunk.Body.STATIC)
    limit.position = (ORIGIN[0] + (100 * S, 0.0)[0], ORIGIN[1])
    body = pymunk.Body(10, 10000 * S * S)
    body.position = ORIGIN
    l1 = pymunk.Segment(body, *((150 * S, 0.0), (-255 * S, 0.0)), 5 * S)
    l2 = pymunk.Segment(body, *((150 * S, 0.0), (150 * S, -50 * S)), 5 * S)
    pin = pymunk.PinJoint(body, center, (0, 0), (0, 0))
    slide = pymunk.SlideJoint(body, limit, (100 * S, 0.0), (0, 0), 0, 25 * S)
    space.add(center, limit, body, l1, l2, pin, slide)
    return body
