"""Self-collision compiled with numba: an optional path behind cloth_contact.self_collide, taken
when the cloth's `kernel` is "numba" (the rods' option, app/physics/rods_compiled.py; off by
default, named in the HUD). The physics is the NumPy pass's, written per pair (the slide's loop):

    find the pairs closer than self_distance on the NumPy pass's own grid (fine_pairs's cells,
    R/8 wide and R/2 high, and its stencil: app/physics/neighbours.py, fine_grid), each pair
    once, leaving out pairs joined by a rod of an active set or a cell's sides and diagonals
    (the same table: cloth_contact.joined_table);
    SELF_SWEEPS times: every pair pushed apart to self_distance, each end by its share
    w / (w_i + w_j), every particle moved by the average of its pairs' pushes x OVER_RELAX.

Why: the NumPy pass costs a dozen array operations per candidate pair and as many per pair
found (sort, runs of candidates, distances, the rod table, gathers, bincounts), each a pass over
memory. A compiled loop visits each candidate once, in registers. The pairs are the same (a test
compares them, and with all pairs on random clouds); positions agree to rounding.

What it costs, like with like (`python -m app bench cloth`: the pass beside the compiled step,
which kernel=numba also makes shorter: 0.35 ms, not NumPy's 0.89): on the crumpled 64 x 64
cloth 1.33 times that step, 0.42 times hanging (2026-11-27, load 1.1); 1.6 times crumpled with
cells R wide and a search that counted its candidates before listing them (41,342 candidates
for 24,845 now; the search 0.46 -> 0.28 ms, the sweeps 0.20 -> 0.15 ms, load ~1.5). Tried and
not kept: a branch per candidate instead of writing every candidate and counting the close ones
(1.2 x slower on the falling cloth: half the candidates are close, the branch guesses wrong),
32-bit work arrays, cells R/8 x R or R x R (the same time within the noise).
"""

from __future__ import annotations

import numpy as np

from app.ctrl_c import compiled
from app.physics.neighbours import fine_grid


def _sort(xs, ys, lo_x, lo_y, to_cell_x, to_cell_y, nx, ny, pad, columns, cells, minus, w,
          cell, start, order, sx, sy, s_key, s_w):        # compiled on use
    """Steps 1 and 2 of the grid (app/physics/neighbours.py): each particle's cell, then a
    counting sort by cell: order (the particles in cell order, index order within a cell),
    start[c + 1] where cell c begins, and in sorted order: the positions sx, sy, the rod-table
    key minus[p] and the weight. Returns True if every weight is the same and not 0 (nothing
    pinned or grabbed: every share 1/2). The cell is NumPy's own (fine_pairs): (x - lo) times
    1 / cell width in the positions' precision, truncated and clamped into the grid."""
    n = xs.size
    for c in range(cells + 2):
        start[c] = 0
    for p in range(n):                                  # 1. each particle's cell
        cx = int(min(max((xs[p] - lo_x) * to_cell_x, 0.0), nx - 1.0))
        cy = int(min(max((ys[p] - lo_y) * to_cell_y, 0.0), ny - 1.0))
        cell[p] = cy * columns + cx + pad
    for p in range(n):
        start[cell[p] + 1] += 1
    total = 0                                           # 2. sorted by cell (a counting sort):
    for c in range(1, cells + 2):                       # start[c + 1]: where cell c ends
        total += start[c]
        start[c] = total
    even = w[0] > 0
    for p in range(n - 1, -1, -1):                      # (filled from the end: each cell's
        c = cell[p]                                     # particles in index order; then
        k = start[c + 1] - 1                            # start[c + 1] is where cell c begins,
        start[c + 1] = k                                # start[c + 2] where it ends)
        order[k], sx[k], sy[k], s_key[k], s_w[k] = p, xs[p], ys[p], minus[p], w[p]
        even = even and w[p] == w[0]
    return even


