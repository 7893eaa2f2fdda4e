"""Finding the pairs of particles closer than a cut-off: the broad phase of a spatial force.

A force of spatial interaction (the lecture's third family: attraction and repulsion that "may act
on any or all pairs of particles, depending on their positions") that vanishes beyond a cut-off R
only needs the pairs with |x_j - x_i| < R. Two ways to find them, same answer:

* `all_pairs`: test every pair i < j, n (n - 1) / 2 distance tests: O(n^2). Simple, and the
  cheapest below about 100-200 particles (`python -m app bench particles` says where).
* `grid_pairs`: a uniform grid (a cell list) of cells at least R wide. Two particles closer than R
  lie in the same cell or in neighbouring cells, so each particle is only tested against the
  particles of its own cell and of the 8 around it (each pair once: its own cell and 4 of the 8,
  the "half stencil"): about 4.5 cells' worth of particles per particle. At a fixed density that
  is O(n) tests; in a fixed box, where more particles means denser, it is still a fixed fraction
  of all pairs (9 / cells: 4.5 cells' worth per particle against n/2 partners each for all
  pairs; 9/432, about 1/50, in the particle dance's box at R = 40). The price is sorting the
  particles by cell every step and a fixed cost per search (some 0.07 ms of NumPy calls, whatever
  n is: measured 72 us at n = 2, 78 us at n = 100) that makes all pairs the cheaper method for
  small n.

Both return the pairs (i, j), i != j, each unordered pair once, with |x_j - x_i| < R, and the
number of pair tests (distances compared with R) it took. The pairs come in a different order,
so forces summed over them agree to rounding, not bit for bit.

The grid covers a box (0, 0)-(w, h); a particle outside the box is counted in the nearest border
cell. That keeps the method exact (clamping never moves two particles' cells further apart than
one) and only costs speed if many particles leave the box.
"""

from __future__ import annotations

import numpy as np

NEIGHBOUR_METHODS = ("all_pairs", "grid")

# all_pairs tests a block of rows against the rest at once: about this many pairs per block keeps
# each temporary array near 0.5 MB, whatever n is (measured: 1M-pair blocks, 8 MB arrays fresh from
# the allocator every block, made n = 1000 about 5x slower).
BLOCK_PAIRS = 1 << 16

# The half stencil: a cell's pairs with the cells right of it and in the row below (the other four
# neighbours see this cell in their own stencil), so every pair of neighbouring cells is met once.
HALF_STENCIL = ((1, 0), (-1, 1), (0, 1), (1, 1))


def all_pair_tests(n: int) -> int:
    """Distance tests of `all_pairs` for n particles: n (n - 1) / 2."""
    return n * (n - 1) // 2


