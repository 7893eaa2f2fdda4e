"""Verlet cloth on obstacles and on itself: Jakobsen's projection, Coulomb friction, tunnelling
caught, self-collision with the neighbour grid.

What it shows: the lecture's Verlet cloth (scenes/cloth.py, every setting of it is here too),
seen edge-on: a strip two particles deep, let go above an obstacle. It drapes over a ball, sticks
to or slides off a tilted box, lies on a table as a tablecloth, falls onto a thin bar, and folds
onto itself.

The ideas, in the order a step runs them (app/physics/cloth_contact.py):
  * Projection (Jakobsen, 2001): after the Verlet step, a particle found inside an obstacle is
    moved to the surface along the shortest way out, x += -d n (d: the signed distance, n: the
    outward normal; app/physics/obstacles.py). No force, no stiffness: nothing to go unstable.
  * Coulomb friction: the sliding of a touching particle in this step loses at most mu times
    the distance the projection pushed it. On a slope the push is g h^2 cos(a) and the sliding
    g h^2 sin(a), so the cloth sticks exactly when tan(a) < mu (measured: at mu 0.5 it sticks at
    20 and 24 degrees, slides at 30; tests/test_cloth_contact.py).
  * Tunnelling: a particle faster than an obstacle is thick can jump across it in one step, and
    projection (which only looks at where it ends) never sees it. The sweep test looks at the
    whole path of the step and puts such a particle back where it entered (`tunneled` counts
    them: the thin-bar card makes hundreds).
  * Self-collision: pairs of particles closer than self_distance (not neighbours in one grid
    cell, not joined by a rod) are pushed apart to it, a constraint projected like a rod that may
    only grow (Breen's repulsion without its stiffness). The pairs come from the particle dance's
    neighbour grid (app/physics/neighbours.py) or, to compare, from testing all pairs.

Controls:
  LMB inside an obstacle   drag the obstacle (the cloth on it rides along by friction)
  LMB elsewhere            grab the nearest particle (as in the cloth scene)
  RMB, U                   unlock a particle, unlock all
Effects collisions, friction, self_collision: off, they cost nothing (the step never calls
them); on, the HUD's second page (F4) shows their share of the step.
"""

from __future__ import annotations

from dataclasses import replace

from app.scene import Try
from scenes.cloth import ClothScene

# This scene's defaults: a strip of cloth seen edge-on (two rows), let go above a ball.
STRIP = {"pins": "none", "rows": 2, "spacing": 10.0}
DEFAULTS = {"obstacles": "ball", **STRIP, "cols": 60}
FOLD = {"start": "folded", "obstacles": "floor", "cols": 60}
# a crumpled cloth on the floor: its heap stands at 3 substeps, not at 1 (the card below)
HEAP = {"start": "crumpled", "obstacles": "floor", "rows": 48, "cols": 48, "self_collision": True}


class ClothCollisionsScene(ClothScene):
    """Verlet cloth on obstacles (ball, tilted box, table, floor, thin bar) and on itself.

    LMB inside an obstacle: drag it. LMB elsewhere: grab a particle. RMB: unlock. U: unlock all.
    Projection keeps particles out of obstacles, Coulomb friction holds them (mu), the sweep
    test catches paths through thin ones (tunneled), self-collision keeps layers apart.
    """

    name = "cloth_collisions"
    title = "Verlet cloth: collisions"
    params = tuple(replace(p, default=DEFAULTS[p.name]) if p.name in DEFAULTS else p
                   for p in ClothScene.params)
    tries = (
        Try("Drape over a ball", {},
            "the strip (a cloth seen edge-on) falls onto the ball and drapes over it, both ends "
            "hanging; press LMB inside the ball and drag it: the cloth rides on it (friction)"),
        Try("Pull the tablecloth", {"obstacles": "table", "cols": 70},
            "the cloth settles on the table, hanging over both edges; grab one end (LMB) and pull "
            "it down and away: friction holds it back (mu in the panel; at mu 0 it follows any "
            "pull)"),
        Try("Fold onto itself", {**FOLD, "self_collision": True},
            "a strip folded once lands on the floor and stays in two layers: self-collision keeps "
            "them apart (self_overlaps: pairs left closer than 95% of self_distance)"),
        Try("Drop onto a thin bar", {"obstacles": "bar", "cols": 50, "hertz": 15},
            "at 15 Hz the strip hits a bar 4 px thick at ~40 px a step, and even resting on it "
            "gravity moves it g h^2 = 4.4 px a step: the sweep test catches each path through "
            "the bar (tunneled in the HUD, ~100 a step: every particle of the strip) and puts "
            "it back where it entered"),
    )
    comparisons = (
        Try("Slope: friction off vs on", {"obstacles": "box", "cols": 30},
            "a strip lands on a box tilted 20 deg: without friction (A) it slides off at once; "
            "with mu 0.5 (B), more than tan 20 deg = 0.36, it sticks where it landed",
            compare=({"friction": False}, {"friction": True})),
        Try("Fold: self-collision off vs on", FOLD,
            "the folded strip lands on the floor: without self-collision (A) the top layer falls "
            "into the bottom one (one line on the floor); with it (B) the two layers stay apart",
            compare=({"self_collision": False}, {"self_collision": True})),
        Try("Heap: 1 vs 3 substeps", HEAP,
            "a crumpled cloth let go onto the floor, self-collision on: at 1 substep (A) its "
            "weight presses the layers into one another, a flat tangle; at 3 substeps (B) the "
            "heap stands, two to three times as tall. Both sweep their pairs twice a substep: "
            "the smaller steps hold it, for the ms per step each pane shows",
            compare=({"substeps": 1}, {"substeps": 3})),
    )

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The strip, room for its ends to hang (half its length) and every obstacle, as it
        starts; then closing in on the strip and the obstacles as it settles (app/draw/follow.py:
        draped on the ball, the strip was a thin rim in two thirds of empty picture)."""
        from app.draw.follow import follow
        c = self.cloth
        cw = c.spacing * (c.cols - 1)
        ox, oy = self.origin
        return follow(self, self.contact_bounds((ox - 0.05 * cw, oy - 2 * c.spacing, 1.1 * cw,
                                                 c.spacing * (c.rows + 1) + 0.5 * cw)),
                      c.x, c.spacing)
