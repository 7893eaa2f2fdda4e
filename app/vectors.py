"""Velocity and force arrows (Algodoo's and PhET's): what a scene hands over, and how the net
force on each body is measured.

A scene that has bodies or particles worth an arrow overrides `Scene.arrows()` and returns an
`Arrows`: which bodies (ids, to match them from one step to the next), where they are, how fast
they move and their masses, for every body or for a sample (a cloth's 1000 particles would be a
thicket: one in a few rows and columns is enough to read the flow). The shell draws them
(app/draw/arrows.py) only while the overlay is on; off, nothing here is called.

The force arrow is the NET force, measured, not summed from the scene's force terms:

    F = m (v_now - v_before) / dt       over the last fixed step

so it holds for every scene alike (pymunk's contacts and joints included): a ball resting on
the floor gets no force arrow (gravity and the floor's push cancel), a pendulum's bob gets the
centripetal pull of its rod. Particles without a mass (the Verlet cloth's) get m = 1: the arrow is
the acceleration then, and the legend says so.

Plain NumPy, no pygame: the Scene contract imports it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MAX_ARROWS = 300       # a sample larger than this is thinned (a thicket reads as nothing)


@dataclass
class Arrows:
    """ids (n,) ints: which bodies (the same body keeps its id between steps); pos (n, 2) world
    px; vel (n, 2) px/s; mass (n,) or None (unit masses: the force arrow is an acceleration);
    `of`: what the arrows sit on, for the legend ("every ball", "1 particle in 17")."""

    ids: np.ndarray
    pos: np.ndarray
    vel: np.ndarray
    mass: np.ndarray | None = None
    of: str = ""


def sample_every(n: int, most: int = MAX_ARROWS) -> int:
    """The stride that keeps at most `most` of n items (1: all of them)."""
    return max(1, -(-n // most))


def sample_text(n_shown: int, n_all: int, what: str) -> str:
    """'every particle' or '1 particle in 17' for the legend."""
    if n_shown >= n_all:
        return f"every {what}"
    return f"1 {what} in {round(n_all / max(n_shown, 1))}"


def grid_sample(rows: int, cols: int, most: int = 120) -> np.ndarray:
    """Flat indices (row-major) of a regular sample of a rows x cols grid: every k-th row and
    column, k the smallest that keeps at most `most` points, edges included."""
    k = 1
    while len(range(0, rows, k)) * len(range(0, cols, k)) > most:
        k += 1
    r = np.unique(np.r_[np.arange(0, rows, k), rows - 1])
    c = np.unique(np.r_[np.arange(0, cols, k), cols - 1])
    return (r[:, None] * cols + c[None, :]).ravel()


class ForceProbe:
    """Measures the net force on each arrow's body over the last step, m (v - v_before) / dt.
    `observe(scene)` after every fixed step (the runner calls it while the overlay is on);
    `latest` holds the last Arrows read and `force` the forces matched to them (None for the
    first step seen, or after a reset or a rollback: a velocity from another world is no
    'before')."""

    def __init__(self):
        self.latest: Arrows | None = None
        self.force: np.ndarray | None = None
        self.steps = -1          # scene.steps when latest was read
        self.observed = 0        # how many steps were observed (tests count it)

    def forget(self) -> None:
        self.latest, self.force, self.steps = None, None, -1

    def observe(self, scene) -> None:
        self.observed += 1
        now = scene.arrows()
        if now is None:
            self.forget()
            return
        before, self.force = self.latest, None
        if before is not None and scene.steps == self.steps + 1 and len(now.ids):
            self.force = net_force(before, now, scene.dt)
        self.latest, self.steps = now, scene.steps

    def current(self, scene) -> tuple[Arrows | None, np.ndarray | None]:
        """The arrows to draw now: the last observed if the scene has not moved on since
        (else read afresh, without a force)."""
        if self.latest is not None and self.steps == scene.steps:
            return self.latest, self.force
        return scene.arrows(), None


def net_force(before: Arrows, now: Arrows, dt: float) -> np.ndarray:
    """m (v_now - v_before) / dt for each of now's bodies; NaN rows for bodies not seen before
    (matched by id: bodies come and go)."""
    force = np.full_like(now.vel, np.nan, dtype=float)
    if before.ids.shape == now.ids.shape and np.array_equal(before.ids, now.ids):
        force[:] = now.vel - before.vel
    else:
        _, i_now, i_before = np.intersect1d(now.ids, before.ids, assume_unique=True,
                                            return_indices=True)
        force[i_now] = now.vel[i_now] - before.vel[i_before]
    force /= dt
    if now.mass is not None:
        force *= now.mass[:, None]
    return force


__all__ = ["Arrows", "ForceProbe", "net_force", "sample_every", "sample_text", "grid_sample",
           "MAX_ARROWS"]