def _search(sx, sy, s_key, cell, order, start, reach, columns, r2_max, key_reach, joined,
            out_a, out_b):                                # compiled on use
    """Step 3: (pairs found, candidate tests): the pairs closer than sqrt(r2_max), not joined
    by a rod, as sorted positions (a, b) into out_a, out_b; found is -1 if those are too short
    (the caller grows them and asks again). Pair (a, b) is joined where joined[s_key[b] -
    s_key[a] + key_reach] (cloth_contact's joined_table: plus = minus + its reach)."""
    n = sx.size
    below = reach.size - 1
    found = 0
    tests = 0
    cap = out_a.size
    for k in range(n):                  # each particle's runs: the rest of its own row's
        c, px, py = cell[order[k]], sx[k], sy[k]            # reach, then each row below
        pk = key_reach - s_key[k]
        for r in range(below + 1):
            if r == 0:
                lo, hi = k + 1, start[c + reach[0] + 2]
            else:
                lo, hi = start[c + r * columns - reach[r] + 1], start[c + r * columns + reach[r] + 2]
            tests += hi - lo
            if found + hi - lo > cap:
                return -1, tests
            # every candidate is written, and `found` steps on only for a close pair no rod
            # joins: no branch to mispredict (a third to a half of the candidates are close)
            for q in range(lo, hi):
                dx, dy = sx[q] - px, sy[q] - py
                out_a[found], out_b[found] = k, q
                found += (dx * dx + dy * dy < r2_max) & ~joined[s_key[q] + pk]
    return found, tests


def _sweep(tx, ty, a, b, s_w, dmin, even, first, over_relax, count, scale, moved_x, moved_y):
    """One Jacobi sweep over the pairs (a, b) (sorted positions) on the sorted positions tx,
    ty: every pair pushed apart to dmin, each end by its share w / (w_a + w_b) of the overlap,
    every particle moved by its pushes times its scale. The first sweep also counts each
    particle's pairs (pairs with both ends pinned left out) and sets scale = over_relax / its
    pairs (Jacobi's average, over-relaxed)."""
    n, m = tx.size, a.size
    for p in range(n):
        moved_x[p] = 0.0
        moved_y[p] = 0.0
        if first:
            count[p] = 0
    share_a = share_b = 0.5
    for k in range(m):
        pa, pb = a[k], b[k]
        if not even:
            total = s_w[pa] + s_w[pb]
            if total <= 0:
                continue                                # both pinned: neither moves
            share_a, share_b = s_w[pa] / total, s_w[pb] / total
        if first:
            count[pa] += 1
            count[pb] += 1
        dx, dy = tx[pb] - tx[pa], ty[pb] - ty[pa]
        r = np.sqrt(dx * dx + dy * dy)
        if r < 1e-6 * dmin:                             # at one point: part them along x
            dx, r = 1.0, 1.0
        push = max(dmin - r, 0.0) / r                   # the overlap per unit of d
        mx, my = dx * push, dy * push
        moved_x[pb] += mx * share_b
        moved_y[pb] += my * share_b
        moved_x[pa] -= mx * share_a
        moved_y[pa] -= my * share_a
    for p in range(n):
        if first:
            scale[p] = over_relax / count[p] if count[p] > 0 else 0.0
        tx[p] += moved_x[p] * scale[p]
        ty[p] += moved_y[p] * scale[p]


def _gather(xs, ys, order, tx, ty):
    """tx, ty = the positions in sorted order (xs[order], ys[order])."""
    for k in range(order.size):
        tx[k], ty[k] = xs[order[k]], ys[order[k]]


def _scatter(tx, ty, order, xs, ys):
    """The sorted positions written back: xs[order] = tx, ys[order] = ty."""
    for k in range(order.size):
        xs[order[k]], ys[order[k]] = tx[k], ty[k]


def _jit(fn):
    """fn compiled by numba on its first call (with Ctrl-C held back: app/ctrl_c.py)."""
    def make():
        import numba as nb
        return nb.njit(cache=True, nogil=True)(fn)
    return compiled(make)


_sort_jit = _jit(_sort)
_search_jit = _jit(_search)
_sweep_jit = _jit(_sweep)
_gather_jit = _jit(_gather)
_scatter_jit = _jit(_scatter)


class Buffers:
    """What the compiled pass keeps between steps: the pair arrays (grown when a step finds
    more pairs than they hold), the sort's arrays and the per-particle sums."""

    def __init__(self, n: int):
        self.a = np.empty(8 * n, np.int32)
        self.b = np.empty(8 * n, np.int32)
        self.moved_x = np.empty(n)
        self.moved_y = np.empty(n)
        self.count = np.zeros(n, np.int32)
        self.scale = np.zeros(n)
        self.cell = np.empty(n, np.int32)
        self.order = np.empty(n, np.int64)
        self.s_key = np.empty(n, np.int64)
        self.start = np.empty(0, np.int32)              # per cell (grown with the grid)
        self.sorted: dict = {}                          # sorted positions and weights, by dtype


