"""Wrong (fails 'the L'): the limit body left dynamic (body_type forgotten): it falls away."""
import pymunk

S = 1.5                                    # the tutorial's lengths, scaled to the lab's world
ORIGIN = (400.0, 440.0)                    # where the tutorial's (300, 300) lands
LONG = ((-150 * S, 0.0), (255 * S, 0.0))   # the long arm, in the L body's frame
LIP = ((-150 * S, 0.0), (-150 * S, -50 * S))   # the short arm, pointing up (y down)
RADIUS = 5 * S
MASS = 10.0
MOMENT = 10000 * S * S                     # the tutorial's moment, scaled with the lengths
SLIDE_ANCHOR = (-100 * S, 0.0)             # the slide joint's anchor on the L
SLIDE_MAX = 25 * S


def add_L(space: pymunk.Space) -> pymunk.Body:
    centre = pymunk.Body(body_type=pymunk.Body.STATIC)
    centre.position = ORIGIN
    limit = pymunk.Body(1, 100)
    limit.position = (ORIGIN[0] + SLIDE_ANCHOR[0], ORIGIN[1] + SLIDE_ANCHOR[1])
    body = pymunk.Body(MASS, MOMENT)
    body.position = ORIGIN
    l1 = pymunk.Segment(body, LONG[0], LONG[1], RADIUS)
    l2 = pymunk.Segment(body, LIP[0], LIP[1], RADIUS)
    pin = pymunk.PinJoint(body, centre, (0, 0), (0, 0))
    slide = pymunk.SlideJoint(body, limit, SLIDE_ANCHOR, (0, 0), 0, SLIDE_MAX)
    space.add(l1, l2, body, pin, slide)
    return body
