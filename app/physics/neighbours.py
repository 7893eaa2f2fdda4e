"""Finding the pairs of particles closer than a cut-off: the broad phase of a spatial force.

A force of spatial interaction (the lecture's third family: attraction and repulsion that "may act
on any or all pairs of particles, depending on their positions") that vanishes beyond a cut-off R
only needs the pairs with |x_j - x_i| < R. Two ways to find them, same answer:

* `all_pairs`: test every pair i < j, n (n - 1) / 2 distance tests: O(n^2). Simple, and the
  cheaper one below about a hundred particles (`python -m app bench particles` says where).
* `grid_pairs`: a uniform grid (a cell list) of cells at least R wide. Two particles closer than R
  lie in the same cell or in neighbouring cells, so each particle is only tested against the
  particles of its own cell and of the 8 around it (each pair once: its own cell and 4 of the 8,
  the "half stencil"): about 4.5 cells' worth of particles per particle. At a fixed density that
  is O(n) tests; in a fixed box, where more particles means denser, it is still a fixed fraction
  of all pairs (9 / cells: 4.5 cells' worth per particle against n/2 partners each for all
  pairs; 9/432, about 1/50, in the particle dance's box at R = 40). The price is sorting the
  particles by cell every step and a fixed cost per search (about 0.08 ms of NumPy calls,
  whatever n is) that makes all pairs the cheaper method for small n.

The grid in three steps, as on the slide:

1. cell index: particle p at (x, y) is in cell (cx, cy) = (floor(x / cell width), floor(y /
   cell height)), numbered row by row: cell = cy * columns + cx;
2. sort: the particles sorted by cell number (`order`), so each cell's particles sit side by
   side in the sorted list, from start[cell] to stop[cell];
3. neighbouring cells: numbered row by row, the cell to the right of c is c + 1 and the three
   cells below are c + columns - 1, c + columns, c + columns + 1: consecutive numbers, so their
   particles are one run of the sorted list. A particle's candidate partners are therefore two
   runs: the rest of its own cell followed by the cell to its right, and the three cells below.
   A border of empty cells (a column on each side, a row below) gives every cell all its
   neighbours, so no cell needs a special case.

When the particles crowd together, the grid saves less and less: with everyone within one cell
and its neighbours it tests every pair, as all pairs does, and each of its candidates costs more
than an all-pairs test (13-15 ns against 5 ns at 5,000 particles). Yet it needs no fallback: its
smaller blocks of candidates keep a crowd at or under all pairs' time (`python -m app bench
particles`, table "Crowds", runs of 2026-11-24: 0.74-0.91 of all pairs' time with every particle
at one point; 0.82-1.02 with four clusters whose every pair is a candidate, 1.02 once: the noise
of two timings). A fallback to all pairs for crowds (90 % of all pairs or more as candidates) was
tried and measured at 2,000 particles: 0.99-1.01 of all pairs' time in the same crowds where the
grid alone took 0.81-0.99, so it would only make a crowd slower. `crowded_share` says how much of
the grid's advantage is gone.

Both methods hand out their pairs in blocks (`PairBlock`) of some tens of thousands, with the
separation d = x_j - x_i and |d|^2 they already computed: a force summed block by block keeps
its temporary arrays in the processor's cache (at 5,000 particles on the lab's busy 2-core
machine, the grid's search and forces took about half the time they took over one array of every
pair). `all_pairs`, `grid_pairs` and `find_pairs` return
every pair at once: (i, j, tests), i != j, each unordered pair once, with |x_j - x_i| < R, and
the number of pair tests (distances compared with R) it took. The two methods list the pairs in a
different order, so forces summed over them agree to rounding, not bit for bit.

The grid covers a box (0, 0)-(w, h); a particle outside the box is counted in the nearest border
cell. That keeps the method exact (clamping never moves two particles' cells further apart than
one) and only costs speed if many particles leave the box.

`fine_pairs` is the same grid with finer cells (R/8 wide, R/2 high) and each row of the stencil
trimmed to what a circle of radius R reaches: ~0.64 as many candidates for the same pairs (the
Verlet cloth's self-collision uses it; see the section "finer cells" below).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Iterator

import numpy as np

NEIGHBOUR_METHODS = ("all_pairs", "grid")

# all_pairs tests a block of rows against the rest at once: about this many pairs per block keeps
# each temporary array near 0.5 MB, whatever n is (measured: 1M-pair blocks, 8 MB arrays fresh from
# the allocator every block, made n = 1000 about 5x slower).
BLOCK_PAIRS = 1 << 16
# The grid tests its candidates in blocks of about this many (runs are never split, so a block
# of a crowded cell can be longer): 16 k candidates, 128 kB per array, stay in the cache.
GRID_BLOCK = 1 << 14
# The half stencil: a cell's pairs with the cells right of it and in the row below (the other four
# neighbours see this cell in their own stencil), so every pair of neighbouring cells is met once.
# sort_into_cells's two runs per particle cover exactly these cells (a test counts them).
HALF_STENCIL = ((1, 0), (-1, 1), (0, 1), (1, 1))


@dataclass
class PairBlock:
    """Some of the pairs closer than the cut-off: particle indices i and j (i != j, each pair
    once), and what the test already computed: d = x_j - x_i per axis (dx, dy) and r2 = |d|^2."""

    i: np.ndarray
    j: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    r2: np.ndarray


def _concatenate(blocks: Iterator[PairBlock]) -> tuple[np.ndarray, np.ndarray]:
    """The i and j of every block, as two arrays."""
    found = list(blocks)
    if not found:
        return np.zeros(0, np.intp), np.zeros(0, np.intp)
    return np.concatenate([b.i for b in found]), np.concatenate([b.j for b in found])


# ----- all pairs ------------------------------------------------------------------------------

def all_pair_tests(n: int) -> int:
    """Distance tests of `all_pairs` for n particles: n (n - 1) / 2."""
    return n * (n - 1) // 2


def all_pair_blocks(x: np.ndarray, cutoff: float) -> Iterator[PairBlock]:
    """Every pair i < j with |x_j - x_i| < cutoff, by testing them all, block by block."""
    n = len(x)
    r2_max = cutoff * cutoff
    rows = max(1, BLOCK_PAIRS // max(n, 1))
    x0, x1 = x[:, 0], x[:, 1]
    # the loop over blocks of rows (not over particles) replaces the double loop
    # `for i in range(n): for j in range(i + 1, n): test |x_j - x_i| < R`
    for a in range(0, n - 1, rows):
        b = min(n - 1, a + rows)
        dx = x0[None, a + 1:] - x0[a:b, None]                 # row i = a + r, column j = a + 1 + c
        dy = x1[None, a + 1:] - x1[a:b, None]
        r2 = dx * dx + dy * dy
        hits = np.flatnonzero(r2 < r2_max)                    # flat: ~10x faster than 2-D
        r, c = np.divmod(hits, n - a - 1)
        keep = c >= r                                          # j > i: each pair once
        hits = hits[keep]
        yield PairBlock(a + r[keep], a + 1 + c[keep], dx.ravel().take(hits),
                        dy.ravel().take(hits), r2.ravel().take(hits))


def all_pairs(x: np.ndarray, cutoff: float) -> tuple[np.ndarray, np.ndarray, int]:
    """Every pair i < j with |x_j - x_i| < cutoff, by testing them all. Returns (i, j, tests)."""
    i, j = _concatenate(all_pair_blocks(x, cutoff))
    return i, j, all_pair_tests(len(x))


# ----- the grid -------------------------------------------------------------------------------

def grid_shape(box: tuple[float, float], cutoff: float) -> tuple[int, int]:
    """Cells across and down: as many as fit with each cell at least `cutoff` wide and high."""
    return max(1, int(box[0] // cutoff)), max(1, int(box[1] // cutoff))


@dataclass
class CellList:
    """The particles sorted into the grid's cells, and each one's candidate partners.

    order[k] is the particle at position k of the sorted list. Particle order[k] is tested
    against the positions first[k] .. stop[k] - 1 (the rest of its own cell and the cell to its
    right) and first[n + k] .. stop[n + k] - 1 (the three cells below). `tests` is the number of
    candidate pairs, sum(stop - first)."""

    order: np.ndarray
    first: np.ndarray
    stop: np.ndarray
    tests: int


def cell_order(cell: np.ndarray, cells: int) -> np.ndarray:
    """The particles' indices sorted by cell, in index order within a cell (a stable sort). With
    at most 2^16 cells the keys are 16 bits, and NumPy's stable sort of them is a radix sort:
    5x faster at 4096 particles, the same order."""
    return np.argsort(cell.astype(np.uint16) if cells <= 1 << 16 else cell, kind="stable")


def sort_into_cells(x: np.ndarray, cutoff: float, box: tuple[float, float]) -> CellList:
    """Steps 1-3 of the module docstring: cell index, sort, the runs of neighbouring cells."""
    n = len(x)
    nx, ny = grid_shape(box, cutoff)
    columns = nx + 2                               # an empty column on either side...
    rows = ny + 1                                  # ...and an empty row below
    # 1. cell index (clamped into the box, then shifted right past the empty column)
    cx = np.clip(np.floor(x[:, 0] * (nx / box[0])), 0, nx - 1).astype(np.intp) + 1
    cy = np.clip(np.floor(x[:, 1] * (ny / box[1])), 0, ny - 1).astype(np.intp)
    cell = cy * columns + cx
    # 2. sort: particle indices in cell order; each cell's run is start[c] .. stop[c] - 1
    order = cell_order(cell, columns * rows)
    count = np.bincount(cell, minlength=columns * rows)    # particles per cell
    stop = np.cumsum(count)
    start = stop - count
    # 3. neighbouring cells: for the particle at sorted position k, in cell c
    k = np.arange(n)
    c = cell[order]
    first = np.concatenate((k + 1,                     # own cell after k, then cell c + 1
                            start[c + columns - 1]))  # cells c + columns - 1 .. c + columns + 1
    stops = np.concatenate((stop[c + 1], stop[c + columns + 1]))
    return CellList(order, first, stops, int((stops - first).sum()))


def grid_pair_blocks(x: np.ndarray, cutoff: float, box: tuple[float, float],
                     cells: CellList | None = None) -> Iterator[PairBlock]:
    """Every pair with |x_j - x_i| < cutoff among the grid's candidates, block by block (`cells`:
    the sort, if it was made already)."""
    cells = cells if cells is not None else sort_into_cells(x, cutoff, box)
    order, first = cells.order, cells.first
    length = cells.stop - first                    # candidates in each run
    owner = np.concatenate((np.arange(len(x)),) * 2)   # the sorted position each run belongs to
    xs, ys = x[order, 0], x[order, 1]              # coordinates in sorted order: neighbours sit
    r2_max = cutoff * cutoff                       # side by side in memory
    # blocks of whole runs, about GRID_BLOCK candidates each
    ends = np.cumsum(length)
    cuts = np.searchsorted(ends, np.arange(GRID_BLOCK, cells.tests, GRID_BLOCK))
    bounds = np.unique(np.concatenate(([0], cuts + 1, [len(length)])))
    for a, b in zip(bounds[:-1], bounds[1:]):
        runs, p = length[a:b], owner[a:b]
        slot = np.cumsum(runs) - runs              # where each run begins in this block
        # q: the partner of each candidate pair, its position in the sorted list; replaces
        # `for each run: for q in range(first, stop): candidates.append((p, q))`
        q = np.arange(int(runs.sum())) + np.repeat(first[a:b] - slot, runs)
        # the owner's coordinates repeated along its run (cheaper than gathering them per pair)
        dx = xs.take(q) - np.repeat(xs.take(p), runs)
        dy = ys.take(q) - np.repeat(ys.take(p), runs)
        r2 = dx * dx + dy * dy
        hits = np.flatnonzero(r2 < r2_max)
        i = np.repeat(order.take(p), runs).take(hits)
        j = order.take(q.take(hits))
        yield PairBlock(i, j, dx.take(hits), dy.take(hits), r2.take(hits))


def grid_pairs(x: np.ndarray, cutoff: float, box: tuple[float, float]
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """Every pair with |x_j - x_i| < cutoff, found with a uniform grid over `box` (w, h).
    Returns (i, j, tests): tests counts the candidate pairs from the same and neighbouring cells."""
    cells = sort_into_cells(x, cutoff, box)
    i, j = _concatenate(grid_pair_blocks(x, cutoff, box, cells))
    return i, j, cells.tests


def crowded_share(grid_tests: int, n: int) -> float:
    """The grid's tests as a share of all pairs' (0 to 1): about 9 / cells spread out, 1 when
    every particle is in one cell or its neighbours."""
    return grid_tests / all_pair_tests(n) if n > 1 else 0.0


# ----- finer cells: fewer candidates -------------------------------------------------------------
# The grid above tests 4.5 cells' worth of area per particle (cells R wide, 9 R^2 around it, half
# of it), while the pairs lie within the circle of radius R (pi R^2, half of it): about 3 times
# more candidates than pairs. Cells a hair over R/8 wide and R/2 high, with each row of cells
# below taking only the cells a circle of radius R can reach, test about 2.5 R^2 (rows of 8, 17
# and 15 cells): the bench's crumpled 64 x 64 cloth has 34,826 candidates for 17,924 pairs, where
# cells R wide gave ~64,000 and cells of exactly R/8 x R/2 ~41,000 (they need a 9th column and a
# 4th row for the rounding slack). Cells numbered row by row again, so each row of the stencil
# is one run of the sorted list: three runs per particle. Where the search's time goes in the
# cloth's step (the bench's crumpled state, a timer between the parts, 60 rounds, load 0.2,
# 2026-11-27): ~545 us, of it the runs' repeat ~100 (73 alone for 12,288 runs: ~6 ns a run, a
# branch per run, not its bytes), the candidates' d and |d|^2 ~80, the cell table ~64 (15 alone),
# the sort ~50, p and q ~50, the hits ~41, the runs' ends (cumsum) ~33. Not faster: cells R/4 or
# R/6 wide (the pass 1.00 and 1.03 x), and any other NumPy form of that cumsum (along either axis
# of a 2-D array it is a serial loop per row or column too, 24-42 us alone against 25; a log-step
# scan in blocks 78-111 us; int32, uint16 or float64 24-27 us).
FINE_CELLS = (8, 2)       # cells per cut-off across and down
CELLS_PER_PARTICLE = 8    # at most this many cells per particle: a spread-out crowd gets bigger
                          # cells (its count array stays small; it has few candidates anyway)
FINE_BLOCK = 1 << 16      # candidates per block (whole runs): the crumpled 64 x 64 cloth's
                          # ~29,000 in one block. Blocks of 8,192 (np.repeat's fresh arrays
                          # under glibc's 128 kB) made its pass ~4 % slower on 2026-11-27 (more
                          # calls), blocks of 16-32 k ~10 % (100 page faults a pass)
SLACK = 1e-3              # in cells: float32 rounding of a cell index never hides a pair
HALF_LIMIT = 1 << 31      # a run's (owner, first) as two int32s below this many candidates
_ROW = {t: np.dtype((np.void, 2 * np.dtype(t).itemsize)) for t in (np.int32, np.int64)}


@functools.lru_cache(maxsize=64)       # (the same cells step after step: asked once)
def fine_stencil(cutoff: float, cell_w: float, cell_h: float) -> tuple[int, ...]:
    """reach[r]: the cells left and right of a particle's column that its row (r = 0) and the
    r-th row below can hold a partner in: row r starts (r - 1) cell heights below the particle,
    where a partner is at most sqrt(R^2 - dy^2) away across."""
    reach = [math.ceil(cutoff / cell_w + SLACK)]
    while (len(reach) - 1) * cell_h * (1 - SLACK) < cutoff:
        dy = max((len(reach) - 1) * cell_h * (1 - SLACK), 0.0)
        reach.append(math.ceil(math.sqrt(cutoff * cutoff - dy * dy) / cell_w + SLACK))
    return tuple(reach)


class Scratch:
    """Work arrays kept between calls, by name (grown by half when too short): fresh arrays of
    some 40,000 elements a call would cost their page faults again each time the allocator hands
    the memory back to the system (a third of the search's time, measured on the crumpled cloth)."""

    def __init__(self) -> None:
        self.arrays: dict[str, np.ndarray] = {}

    def get(self, name: str, size: int, dtype=np.float32) -> np.ndarray:
        """The first `size` elements of the work array `name` (its values are left over)."""
        a = self.arrays.get(name)
        if a is None or a.size < size or a.dtype != dtype or a.size > max(8 * size, 1 << 20):
            # (grown by half; given back once a crowd that needed a huge one has spread out)
            a = self.arrays[name] = np.empty(max(size + size // 2, 1024), dtype)
        return a[:size]

    def count(self, size: int) -> np.ndarray:
        """0, 1, ..., size - 1 (np.arange, kept)."""
        a = self.arrays.get("count")
        if a is None or a.size < size or a.size > max(8 * size, 1 << 20):
            a = self.arrays["count"] = np.arange(max(size + size // 2, 1024))
        return a[:size]


def fine_grid(xs: np.ndarray, ys: np.ndarray, cutoff: float) -> tuple | None:
    """fine_pairs's grid: (lo_x, lo_y, cell_w, cell_h, nx, ny, reach, clamped), the grid's
    corner, the cells' size, how many across and down, fine_stencil's reach, and whether some
    points lie outside the grid (each is then counted in the nearest border cell: the callers
    clamp). The grid covers the points' own box, or, when a few points were flung far from the
    rest (a blown-up cloth lying flat: a long thin box), the box of the bulk. The compiled
    self-collision (app/physics/self_compiled.py) searches the same grid. None if a point is
    not finite (no pair is closer than the cut-off to a NaN; the runner reports it)."""
    lo_x, lo_y = float(xs.min()), float(ys.min())
    w, h = float(xs.max()) - lo_x, float(ys.max()) - lo_y
    if not (math.isfinite(w) and math.isfinite(h)):
        return None
    # (a hair over R/8 and R/2: a pair's cells are then at most 8 columns and 2 rows apart with
    # SLACK to spare, where exactly R/8 would need a 9th column and a 3rd row for the slack)
    fine_w = cutoff / (FINE_CELLS[0] - 2 * SLACK)
    fine_h = cutoff / (FINE_CELLS[1] * (1 - 2 * SLACK))
    cell_w, cell_h = _grown(w, h, fine_w, fine_h, xs.size)
    budget = 2 * CELLS_PER_PARTICLE * xs.size + 64
    clamped = False
    if (w / cell_w + 1) * (h / cell_h + 3) > budget and xs.size >= 20:
        # a long thin box: growing both sides alike leaves ~sqrt(length) cells along it (86 GB
        # of counts at 1e20 px). The grid covers the middle 90 % of the points on each axis and
        # a cut-off around them; a point outside is counted in the nearest border cell. Still
        # exact: clamping never moves two points' cells further apart, so a pair's cells stay
        # within the stencil's reach
        k = xs.size // 20
        qx = np.partition(xs, (k, xs.size - 1 - k))
        qy = np.partition(ys, (k, ys.size - 1 - k))
        lo_x, lo_y = float(qx[k]) - cutoff, float(qy[k]) - cutoff
        w, h = float(qx[-1 - k]) - lo_x + cutoff, float(qy[-1 - k]) - lo_y + cutoff
        cell_w, cell_h = _grown(w, h, fine_w, fine_h, xs.size)
        clamped = True
    if (w / cell_w + 1) * (h / cell_h + 3) > budget:     # the bulk itself long and thin: the
        if w / cell_w > h / cell_h:                       # long side's cells grow on until
            cell_w = max(cell_w, w / max(budget / (h / cell_h + 3) - 1, 1.0))     # the count
        else:                                             # is within the budget
            cell_h = max(cell_h, h / max(budget / (w / cell_w + 1) - 3, 1.0))
    reach = fine_stencil(cutoff, cell_w, cell_h)
    return (lo_x, lo_y, cell_w, cell_h, int(w / cell_w) + 1, int(h / cell_h) + 1, reach,
            clamped)


def _grown(w: float, h: float, cell_w: float, cell_h: float, n: int) -> tuple[float, float]:
    """The cells, grown alike on both sides if a box w x h would need more than
    CELLS_PER_PARTICLE cells a point (a spread-out crowd: its count array stays small)."""
    grow = math.sqrt((w / cell_w + 1) * (h / cell_h + 3) / (CELLS_PER_PARTICLE * n))
    return (cell_w * grow, cell_h * grow) if grow > 1 else (cell_w, cell_h)


def fine_pairs(xs: np.ndarray, ys: np.ndarray, cutoff: float, scratch: Scratch | None = None
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """Every pair with |x_j - x_i| < cutoff (each once, i != j), found with the finer cells
    above over the points' own box: (i, j, tests). Steps 1-3 of the module docstring, then the
    candidates block by block. i and j are work arrays of `scratch`: valid until its next use."""
    scratch = scratch if scratch is not None else Scratch()
    n = xs.size
    grid = fine_grid(xs, ys, cutoff)
    if grid is None:
        return np.zeros(0, np.intp), np.zeros(0, np.intp), 0
    lo_x, lo_y, cell_w, cell_h, nx, ny, reach, clamped = grid
    below = len(reach) - 1
    # an empty border as wide as the stencil on either side and as many empty rows below: every
    # stencil cell of every particle exists, in its own row, with no clipping
    pad = max(reach)
    columns = nx + 2 * pad
    # 1. cell index, 2. sort (16-bit keys: a radix sort), run ends: stop[c]
    if clamped:            # points outside the grid: into the nearest border cell (fine_grid)
        cx = np.clip((xs - lo_x) * (1 / cell_w), 0, nx - 1).astype(np.intp)
        cy = np.clip((ys - lo_y) * (1 / cell_h), 0, ny - 1).astype(np.intp)
    else:
        cx = np.minimum(((xs - lo_x) * (1 / cell_w)).astype(np.intp), nx - 1)
        cy = np.minimum(((ys - lo_y) * (1 / cell_h)).astype(np.intp), ny - 1)
    cell = np.multiply(cy, columns, out=cy)
    cell += cx
    cell += pad
    cells = columns * (ny + below)
    order = cell_order(cell, cells)
    c = cell.take(order)
    # stop[cell]: the particles in this cell and the ones before it. It is a step function of
    # the sorted cells: t from the cell of the t-th particle (sorted order) up to the next
    # particle's, so 0, 1, ..., n repeated over the gaps between them. It replaces
    # np.bincount(cell).cumsum(), the same numbers: a cumsum waits on its last sum at each
    # of the ~30,000 cells (~2.5 ns a cell), repeat writes them independently (4x faster alone)
    gap = scratch.get("gap", n + 1, np.intp)
    gap[0], gap[n] = c[0], cells - c[-1]
    np.subtract(c[1:], c[:-1], out=gap[1:n])
    stop = scratch.count(n + 1).repeat(gap)
    # (repeat has no out=: the table, ~270 kB, is fresh; held until the next search, so the
    # allocator does not give its pages back and fault them in again: 189 -> ~10 minor page
    # faults a pass on the crumpled cloth)
    scratch.arrays["stop"] = stop
    # 3. the runs of the particle at sorted position k, in cell c: the rest of its own row's
    # reach (k + 1 to the stop of cell c + reach[0]), then row r below: the cells c + r columns
    # - reach[r] .. c + r columns + reach[r] (the start of a cell is the stop of the one before)
    first = scratch.get("first", n * (below + 1), np.intp).reshape(below + 1, n)
    length = scratch.get("length", n * (below + 1), np.intp).reshape(below + 1, n)
    first[0] = scratch.count(n + 1)[1:]
    # (mode="wrap" with out=: the indices are in range by the border, and the default "raise"
    # writes through a copy of `out`, twice the time)
    stop[reach[0]:].take(c, out=length[0], mode="wrap")
    for r in range(1, below + 1):
        stop[r * columns - reach[r] - 1:].take(c, out=first[r], mode="wrap")
        stop[r * columns + reach[r]:].take(c, out=length[r], mode="wrap")
    first, length = first.ravel(), length.ravel()
    length -= first
    ends = length.cumsum(out=scratch.get("ends", length.size, np.intp))
    total = int(ends[-1])
    if total == 0:
        return np.zeros(0, np.intp), np.zeros(0, np.intp), 0
    first -= np.subtract(ends, length, out=scratch.get("starts", length.size, np.intp))
    # (q = first + c for candidate c of a run)
    real = np.result_type(xs, ys, np.float32)  # float32 or float64: all_pairs's own rounding
    pair = np.complex64 if real == np.float32 else np.complex128
    # each run as one 8-byte row (owner, first), two int32s, so that one repeat hands out both
    # (np.repeat makes a fresh array a call: one of them, not two). The owner is the run's
    # particle by its index (order[k]), not its sorted position k: a pair's i is then found as
    # it is, with no gather through `order` after the search (~4 % of the pass)
    # (int64 halves only where int32 cannot hold them: 2^31 candidates, a crowd of 65,536)
    half = np.int32 if total < HALF_LIMIT else np.int64
    runs_of = scratch.get("runs_of", 2 * first.size, half).reshape(below + 1, n, 2)
    runs_of[:, :, 0] = order
    runs_of[:, :, 1] = first.reshape(below + 1, n)
    runs_of = runs_of.reshape(-1, 2).view(_ROW[half]).reshape(-1)
    z_id = np.empty(n, pair)                   # positions x + i y, by index...
    z_id.real, z_id.imag = xs, ys
    z = z_id.take(order)                       # ...and in sorted order (the partners q)
    count = scratch.count(total)
    hit_p = scratch.get("hit_p", total, np.intp)
    hit_q = scratch.get("hit_q", total, np.intp)
    found = 0
    # blocks of whole runs, about FINE_BLOCK candidates each: their arrays stay in the cache
    bounds = [0, ends.size]                    # (one block: the crumpled cloth's ~29,000)
    if total > FINE_BLOCK:
        cuts = ends.searchsorted(np.arange(FINE_BLOCK, total, FINE_BLOCK)) + 1
        bounds[1:1] = sorted(set(np.minimum(cuts, ends.size).tolist()) - {0, ends.size})
    for r0, r1 in zip(bounds[:-1], bounds[1:]):
        c0 = int(ends[r0 - 1]) if r0 else 0
        runs = length[r0:r1]
        # p, q: each candidate's particle (its index) and partner (its sorted position):
        # repeat replaces `for each run: for q in range(first, stop): candidates.append((p,
        # q))`. The arrays' own methods (a.take, a.repeat), not np.take and the like: those
        # Python wrappers cost ~1 us a call, some 50 us of the crumpled cloth's pass
        both = runs_of[r0:r1].repeat(runs).view(half)
        scratch.arrays["both"] = both          # (held, as the cell table: no page faults)
        m = both.size // 2
        p = scratch.get("p", m, np.intp)
        p[:] = both[0::2]
        q = np.add(both[1::2], count[c0:c0 + m], out=scratch.get("q", m, np.intp))
        # d = x_q - x_p, x and y as one complex number (one gather, not two), then |d|^2 in
        # the positions' precision (all_pairs's rounding: the same pairs, exactly)
        d = z.take(q, out=scratch.get("d", q.size, pair), mode="wrap")
        d -= z_id.take(p, out=scratch.get("dp", q.size, pair), mode="wrap")
        dd = d.view(real)
        dd *= dd
        r2 = np.add(dd[0::2], dd[1::2], out=scratch.get("r2", q.size, real))
        hit = np.less(r2, real.type(cutoff * cutoff), out=scratch.get("hit", q.size, bool))
        # (the hits' indices, then two takes: 3x faster than p.compress(hit), q.compress(hit))
        hits = hit.nonzero()[0]
        k = hits.size
        p.take(hits, out=hit_p[found:found + k], mode="wrap")
        q.take(hits, out=hit_q[found:found + k], mode="wrap")
        found += k
    i = hit_p[:found]                          # (already indices)
    j = order.take(hit_q[:found], out=scratch.get("j", found, np.intp), mode="wrap")
    return i, j, total


# ----- both -----------------------------------------------------------------------------------

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


__all__ = ["NEIGHBOUR_METHODS", "PairBlock", "CellList", "all_pairs", "all_pair_blocks",
           "grid_pairs", "grid_pair_blocks", "sort_into_cells", "crowded_share", "find_pairs",
           "all_pair_tests", "grid_shape", "expected_grid_tests", "fine_pairs", "fine_grid",
           "Scratch"]
