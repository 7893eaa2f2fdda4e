"""Jakobsen's two loops on flat particle arrays: the velocity-less Verlet step and rod relaxation.

The cloth (app/physics/cloth.py) runs these two ideas on a grid, with its rods grouped by grid
direction. Here they are written for any particles and any rods: positions x of shape (n, 2),
rods as index arrays a, b (rod k joins particle a[k] to particle b[k]). They are the reference
answers of the exercises `verlet` and `constraints` (exercises/verlet.py, exercises/constraints.py)
and the ghost those exercises' scenes draw.

    verlet_step     x' = x + (1 - drag)(x - x_prev) + a h^2,  then x_prev = x
                    (the slide: x' = 2x - x_prev + a h^2; "lowering the value 2 to something like
                    1.99" is drag = 0.01: x' = 1.99 x - 0.99 x_prev + a h^2)
    satisfy_rods    for each rod: delta = x_b - x_a, diff = (|delta| - rest) / |delta|,
                    x_a += delta diff w_a/(w_a + w_b),  x_b -= delta diff w_b/(w_a + w_b)
                    (w = inverse mass, 0 = pinned), `iterations` sweeps over all rods.

One sweep is Gauss-Seidel: each rod sees the corrections of the rods before it. The loop over
rods is replaced by a loop over *batches* of rods that share no particle (each batch is solved at
once, like the cloth's batches); a batch after batch sweep is still Gauss-Seidel, only in another
order than rod by rod.
"""

from __future__ import annotations

import numpy as np

from app.physics.rods import EPS   # shortest rod length we divide by: no 0/0 at one point

_batches: dict[tuple, list[np.ndarray]] = {}     # rod_batches by rod list: rods rarely change


def verlet_step(x: np.ndarray, x_prev: np.ndarray, a: np.ndarray, h: float,
                drag: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """One velocity-less Verlet step: return (x_new, x), the new positions and the new previous
    positions. `drag` is the fraction of the distance travelled last step that is lost (0.01 turns
    the slide's 2 into 1.99). The input arrays are not changed."""
    x_new = x + (1.0 - drag) * (x - x_prev) + a * (h * h)
    return x_new, x.copy()


def rod_batches(a: np.ndarray, b: np.ndarray, n: int) -> list[np.ndarray]:
    """Split rods (a[k], b[k]) into batches of rod indices in which no two rods share a particle.

    Each round takes, among the rods left, every rod whose priority is the highest at both of its
    ends (a fixed shuffle of the rods: neighbouring rods rarely have falling priorities for long,
    so few rounds are needed). The loop runs once per batch, not once per rod."""
    m = len(a)
    priority = np.random.default_rng(0).permutation(m)
    left = np.arange(m)
    batches = []
    while left.size:
        best = np.full(n, -1)
        np.maximum.at(best, a[left], priority[left])      # the highest priority at each particle
        np.maximum.at(best, b[left], priority[left])
        p = priority[left]
        pick = (best[a[left]] == p) & (best[b[left]] == p)
        batches.append(left[pick])
        left = left[~pick]
    return batches


def satisfy_rods(x: np.ndarray, a: np.ndarray, b: np.ndarray, rest: np.ndarray, w: np.ndarray,
                 iterations: int) -> np.ndarray:
    """Relax the rods |x[b[k]] - x[a[k]]| = rest[k] by `iterations` Gauss-Seidel sweeps; return the
    new positions (a new array). w: inverse masses, 0 for a pinned particle (it never moves)."""
    x = np.array(x, dtype=float)
    a, b = np.asarray(a, dtype=np.intp), np.asarray(b, dtype=np.intp)
    rest, w = np.asarray(rest, dtype=float), np.asarray(w, dtype=float)
    total = w[a] + w[b]
    safe = np.where(total > 0, total, 1.0)
    share_a = np.where(total > 0, w[a] / safe, 0.0)[:, None]   # both ends pinned: nobody moves
    share_b = np.where(total > 0, w[b] / safe, 0.0)[:, None]
    key = (a.tobytes(), b.tobytes(), len(x))
    if key not in _batches:             # the same rods every step: find their batches once
        if len(_batches) > 16:
            _batches.clear()
        _batches[key] = rod_batches(a, b, len(x))
    batches = _batches[key]
    for _ in range(iterations):
        for k in batches:            # the rods of one batch share no particle: solved at once
            ia, ib = a[k], b[k]
            delta = x[ib] - x[ia]
            length = np.maximum(np.linalg.norm(delta, axis=1, keepdims=True), EPS)
            diff = (length - rest[k, None]) / length
            x[ia] += delta * diff * share_a[k]
            x[ib] -= delta * diff * share_b[k]
    return x


__all__ = ["verlet_step", "satisfy_rods", "rod_batches", "EPS"]
