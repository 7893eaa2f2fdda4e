"""Wrong (fails 'built as asked'): angles converted to radians again (they are radians already)."""
import pymunk


def build_double_pendulum(space: pymunk.Space, anchor: tuple[float, float],
                          lengths: tuple[float, float], masses: tuple[float, float],
                          angles: tuple[float, float]) -> tuple[pymunk.Body, pymunk.Body]:
    import math
    angles = [math.radians(t) for t in angles]
    p1 = (anchor[0] + lengths[0] * math.sin(angles[0]), anchor[1] + lengths[0] * math.cos(angles[0]))
    p2 = (p1[0] + lengths[1] * math.sin(angles[1]), p1[1] + lengths[1] * math.cos(angles[1]))
    bodies = []
    for p, m in ((p1, masses[0]), (p2, masses[1])):
        body = pymunk.Body(m, pymunk.moment_for_circle(m, 0, 14))
        body.position = p
        shape = pymunk.Circle(body, 14)
        shape.filter = pymunk.ShapeFilter(group=1)
        space.add(body, shape)
        bodies.append(body)
    j1 = pymunk.PinJoint(space.static_body, bodies[0], anchor, (0, 0))
    j2 = pymunk.PinJoint(bodies[0], bodies[1], (0, 0), (0, 0))
    j1.error_bias = 0
    j2.error_bias = 0
    space.add(j1, j2)
    return bodies[0], bodies[1]
