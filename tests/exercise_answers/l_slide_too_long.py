"""Wrong (fails 'stops at the slide max'): the slide joint's max is 100 px, not 25 * 1.5."""
import pymunk

S = 1.5


def add_L(space):
    center = pymunk.Body(body_type=pymunk.Body.STATIC)
    center.position = (400, 440)
    limit = pymunk.Body(body_type=pymunk.Body.STATIC)
    limit.position = (400 - 100 * S, 440)
    body = pymunk.Body(10, 10000 * S * S)
    body.position = (400, 440)
    l1 = pymunk.Segment(body, (-150 * S, 0), (255 * S, 0), 5 * S)
    l2 = pymunk.Segment(body, (-150 * S, 0), (-150 * S, -50 * S), 5 * S)
    pin = pymunk.PinJoint(body, center, (0, 0), (0, 0))
    slide = pymunk.SlideJoint(body, limit, (-100 * S, 0), (0, 0), 0, 100)
    space.add(center, limit, body, l1, l2, pin, slide)
    return body
