"""The `neighbour_grid` exercise's scene: `python -m app --scene exercise:neighbour_grid`.

A small particle dance (the lab's pair rule, app/physics/particle_dance.py) whose pairs come from
the student's grid_pairs every step; on the same positions the lab's grid finds its pairs, and
the difference is drawn: a pair they missed in orange (the lab's), one too many in red.
"""

from __future__ import annotations

import numpy as np
import pygame

from app.exercises.live import ERROR, GHOST, MINE, StudentCode
from app.exercises.neighbour_grid.grader import pairs_of
from app.physics.neighbours import all_pair_tests, grid_shape
from app.physics.particle_dance import PairRule, reflect_into_box, rule_matrix
from app.scene import Param, Scene, common

BOX = (960.0, 720.0)
SPECIES = ((230, 230, 240), (120, 200, 120), (200, 120, 200))
CELL = (48, 52, 62)
LINK = (70, 110, 140)


class _Dance(Scene):
    """The scene's body; the exercise class below puts StudentCode in front of it (StudentCode's
    build imports the student's file, then calls this build)."""

    snapshot_skip = ("impl", "reference", "demo")

    def build(self) -> None:
        n = self.p["particles"]
        self.rule = PairRule(rule_matrix("random", len(SPECIES), self.rng), self.p["cutoff"],
                             attraction=400.0, repulsion=1200.0)
        self.x = self.rng.uniform(0.0, 1.0, (n, 2)) * BOX
        self.v = self.rng.normal(0.0, 40.0, (n, 2))
        self.species = self.rng.integers(0, len(SPECIES), n)
        self.find()

    def find(self) -> None:
        """Your pairs and the lab's on the positions now, and their difference."""
        mine = pairs_of(self.impl, self.x, self.p["cutoff"], BOX)
        self.i, self.j, self.tests = mine["i"], mine["j"], mine["tests"]
        li, lj, self.tests_lab = self.reference.grid_pairs(self.x, self.p["cutoff"], BOX)
        n = len(self.x)
        key = np.minimum(self.i, self.j) * n + np.maximum(self.i, self.j)
        lab_key = np.minimum(li, lj) * n + np.maximum(li, lj)
        self.pairs_lab = len(lab_key)
        unique, first = np.unique(key, return_index=True)
        bad = np.ones(len(key), bool)            # too far, with itself, or a second time
        bad[first] = ~np.isin(unique, lab_key)
        bad |= self.i == self.j
        self.extra = np.flatnonzero(bad)
        missed = np.setdiff1d(lab_key, unique)
        self.missed = np.stack([missed // n, missed % n], axis=1)

    def step(self, h: float) -> None:
        d = self.x[self.j] - self.x[self.i]
        r = np.sqrt(np.einsum("ij,ij->i", d, d))
        F = self.rule.magnitude(r, self.rule.matrix[self.species[self.i], self.species[self.j]])
        fi = (F / np.maximum(r, 1e-12))[:, None] * d
        f = np.zeros_like(self.x)
        np.add.at(f, self.i, fi)
        np.add.at(f, self.j, -fi)
        self.v = (self.v + h * f) * (1.0 - 0.8 * h)          # drag: the dance settles slowly
        self.x = self.x + h * self.v
        reflect_into_box(self.x, self.v, BOX)
        self.find()

    def metrics(self) -> dict[str, float]:
        return {"pairs": len(self.i), "pairs_lab": self.pairs_lab, "missed": len(self.missed),
                "extra": len(self.extra), "pair_tests": self.tests,
                "pair_tests_lab": self.tests_lab, "all_pair_tests": all_pair_tests(len(self.x))}

    def hud_lines(self) -> list[str]:
        m = self.metrics()
        share = 100.0 * m["pair_tests"] / max(m["all_pair_tests"], 1)
        return [f"pairs: yours {m['pairs']:,}, the lab's {m['pairs_lab']:,} (missed "
                f"{m['missed']:,}, too many {m['extra']:,})",
                f"pair tests: yours {m['pair_tests']:,}, the lab's {m['pair_tests_lab']:,}, all "
                f"pairs {m['all_pair_tests']:,} (yours: {share:.1f}% of all)"]

    def state_arrays(self):
        return (self.x, self.v)

    def content_bounds(self) -> tuple[float, float, float, float]:
        return (0.0, 0.0, BOX[0], BOX[1])

    def draw(self, surface, view) -> None:
        nx, ny = grid_shape(BOX, self.p["cutoff"])
        for k in range(nx + 1):
            pygame.draw.line(surface, CELL, view.pt((k * BOX[0] / nx, 0)),
                             view.pt((k * BOX[0] / nx, BOX[1])))
        for k in range(ny + 1):
            pygame.draw.line(surface, CELL, view.pt((0, k * BOX[1] / ny)),
                             view.pt((BOX[0], k * BOX[1] / ny)))
        pts = view.pts(self.x)
        if not self.is_demo:
            for a, b in zip(self.i.tolist(), self.j.tolist()):
                pygame.draw.aaline(surface, LINK, pts[a], pts[b])
        missed = self.missed if not self.is_demo else np.stack([self.i, self.j], axis=1)
        width = 1 if self.is_demo else max(2, int(view.len(3)))
        for a, b in missed.tolist():            # the lab's pairs you do not have: the ghost
            pygame.draw.line(surface, GHOST, pts[a], pts[b], width)
        for k in self.extra.tolist():
            pygame.draw.line(surface, ERROR, pts[self.i[k]], pts[self.j[k]], max(2, int(
                view.len(3))))
        r = max(2.0, view.len(3.5))
        for s, color in enumerate(SPECIES):
            for p in pts[self.species == s]:
                pygame.draw.circle(surface, GHOST if self.is_demo else color, p, r)
        if not self.is_demo:
            pygame.draw.rect(surface, MINE, (*view.pt((0, 0)), int(view.len(BOX[0])),
                                             int(view.len(BOX[1]))), 1)


class NeighbourGridExercise(StudentCode, _Dance):
    """Exercise `neighbour_grid`: a small particle dance (three species that attract and repel
    within the cut-off) moved by the pair forces over the pairs YOUR grid_pairs finds, every
    step. The grey lines are the grid's cells (as the lab cuts them); a thin line joins each pair
    you found. On the same positions the lab's grid finds its pairs: a pair you missed is drawn
    thick orange, a pair that is not one (too far, twice, with itself) thick red.

    HUD: your pairs against the lab's (missed, too many), your pair tests against the lab's and
    against all pairs (the grid's reason to exist).
    """

    exercise = "neighbour_grid"
    title = "Exercise: the neighbour grid"
    category = "Exercises"
    # 300 particles at 30 Hz: a grid written with Python loops (as the starter allows) keeps
    # up (~8 ms a step); 500 at 60 Hz fell to 6 fps with one
    params = (common("hertz", default=30), common("substeps", default=1),
              Param("particles", 300, int, 2, 3000, help="number of particles"),
              Param("cutoff", 60.0, float, 20.0, 200.0, help="interaction cut-off R, px"))


SCENE = NeighbourGridExercise