def all_pairs(x: np.ndarray, cutoff: float) -> tuple[np.ndarray, np.ndarray, int]:
    """Every pair i < j with |x_j - x_i| < cutoff, by testing them all. Returns (i, j, tests)."""
    n = len(x)
    r2_max = cutoff * cutoff
    rows = max(1, BLOCK_PAIRS // max(n, 1))
    found_i, found_j = [], []
    # the loop over blocks of rows (not over particles) replaces the double loop
    # `for i in range(n): for j in range(i + 1, n): test |x_j - x_i| < R`
    for a in range(0, n - 1, rows):
        b = min(n - 1, a + rows)
        dx = x[None, a + 1:, 0] - x[a:b, None, 0]             # row i = a + r, column j = a + 1 + c
        dy = x[None, a + 1:, 1] - x[a:b, None, 1]
        hits = np.flatnonzero(dx * dx + dy * dy < r2_max)     # flat: ~10x faster than 2-D
        r, c = np.divmod(hits, n - a - 1)
        keep = c >= r                                          # j > i: each pair once
        found_i.append(a + r[keep])
        found_j.append(a + 1 + c[keep])
    if not found_i:
        return np.zeros(0, np.intp), np.zeros(0, np.intp), 0
    return np.concatenate(found_i), np.concatenate(found_j), all_pair_tests(n)


def grid_shape(box: tuple[float, float], cutoff: float) -> tuple[int, int]:
    """Cells across and down: as many as fit with each cell at least `cutoff` wide and high."""
    return max(1, int(box[0] // cutoff)), max(1, int(box[1] // cutoff))


def _runs(owner: np.ndarray, first: np.ndarray, count: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each k: owner[k] paired with the positions first[k], first[k] + 1, ..., first[k] +
    count[k] - 1 (of the cell-sorted particle list). Replaces the loop
    `for k: for q in range(first[k], first[k] + count[k]): pairs.append((owner[k], q))`."""
    total = int(count.sum())
    i = np.repeat(owner, count)
    run_start = np.repeat(np.cumsum(count) - count, count)      # where each owner's run begins
    q = np.repeat(first, count) + (np.arange(total) - run_start)
    return i, q


def grid_pairs(x: np.ndarray, cutoff: float, box: tuple[float, float]
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """Every pair with |x_j - x_i| < cutoff, found with a uniform grid over `box` (w, h).
    Returns (i, j, tests): tests counts the candidate pairs from the same and neighbouring cells."""
    n = len(x)
    nx, ny = grid_shape(box, cutoff)
    cx = np.clip(np.floor(x[:, 0] * (nx / box[0])), 0, nx - 1).astype(np.intp)
    cy = np.clip(np.floor(x[:, 1] * (ny / box[1])), 0, ny - 1).astype(np.intp)
    cell = cy * nx + cx
    order = np.argsort(cell, kind="stable")        # particle indices, sorted by cell
    count = np.bincount(cell, minlength=nx * ny)   # particles per cell
    start = np.cumsum(count) - count               # where each cell's run begins in `order`
    k = np.arange(n)                               # positions in the sorted list
    kx, ky, kc = cx[order], cy[order], cell[order]
    # same cell: each particle with the ones after it in its cell's run (each pair once)
    pieces = [_runs(k, k + 1, start[kc] + count[kc] - (k + 1))]
    for dx, dy in HALF_STENCIL:                    # the 4 neighbouring cells of the half stencil
        ox, oy = kx + dx, ky + dy
        inside = (ox >= 0) & (ox < nx) & (oy >= 0) & (oy < ny)
        other = np.where(inside, oy * nx + ox, 0)
        pieces.append(_runs(k, start[other], np.where(inside, count[other], 0)))
    qi = np.concatenate([p[0] for p in pieces])
    qj = np.concatenate([p[1] for p in pieces])
    # coordinates in cell order (neighbours sit close in memory), one 1-D array each: taking
    # from 1-D arrays is about twice as fast as gathering rows of the (n, 2) array
    xs, ys = x[order, 0], x[order, 1]
    dx, dy = xs.take(qj) - xs.take(qi), ys.take(qj) - ys.take(qi)
    close = dx * dx + dy * dy < cutoff * cutoff
    return order[qi[close]], order[qj[close]], len(qi)


def find_pairs(method: str, x: np.ndarray, cutoff: float, box: tuple[float, float]
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """The pairs closer than `cutoff` by `method` ("all_pairs" or "grid"): (i, j, tests)."""
    if method == "all_pairs":
        return all_pairs(x, cutoff)
    if method == "grid":
        return grid_pairs(x, cutoff, box)
    raise ValueError(f"unknown neighbour method {method!r}; accepted: {', '.join(NEIGHBOUR_METHODS)}")


def expected_grid_tests(n: int, cutoff: float, box: tuple[float, float]) -> float:
    """Candidate pairs of `grid_pairs` for n particles spread evenly over the box: each particle
    meets the others of its own cell once (half of them) and those of 4 neighbouring cells."""
    nx, ny = grid_shape(box, cutoff)
    per_cell = n / (nx * ny)
    return n * (per_cell * 4.5 - 0.5) if n > 1 else 0.0


__all__ = ["NEIGHBOUR_METHODS", "all_pairs", "grid_pairs", "find_pairs", "all_pair_tests",
           "grid_shape", "expected_grid_tests"]
