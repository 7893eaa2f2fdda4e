"""The NumPy exercises' scenes: two copies of one small system, the student's and the lab's,
stepped together and compared (each exercise's scene.py subclasses ParticleExercise and mixes in
StudentCode from app/exercises/live.py)."""

from __future__ import annotations

import copy
from typing import Iterable

import numpy as np
import pygame

from app.exercises.live import FIXED, GHOST, LINK, MINE
from app.scene import Scene


class ParticleExercise(Scene):
    """`make(impl)` builds a system whose `step(h)` calls impl's functions; the student's copy
    (`mine`) and the lab's (`lab`) are stepped together. A system has `x` (its particles, for
    the comparison), `points()` (what is drawn), `fixed` (anchors drawn grey), `links` (index
    pairs into points() + fixed), `radius` and `ring` (the lab's drawn as rings around yours, or
    as dots beside)."""

    category = "Exercises"
    snapshot_skip = ("impl", "reference", "demo")
    live: tuple[str, ...] = ()      # params both copies read every step (attributes of theirs)

    _bounds_cache: dict[tuple, tuple[float, float, float, float]] = {}

    def build(self) -> None:
        # the student's copy first: if their code raises while building, no step has run
        self.mine = self.make(self.impl)
        self.lab = self.make(self.reference)
        key = (self.exercise, tuple(sorted(self.p.items())))
        if key not in self._bounds_cache:      # the lab's copy alone decides them
            if len(self._bounds_cache) > 32:
                self._bounds_cache.clear()
            self._bounds_cache[key] = self.rest_bounds()
        self._bounds = self._bounds_cache[key]

    def rest_bounds(self, seconds: float = 3.0) -> tuple[float, float, float, float]:
        """Where the lab's copy goes in its first seconds (run on a copy, at most 2000 steps),
        with a margin, for the layout: fixed once built, so the picture does not jump (and the
        same for the same settings: kept per settings)."""
        sim = copy.deepcopy(self.lab)
        for name in self.live:
            setattr(sim, name, self.p[name])
        h = self.dt / self.p["substeps"]
        n = min(2000, int(seconds / h))
        pts = [np.reshape(sim.fixed, (-1, 2)), np.reshape(self.lab.points(), (-1, 2))]
        for _ in range(n):
            sim.step(h)
            pts.append(np.reshape(sim.points(), (-1, 2)))
        pts = np.concatenate(pts)
        pts = pts[np.isfinite(pts).all(axis=1)]
        (x0, y0), (x1, y1) = pts.min(axis=0), pts.max(axis=0)
        pad = max(40.0, 0.12 * max(x1 - x0, y1 - y0))
        return (float(x0 - pad), float(y0 - pad), float(x1 - x0 + 2 * pad),
                float(y1 - y0 + 2 * pad))

    def content_bounds(self) -> tuple[float, float, float, float]:
        return getattr(self, "_bounds", None) or super().content_bounds()

    def make(self, impl):
        """The system, its step calling impl's functions."""
        raise NotImplementedError

    def step(self, h: float) -> None:
        for sim in (self.mine, self.lab):
            for name in self.live:
                setattr(sim, name, self.p[name])
            sim.step(h)

    def measure(self) -> dict[str, float]:
        """The grader's live numbers (the metrics)."""
        return {"apart_px": self.apart()}

    def live_line(self, m: dict[str, float]) -> str:
        """The HUD line that reads them (lines, if it holds a newline)."""
        return f"yours vs the lab's: {m['apart_px']:.3g} px apart"

    def metrics(self) -> dict[str, float]:
        return self.measure()

    def hud_lines(self) -> list[str]:
        return self.live_line(self.metrics()).split("\n")

    def state_arrays(self) -> Iterable[np.ndarray]:
        return (self.mine.x, self.lab.x)

    def apart(self) -> float:
        """Largest distance between a particle of yours and the lab's, px (NaN if yours went
        NaN: a NaN is never 'close')."""
        d = np.abs(np.asarray(self.mine.x, dtype=float) - self.lab.x)
        return float(d.max()) if np.isfinite(d).all() else float("nan")

    def draw(self, surface, view) -> None:
        """Links and fixed points (grey), your particles (filled), the lab's as orange rings a
        little larger, on top: where yours is right, each blue disc sits inside its ring. As the
        demo beside an error, only the lab's copy, in orange."""
        sims = ((self.lab, GHOST),) if self.is_demo else ((self.lab, GHOST), (self.mine, LINK))
        for sim, color in sims:
            pts = view.pts(np.concatenate([np.reshape(sim.points(), (-1, 2)),
                                           np.reshape(sim.fixed, (-1, 2))]))
            for i, j in sim.links:
                pygame.draw.aaline(surface, color, pts[i], pts[j])
        for p in view.pts(np.reshape(self.lab.fixed, (-1, 2))):
            pygame.draw.circle(surface, FIXED, p, max(2.0, view.len(4)))
        r = max(2.0, view.len(self.lab.radius))
        if self.is_demo:
            for p in view.pts(np.reshape(self.lab.points(), (-1, 2))):
                pygame.draw.circle(surface, GHOST, p, r)
            return
        for p in view.pts(np.reshape(self.mine.points(), (-1, 2))):
            pygame.draw.circle(surface, MINE, p, r)
        for p in view.pts(np.reshape(self.lab.points(), (-1, 2))):
            if self.lab.ring:
                pygame.draw.circle(surface, GHOST, p, r + max(2.0, view.len(3)), 2)
            else:                       # drawn beside yours, not around it: dots
                pygame.draw.circle(surface, GHOST, p, r)


__all__ = ["ParticleExercise"]
