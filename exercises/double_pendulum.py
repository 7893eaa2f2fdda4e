"""Exercise `double_pendulum`: a double pendulum in pymunk (the lecture's "test 10
doublePendulum.py"), checked against its equations of motion.

Two bobs hang from a fixed `anchor`: rod 1 (length l1) from the anchor to bob 1, rod 2 (length
l2) from bob 1 to bob 2. Angles are measured from straight down, in radians, and y points down:

    p1 = anchor + l1 (sin theta1, cos theta1)
    p2 = p1     + l2 (sin theta2, cos theta2)

Each bob is a dynamic body of its mass (give it a circle shape of radius ~14 px so the mouse can
grab it, and keep the two bobs from colliding: shape.filter = pymunk.ShapeFilter(group=1)); each
rod is a pymunk.PinJoint between the bodies' centres (the first one from space.static_body at the
anchor).

Write `build_double_pendulum`: add everything to `space` and return (body1, body2).

Check it:   python -m app exercise check double_pendulum
Watch it:   python -m app --scene exercise:double_pendulum   (the orange ghost: the equations of
            motion; try --set angle1=10 --set angle2=10: a small release stays with it)

What the grader measures: the bobs start where asked with their masses, in the space with
both rods, and cannot collide with each other; from a small release the tip stays within 1 px of
the equations' solution for 2 s; released high, the energy drifts less than 1% in 20 s; the rods'
lengths hold within 1 px.
Then random pendulums (seeded: the seed is printed, --seed N repeats it): any anchor, lengths,
masses and angles are built as asked, and a small random release stays within 1 px of the
equations.

Hints:
  * moment: pymunk.moment_for_circle(mass, 0, radius).
  * pymunk's joints are soft by default: set joint.error_bias = 0 (correct the whole length error
    every step), or the pendulum slowly loses energy.
"""

import pymunk


def build_double_pendulum(space: pymunk.Space, anchor: tuple[float, float],
                          lengths: tuple[float, float], masses: tuple[float, float],
                          angles: tuple[float, float]) -> tuple[pymunk.Body, pymunk.Body]:
    """Add the double pendulum to `space`; return (body1, body2)."""
    raise NotImplementedError("write me: two bodies at p1, p2 and two PinJoints")
