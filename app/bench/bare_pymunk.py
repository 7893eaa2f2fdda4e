"""The bare pymunk loop that `python -m app bench pymunk` measures the lab against: what a
minimal hand-written pymunk script doing the same physics would do, and nothing more.

For a scene whose bodies stay the same (a pile, the cradle, the pendulum) that is
`space.step(dt / substeps)`, substeps times a step. A scene that drops balls in and removes
those that fall out (falling_balls, pivoting_l) changes its space between substeps; so does the
bare script, at the same substeps and in the same order: for each new ball
`pymunk.Body(mass, pymunk.moment_for_circle(mass, 0, r))`, its position, a `pymunk.Circle`, its
friction and elasticity, `space.add(body, circle)`; for each ball that left, `space.remove(circle,
body)`. What to do at which substep is recorded once from a copy of the lab's scene run over the
same steps (`record`), and replayed (`Replay`): the bare script is told which balls leave, so it
reads no position and tests nothing (the strictest yardstick: the lab's reads, tests and
bookkeeping all count as the lab's cost). Same objects, same order of adds and removes, same
steps: the bare space holds the same bodies as the lab's, at the same places
(tests/test_bench_speed.py compares them step by step).
"""

from __future__ import annotations

from typing import Callable

import pymunk

from app.scene import Scene


class Unreplayable(Exception):
    """The scene changed its space in a way the bare loop does not replay (not a ball)."""


def _ball(body: pymunk.Body, shape: pymunk.Circle) -> tuple:
    """What the bare script needs to make the same ball: (mass, radius, offset, position,
    angle, velocity, angular velocity, friction, elasticity)."""
    return (body.mass, shape.radius, tuple(shape.offset), tuple(body.position), body.angle,
            tuple(body.velocity), body.angular_velocity, shape.friction, shape.elasticity)


def record(build: Callable[[], Scene], steps: int) -> list[list[tuple]]:
    """Run a fresh copy of the scene (build()) for `steps` steps and return, for every substep
    (steps x substeps of them), what the lab did to its space after that substep's
    `space.step`: a list of ("add", ball) and ("remove", number), where a ball's number is its
    place in the list of the space's bodies at the start followed by every body added since.
    Raises Unreplayable for a change that is not a ball (Body + Circle) added or removed."""
    scene = build()
    space = scene.space
    n = scene.p["substeps"]
    schedule: list[list[tuple]] = [[] for _ in range(steps * n)]
    number = {id(b): i for i, b in enumerate(space.bodies)}
    # every body numbered is held until the end: a ball removed and freed would leave its id to
    # the next new Body (CPython hands the same memory out again), which would then take over
    # its number, and every number after it would name another ball
    held = list(space.bodies)
    done = [0]                    # space.step calls so far
    step, add, remove = space.step, space.add, space.remove

    def counted_step(h: float) -> None:
        step(h)
        done[0] += 1

    def recorded_add(*objs) -> None:
        if not objs:              # (space.step's own call, for what a callback added)
            return
        bodies = [o for o in objs if isinstance(o, pymunk.Body)]
        shapes = [o for o in objs if isinstance(o, pymunk.Circle)]
        if (len(objs) != 2 or len(bodies) != 1 or len(shapes) != 1
                or shapes[0].body is not bodies[0] or not done[0]):
            raise Unreplayable(f"space.add{objs!r} after {done[0]} substeps")
        number[id(bodies[0])] = len(number)
        held.append(bodies[0])
        schedule[done[0] - 1].append(("add", _ball(bodies[0], shapes[0])))
        add(*objs)

    def recorded_remove(*objs) -> None:
        if not objs:
            return
        bodies = [o for o in objs if isinstance(o, pymunk.Body)]
        if len(objs) != 2 or len(bodies) != 1 or not done[0] or id(bodies[0]) not in number:
            raise Unreplayable(f"space.remove{objs!r} after {done[0]} substeps")
        schedule[done[0] - 1].append(("remove", number[id(bodies[0])]))
        remove(*objs)

    space.step, space.add, space.remove = counted_step, recorded_add, recorded_remove
    try:
        for _ in range(steps):
            scene.advance()
    finally:
        del space.step, space.add, space.remove
    if done[0] != steps * n:
        raise Unreplayable(f"{done[0]} substeps in {steps} steps of {n}")
    return schedule


class Replay:
    """The bare script over the space of a twin of the recorded scene (built the same way):
    `run(steps)` makes the next `steps` steps of `substeps` calls of space.step(h), adding and
    removing the recorded balls after the substeps where the lab did."""

    def __init__(self, twin: Scene, schedule: list[list[tuple]]):
        self.space = twin.space
        self.n = twin.p["substeps"]
        self.h = twin.dt / self.n
        self.schedule = schedule
        self.at = 0                                  # substeps made so far
        self.bodies = list(self.space.bodies)        # numbered as in record()
        self.shapes = {id(s.body): s for s in self.space.shapes}
        self.changes = any(schedule)

    def run(self, steps: int) -> None:
        space, h = self.space, self.h
        if not self.changes:                  # a scene whose bodies stay: only the steps
            for _ in range(steps * self.n):
                space.step(h)
            self.at += steps * self.n
            return
        schedule = self.schedule
        for i in range(self.at, self.at + steps * self.n):
            space.step(h)
            if schedule[i]:
                self.change(schedule[i])
        self.at += steps * self.n

    def change(self, ops: list[tuple]) -> None:
        """What a hand-written script does to drop in a ball, or to take out one that left."""
        space = self.space
        for op, what in ops:
            if op == "add":
                mass, radius, offset, pos, angle, vel, w, friction, elasticity = what
                body = pymunk.Body(mass, pymunk.moment_for_circle(mass, 0, radius, offset))
                body.position = pos
                if angle or w or vel != (0.0, 0.0):
                    body.angle, body.velocity, body.angular_velocity = angle, vel, w
                shape = pymunk.Circle(body, radius, offset)
                shape.friction, shape.elasticity = friction, elasticity
                space.add(body, shape)
                self.bodies.append(body)
                self.shapes[id(body)] = shape
            else:
                body = self.bodies[what]
                space.remove(self.shapes.pop(id(body)), body)


def counts(schedule: list) -> tuple[int, int]:
    """(balls added, balls removed) in a schedule (record(): a list of each substep's ops)."""
    ops = [op for substep in schedule for op, _ in substep]
    return ops.count("add"), ops.count("remove")