def _grid(xs, ys, distance: float, joined: tuple, w, buf: Buffers):
    """Sort the particles into fine_pairs's grid (_sort) and find the pairs (_search): (found,
    tests, even, sorted positions and weights, the grid's args), or None for a point not
    finite (then no pair: the runner reports the state)."""
    n = xs.size
    grid = fine_grid(xs, ys, distance)
    if grid is None:
        return None
    lo_x, lo_y, cell_w, cell_h, nx, ny, reach, _ = grid     # (_sort clamps every point)
    pad, below = max(reach), len(reach) - 1
    columns = nx + 2 * pad
    cells = columns * (ny + below)
    if buf.start.size < cells + 2:
        buf.start = np.empty(cells + 2 + cells // 2, np.int32)
    arrays = buf.sorted.get((xs.dtype, w.dtype))
    if arrays is None or arrays[0].size != n:
        arrays = buf.sorted[xs.dtype, w.dtype] = (*(np.empty_like(xs) for _ in range(4)),
                                                  np.empty_like(w))
    sx, sy, tx, ty, s_w = arrays
    plus, minus, table = joined
    real = np.result_type(xs, ys, np.float32)           # fine_pairs's rounding: the same cells
    even = _sort_jit(xs, ys, real.type(lo_x), real.type(lo_y), real.type(1 / cell_w),
                     real.type(1 / cell_h), nx, ny, pad, columns, cells, minus, w, buf.cell,
                     buf.start, buf.order, sx, sy, buf.s_key, s_w)
    args = (sx, sy, buf.s_key, buf.cell, buf.order, buf.start, np.asarray(reach, np.int64),
            columns, real.type(distance * distance), int(plus[0] - minus[0]), table)
    found, tests = _search_jit(*args, buf.a, buf.b)
    while found < 0:                        # more than ever before (tests: those seen until
        size = 2 * max(tests, buf.a.size)   # the arrays were full): grow, search again
        buf.a, buf.b = np.empty(size, np.int32), np.empty(size, np.int32)
        found, tests = _search_jit(*args, buf.a, buf.b)
    return found, tests, bool(even), arrays


def find_pairs(xs, ys, distance: float, joined: tuple, buf: Buffers
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """(i, j, tests): the pairs closer than `distance` that are not joined (joined: cloth_contact's
    joined_table, (plus, minus, table)), on fine_pairs's grid (app/physics/neighbours.py)."""
    got = _grid(xs, ys, distance, joined, np.ones(xs.size, xs.dtype), buf)
    if got is None:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), 0
    found, tests = got[:2]
    return buf.order[buf.a[:found]], buf.order[buf.b[:found]], tests


def self_collide(xs, ys, w, distance: float, joined: tuple, over_relax: float, sweeps: int,
                 between, buf: Buffers) -> tuple[int, int]:
    """The whole pass, in place on xs, ys: the pairs found (find_pairs), then `sweeps` sweeps
    of the Jacobi projection over them, calling between() before each (the obstacles'
    projection, or None). The sweeps run on the positions in cell order (a pair's ends lie near
    each other in memory), written back once at the end. Returns (pairs, candidate tests)."""
    got = _grid(xs, ys, distance, joined, w, buf)
    if got is None:
        return 0, 0
    found, tests, even, (sx, sy, tx, ty, s_w) = got
    if found == 0:
        return 0, tests
    a, b, order = buf.a[:found], buf.b[:found], buf.order
    if between is None:
        tx, ty = sx, sy                                 # (the search is done with them)
    for sweep in range(sweeps):
        if between is not None:
            if sweep:
                _scatter_jit(tx, ty, order, xs, ys)
            between()
            _gather_jit(xs, ys, order, tx, ty)
        _sweep_jit(tx, ty, a, b, s_w, float(distance), even, sweep == 0, float(over_relax),
                   buf.count, buf.scale, buf.moved_x, buf.moved_y)
    _scatter_jit(tx, ty, order, xs, ys)
    return found, tests
