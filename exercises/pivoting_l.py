"""Exercise `pivoting_l`: the pymunk tutorial's add_L with joints ("Joints. Just wait and the L
will tip over").

The tutorial turns the static L into a moving one (these are the numbers of pymunk's example
file examples/slide_and_pinjoint.py and of the tutorial's older edition; the current tutorial
gives each segment a mass instead and lets pymunk compute the body's mass and moment):

    rotation_center_body = pymunk.Body(body_type=pymunk.Body.STATIC), at (300, 300)
    rotation_limit_body  = pymunk.Body(body_type=pymunk.Body.STATIC), at (200, 300)
    body = pymunk.Body(10, 10000), at (300, 300)
    l1 = pymunk.Segment(body, (-150, 0), (255, 0), 5)       the long arm
    l2 = pymunk.Segment(body, (-150, 0), (-150, 50), 5)     the short arm
    rotation_center_joint = pymunk.PinJoint(body, rotation_center_body, (0, 0), (0, 0))
    rotation_limit_joint  = pymunk.SlideJoint(body, rotation_limit_body, (-100, 0), (0, 0), 0, 25)
    space.add(l1, l2, body, rotation_center_joint, rotation_limit_joint)

A PinJoint keeps the distance between its two anchors (here 0: the L turns about the centre); a
SlideJoint lets the distance be anything from min to max, so the L turns until it reaches 25.

In the lab the world is 1.5x the tutorial's and y points down, so use the numbers below: the L at
ORIGIN, its arms LONG and LIP (the short arm points UP: -y), thickness RADIUS, mass MASS and
moment MOMENT, the slide joint's anchor on the L SLIDE_ANCHOR, its limit body at
ORIGIN + SLIDE_ANCHOR and its max SLIDE_MAX.

Write `add_L`: add the bodies, shapes and joints to `space` and return the L's body.

Check it:   python -m app exercise check pivoting_l
Watch it:   python -m app --scene exercise:pivoting_l    (balls land on your L)

What the grader measures: the L, pin and slide joint are built as above; with balls landing on it
for 10 s the L turns (more than 2 degrees) with its pin holding within 1 px, and the slide joint
stops it at its max (reached within 1 px, overshot by at most 2 px).
"""

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
    """Add the pivoting L (body, two segments, pin joint, slide joint) to `space`; return the L's
    body."""
    raise NotImplementedError("write me: the tutorial's add_L with the numbers above")
