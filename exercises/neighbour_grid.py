"""Exercise `neighbour_grid`: the particle dance's cell grid (lecture: spatial interaction forces,
"may act on any or all pairs of particles, depending on their positions").

A force that vanishes beyond a cut-off R only needs the pairs of particles closer than R. Testing
every pair costs n (n - 1) / 2 distances: 2 million for 2000 particles, every step. A uniform
grid of cells at least R wide finds the same pairs with a small fraction of the tests: two
particles closer than R lie in the same cell or in neighbouring cells (the 3 x 3 block around a
cell), so each particle is only tested against the particles of those nine cells.

    cells:      nx = floor(w / R) across, ny = floor(h / R) down (each at least R wide), a
                particle at (x, y) in cell (floor(x nx / w), floor(y ny / h)), clamped into
                0..nx-1 and 0..ny-1 (a particle exactly on the far edge, x = w, belongs to the
                last cell)
    candidates: for each particle, the particles of its own cell and of the 8 around it
    pairs:      the candidates with |x_j - x_i| < R, each unordered pair once, never (i, i)

Write `grid_pairs(x, cutoff, box)`: x has shape (n, 2), every particle inside the box
[0, w] x [0, h] (edges included), box = (w, h). Return (i, j, tests): two integer arrays of the
same length, pair k being particles i[k] and j[k] (in any order, each pair once), and `tests`, the
number of distances you computed (one per candidate pair you tested against the cut-off).

Check it:   python -m app exercise check neighbour_grid
Watch it:   python -m app --scene exercise:neighbour_grid   (your pairs as lines; a pair you
            missed in orange, one too many in red; the HUD counts your tests against all pairs)

What the grader measures: your pairs are exactly all pairs closer than the cut-off (found by
testing every pair), for random particles, tight clusters (many in one cell), particles on the
cell borders and the box's edges, and for 0, 1 and 2 particles; and on 2000 particles (the
particle dance's density, in a box 1440 x 480), your test count is the number of candidates of
a cell grid on those particles (about 2% of all pairs), which the grader counts itself: cells of
floor(w / R) searched 3 x 3 (or cells R / 2 or R / 3 wide, searched 2 or 3 cells around), each
candidate pair counted once or both ways round. Then random boxes, cut-offs (w / cutoff with any
fraction) and particles (seeded: the seed is printed, --seed N repeats it): every pair exactly,
and again a grid's count.

Hints:
  * Sort the particles into cells first: a dict from (cx, cy) to a list of indices, or NumPy
    (np.argsort of the cell number, then each cell's run); then visit each cell's neighbours.
  * Each pair once: within a cell, pair each particle with the ones after it; with a neighbour
    cell, keep i < j (or visit only half the neighbours: right, and the three below).
  * A plain Python loop over the cells is fine here; the lab's version (app/physics/neighbours.py,
    grid_pairs) finds all candidates at once with NumPy and a half stencil.
  * |d| < R, not <=: a pair exactly R apart does not interact.
"""

import numpy as np


def grid_pairs(x: np.ndarray, cutoff: float,
               box: tuple[float, float]) -> tuple[np.ndarray, np.ndarray, int]:
    """Every pair closer than `cutoff`, found with a cell grid over `box`: (i, j, tests)."""
    raise NotImplementedError("write me: put each particle in its cell, test it against the "
                              "particles of the 3 x 3 cells around it, keep |d| < cutoff")
