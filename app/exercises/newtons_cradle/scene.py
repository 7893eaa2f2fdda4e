"""The `newtons_cradle` exercise's scene: `python -m app --scene exercise:newtons_cradle`.

The lecture's cradle scene (scenes/newtons_cradle.py), its balls and strings built by the
student's build_cradle; the lab's cradle swings behind it as orange rings.
"""

from __future__ import annotations

from typing import Any

import pygame
import pymunk

from app.exercises.live import GHOST, StudentCode
from app.scene import Effect
from scenes.newtons_cradle import RADIUS, SLOP, NewtonsCradleScene, string_of


def bodies_of(value: Any, count: int, what: str) -> list[pymunk.Body]:
    """What a builder returned, as `count` pymunk bodies (TypeError naming what came back)."""
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    if len(items) != count or not all(isinstance(b, pymunk.Body) for b in items):
        raise TypeError(f"{what} must return {count} pymunk.Body object(s), got {value!r:.200}")
    return items


class CradleExercise(StudentCode, NewtonsCradleScene):
    """Exercise `newtons_cradle`: the cradle scene, its balls and strings built by YOUR
    build_cradle; the lab's cradle swings behind it as orange rings (effect `reference`). The
    HUD gives the scene's verdict (k in, k out; middle drift; energy left), the grader's numbers.

    Mouse: drag a ball. Parameters: balls, lifted, damping, substeps, iterations, g.
    """

    exercise = "newtons_cradle"
    title = "Exercise: Newton's cradle"
    category = "Exercises"
    params = tuple(p for p in NewtonsCradleScene.params
                   if p.name not in ("gap", "angle", "elasticity"))   # yours decides these
    effects = NewtonsCradleScene.effects + (
        Effect("reference", True, "the lab's cradle, built by the lab's build_cradle, as orange "
               "rings", rebuild=True),)
    world_keys = NewtonsCradleScene.world_keys + ("ghost", "ghost_bodies", "ghost_anchors")
    overridden: list[str] = []          # space settings the student's builder set (and the
                                        # scene overrides): the HUD says so

    def add_balls(self, space: pymunk.Space) -> list[pymunk.Body]:
        from app.exercises.newtons_cradle.grader import overridden, space_settings
        n, k = self.p["balls"], self.p["lifted"]
        before = space_settings(space)
        bodies = bodies_of(self.impl.build_cradle(space, n, RADIUS, k), n, "build_cradle")
        self.overridden = overridden(before, space_settings(space))
        space.gravity, space.damping, space.iterations = (before["gravity"], before["damping"],
                                                          before["iterations"])   # the scene's
        try:                 # the order along the row is the strings' (lifted balls move)
            xs, where = [string_of(space, b)[1][0] for b in bodies], "their strings' anchors"
        except ValueError:   # a ball on no string: 'lifted as asked' says so; its x, here
            xs, where = [b.position.x for b in bodies], "their x"
        if any(not left < right for left, right in zip(xs, xs[1:])):
            # the verdict counts the LAST k balls as the far end: another order miscounts it
            raise ValueError("build_cradle must return the balls in order along the row, left "
                             f"to right; {where}: {', '.join(f'{x:.1f}' for x in xs)}")
        self.ghost, self.ghost_bodies, self.ghost_anchors = None, [], []
        if "reference" not in self.on:          # off: not built, not stepped
            return bodies
        self.ghost = pymunk.Space()
        self.ghost.collision_slop = SLOP
        self.ghost.iterations = self.p["iterations"]
        self.ghost.gravity = (0.0, self.gravity())
        self.ghost_bodies = self.reference.build_cradle(self.ghost, n, RADIUS, k)
        self.ghost_anchors = [string_of(self.ghost, b)[1] for b in self.ghost_bodies]
        return bodies

    def hud_lines(self) -> list[str]:
        lines = super().hud_lines()
        if self.overridden and not self.error:
            lines.insert(1, f"overridden: your build_cradle sets {', '.join(self.overridden)}; "
                         "the scene uses its g, damping, iterations")
        return lines

    def step(self, h: float) -> None:
        super().step(h)
        if self.ghost is None:
            return
        self.ghost.damping = self.space.damping
        self.ghost.gravity = self.space.gravity
        self.ghost.step(h)

    def draw(self, surface, view) -> None:
        if self.is_demo:               # the lab's cradle alone, in orange
            for body, anchor in zip(self.ghost_bodies, self.ghost_anchors):
                pygame.draw.aaline(surface, GHOST, view.pt(anchor), view.pt(body.position))
                pygame.draw.circle(surface, GHOST, view.pt(body.position),
                                   max(2.0, view.len(RADIUS)))
            return
        super().draw(surface, view)
        if not self.error:             # rings just outside the balls: yours sit inside them
            for body in self.ghost_bodies:
                pygame.draw.circle(surface, GHOST, view.pt(body.position),
                                   max(2.0, view.len(RADIUS + 3)), 2)


SCENE = CradleExercise
