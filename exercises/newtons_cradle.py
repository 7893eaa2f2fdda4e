"""Exercise `newtons_cradle`: the lecture's pymunk classwork ("Classwork: Newton's Cradle"; the
slide's hint: shape.elasticity = 0.9999999).

Build the cradle in a pymunk space: `balls` balls of radius `radius` and mass 1, each hanging on
its own string from an anchor on a horizontal bar, side by side; the first `lifted` balls (the
left end) pulled out to the left by LIFT_ANGLE and let go. Then k balls in must give k balls out
at the far end, with the middle balls still:

    anchor i   = (CENTRE_X + (i - (balls - 1) / 2) * pitch, BAR_Y)     pitch = 2 radius + gap
    ball i     = anchor i + STRING (sin th, cos th)   th = -LIFT_ANGLE for the lifted ones, else 0
    a string   = pymunk.PinJoint(space.static_body, ball_body, anchor_i, (0, 0))

(y points down, so "down" is +y and "to the left" is -x.) The physics of an elastic collision of
equal masses swaps their velocities, so momentum and energy pass down the row ball by ball. Your
job is to make pymunk's impulse solver see that: read the docstring of scenes/newtons_cradle.py
for why each of these matters.

Write `build_cradle`: add every body, shape and joint to `space` and return the ball bodies in
order along the row (left to right).

Check it:   python -m app exercise check newtons_cradle
Watch it:   python -m app --scene exercise:newtons_cradle --set lifted=2

What the grader measures: the balls hang as above (angles, string lengths, the anchors on the bar
and centred on CENTRE_X, mass 1 each); then with the cradle scene's own verdict (5 balls, 120 Hz
x 30 substeps): k in, k out for k = 1, 2, 3; the middle balls stay within 2 px of rest over 10 s;
more than 95% of the energy is left after 10 s.
Then random rows (seeded: the seed is printed, --seed N repeats it): 2 to 9 balls of any
`radius` and any number lifted hang as above, and one random row gives k in, k out. The scene
sets the space's gravity, damping and iterations itself: if your build_cradle sets them, the
check and the scene's HUD say they were overridden.

Hints:
  * Leave a hair of space between the balls (gap ~0.02 px): balls pressed together (overlapping
    by 0.01 px) are solved as one lump, and the whole row leaves slowly instead of one ball
    leaving fast. Balls that touch exactly (gap 0) happen to pass here, but that hangs on
    rounding.
  * elasticity 0.9999999 on every ball, friction 0.
  * A PinJoint is soft by default (error_bias): set string.error_bias = 0 so a string does not
    stretch. At the grader's fine steps the soft default costs little (0.06% of the energy in
    10 s instead of 0.02%); in the double pendulum exercise it fails the energy check.
"""

import math

import pymunk

CENTRE_X = 480.0       # the middle of the bar, px
BAR_Y = 230.0          # height of the bar (y down), px
STRING = 280.0         # string length, anchor to ball centre, px
LIFT_ANGLE = math.radians(30.0)


def build_cradle(space: pymunk.Space, balls: int, radius: float,
                 lifted: int) -> list[pymunk.Body]:
    """Add the cradle to `space`; return the ball bodies, left to right."""
    raise NotImplementedError("write me: one Body + Circle + PinJoint string per ball, the first "
                              "`lifted` pulled out to the left")
