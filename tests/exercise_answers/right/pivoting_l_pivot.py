"""Right: a PivotJoint (a pin of length 0) at the rotation centre, the joints made first."""
import pymunk

S = 1.5
ORIGIN = (400.0, 440.0)


def add_L(space):
    centre = pymunk.Body(body_type=pymunk.Body.STATIC)
    centre.position = ORIGIN
    limit = pymunk.Body(body_type=pymunk.Body.STATIC)
    limit.position = (ORIGIN[0] - 100 * S, ORIGIN[1])
    body = pymunk.Body(10.0, 10000 * S * S)
    body.position = ORIGIN
    pin = pymunk.PivotJoint(body, centre, ORIGIN)
    slide = pymunk.SlideJoint(body, limit, (-100 * S, 0.0), (0, 0), 0, 25 * S)
    arms = [pymunk.Segment(body, (255 * S, 0.0), (-150 * S, 0.0), 5 * S),
            pymunk.Segment(body, (-150 * S, -50 * S), (-150 * S, 0.0), 5 * S)]
    space.add(centre, limit, body, *arms, pin, slide)
    return body
