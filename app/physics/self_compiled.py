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
compares them, and with all pairs on random clouds); positions agree to rounding (to the
last bit in the bench's runs: below; tests/test_self_compiled.py compares whole passes).

What it costs, like with like (`python -m app bench cloth`: the pass beside the compiled step,
which kernel=numba also makes shorter, ~0.31-0.38 ms): on 2026-11-27, four whole runs of the
bench taking turns with main's code (load 5.5-9.2): crumpled 0.88-0.91 x the compiled step,
median 0.90 (main 1.42-1.50 x, median 1.46), hanging 0.33-0.35 x (main 0.42-0.46 x): the goal
of at most 1 x is met. (Four runs earlier that day, before the last four changes below, load
1.7-11: 0.95-0.99 x.) In one process, the pass taking turns with main's over the bench's 15
crumpled steps (31 rounds, load 4.2): 0.85 x (main 1.38-1.39 x), hanging 0.30-0.31 x
(0.39-0.41 x). What made it (each against the code before it, one process, the bench's 15
states in turn, CPU us a step, load 1.5-7.6):

  * a particle's three runs walked as one loop (t from 0 to e2: run 1 from e0, run 2 from e1,
    the candidate's place picked with no branch): the loop's end is mispredicted once a
    particle, not three times; the search 268 -> 191 us;
  * indices as unsigned integers where the compiler cannot see they are not negative (numba
    tests a signed index for Python's negative indexing: ~10 instructions a candidate);
    193 -> 160 us;
  * the cell table in 32 bits (its zeroing and running sum over ~30,000 cells, mostly empty):
    162 -> 147 us (hanging 96 -> 88);
  * numba's NumPy error model: no test and branch before each division (as NumPy, a division
    by zero gives inf or NaN), so the sweeps' pushes, computed in a loop of their own after d
    is gathered, become vector instructions: the two sweeps 132 -> 118 us; the pushes in the
    positions' precision (float32), as the NumPy pass computes them: 131 -> 114 us;
  * each particle's two sums, x and y, side by side in one array (one line of the cache):
    the two sweeps 117 -> 107 us;
  * the pairs (i, j) as unsigned 32-bit numbers, so that the sweeps index with them without
    numba's test for negative indices (and read half the bytes): the sweeps 116-122 -> 94-96
    us; in the run, the pass 0.96-0.97 -> 0.88-0.89 x the compiled step (load 4.8-5.0);
  * the sort's and each particle's cell indices unsigned too: the search 178-182 -> 172-175
    us, hanging 102-104 -> 97-98; the sorted particles' indices and rod numbers in 32 bits:
    166-174 -> 164-170 us, hanging 92-102 -> 89-98.

With float32 pushes summed in float64 (a sum of a few float32 numbers is exact in float64
unless their sizes differ by some 2^25 or more, so the order of the sums does not matter) the
compiled pass left the very positions the NumPy pass left: over the bench's 15 crumpled steps,
kernel=numba and kernel=numpy agreed to the last bit at every step (main's float64 pushes: 6e-5
px apart after one step, 14 px after 15, the crumpled cloth being chaotic). Since the evening of
2026-11-27 the NumPy pass sums in float32 (app/physics/cloth_contact.py says why): the two
kernels agree to a float32 step of a coordinate after a pass (6.1e-5 px, the bench's crumpled
cloth) and, chaos again, by 17 px after its 15 steps; tests compare single passes (1e-4 px). Where
the time goes now (the same states, 41 rounds, load ~4, CPU us a step): the Python side,
fine_grid's four NumPy reductions and numba's dispatch ~25-30; the cells and their running sum
~26; the sort's fill ~15; each particle's runs ~7; the 28,700 candidates ~99 (10,100 pairs,
averages of the 15 states); the two sweeps ~95 (the sums per pair ~29, d gathered and the pushes
~30, the passes over the particles, numba's calls and the Python side ~36), plus the obstacles'
projection before each (cloth_contact._push_out, NumPy: ~15 in the run).

Tried and not kept, the same way: the rod table read in a pass of its own over the close pairs
(as main's code does; with unsigned indices 155 -> 186 us); the pairs counted by the search
(free for the i ends, one pass over the j ends) instead of in the first sweep (crumpled the
same, hanging +5 us); the count in the first sweep's gather loop (the same); the pushes' x and y
side by side too (+4-6 us: their loop is then less of a vector loop); the sums zeroed in the
sweep's last pass over the particles, not a pass of their own (no faster); d gathered in the
pushes' loop (no vector instructions then: the sweeps 108 -> 133-141 us); the sums in two halves
at once, so consecutive pairs do not share an end (the same); rows of the stencil three at a
time through a table of offsets, one path for every stencil (+6 us, hanging +16); the positions
and (index, rod number) interleaved in one array each (the same); cells 2, 1.5 or 0.75 times as
wide, or 2 times as wide and 1.5 as high (the same or up to 15 us slower); the running sum of
the cell table with an accumulator or as two sums at once, the cells computed in a loop of their
own before the histogram, a 16-bit cell table (the same within the noise, or slower); the grid's
box in a compiled pass instead of fine_grid's four reductions (~5-10 us, but a second copy of
fine_grid's rules: left to neighbours.py). Before 2026-11-27 (with their figures then): cells R
wide and a search that counted its candidates before listing them (1.6 x the compiled step
against 1.33); a branch per candidate instead of writing every candidate and counting the close
ones (1.2 x slower falling: the branch guesses wrong); cells R/8 x R or R x R (the same); the
sweeps on the cell-sorted copies (the gather and scatter cost ~10 us); the pairs as per-particle
lists (CSR: the sweeps 25 % slower); a particle's runs in blocks of 4 or 8 candidates (hanging
1.35 x slower); a's sums kept in registers along its pairs (slower). Timing a kernel called
again and again on one state misleads: the branch predictor learns the state (the old search 88
us there, 190-245 us when the states change as in a run).
"""

from __future__ import annotations

import numpy as np

from app.ctrl_c import compiled
from app.physics.neighbours import fine_grid


def _find_pairs(xs, ys, lo_x, lo_y, to_cell_x, to_cell_y, nx, ny, reach, limit, plus, minus,
                cell, start, order, sx, sy, s_cell, s_plus, out_i, out_j):  # (compiled)
    """(pairs found, candidate tests): the pairs of fine_pairs's grid (cells 1 / to_cell_x by
    1 / to_cell_y from (lo_x, lo_y), nx x ny of them, the stencil's reach per row) closer than
    the cut-off and not joined, into out_i, out_j; found is -1 if those are too short (the
    caller grows them and asks again). Pair (p, q) counts where |x_q - x_p|^2 <
    limit[plus[q] - minus[p]]: limit is r2_max (the cut-off squared) where cloth_contact's
    joined_table says free, -1 where it says joined. The rest: work arrays."""
    n = xs.size
    pad = 0
    for r in range(reach.size):
        pad = max(pad, reach[r])
    below = reach.size - 1
    columns = nx + 2 * pad          # empty borders: every stencil cell exists, no clipping
    cells = columns * (ny + below)
    for c in range(cells + 2):
        start[c] = 0
    for p in range(n):                                  # 1. each particle's cell
        # clamped before the int (a point outside the grid goes to the nearest border cell:
        # fine_grid), so no cell index falls outside the arrays; (x - lo) times 1 / width in
        # the positions' precision, as fine_pairs computes it: the very same cells
        cx = int(min(max((xs[p] - lo_x) * to_cell_x, 0.0), nx - 1.0))
        cy = int(min(max((ys[p] - lo_y) * to_cell_y, 0.0), ny - 1.0))
        cell[p] = cy * columns + cx + pad
        start[np.uint64(cy * columns + cx + pad + 1)] += 1
    for c in range(1, cells + 1):                       # 2. sorted by cell (a counting sort):
        start[c] += start[c - 1]                        # start[c + 1]: where cell c ends
    start[cells + 1] = n
    one = np.uint64(1)                                  # (unsigned indices: below)
    for p in range(n - 1, -1, -1):                      # (filled from the end: each cell's
        c = np.uint64(cell[p])                          # particles in index order; then
        k = np.uint64(start[c + one] - 1)               # start[c + 1] is where cell c begins,
        start[c + one] = k                              # start[c + 2] where it ends)
        order[k], sx[k], sy[k], s_cell[k], s_plus[k] = p, xs[p], ys[p], c, plus[p]
    # 3. each particle's runs of candidates: the rest of its own row's reach (from k + 1),
    # then in each row r below the cells c + r columns - reach[r] .. c + r columns + reach[r].
    # Every candidate is written, and `found` steps on only for a pair that counts: no branch
    # to mispredict (a third to a half of the candidates count). The limit is read for every
    # candidate, not only for a close one: the compiler then makes no branch of it either
    found = 0
    tests = 0
    cap = out_i.size
    if below > 2:                                       # (more rows than fine_grid makes)
        for k in range(n):
            c, p, px, py = s_cell[k], order[k], sx[k], sy[k]
            mp = minus[p]
            for r in range(below + 1):
                lo = start[c + r * columns - reach[r] + 1] if r else k + 1
                hi = start[c + r * columns + reach[r] + 2]
                tests += hi - lo
                if found + hi - lo > cap:
                    return -1, tests
                for q in range(lo, hi):
                    dx, dy = sx[q] - px, sy[q] - py
                    out_i[found], out_j[found] = p, order[q]
                    found += dx * dx + dy * dy < limit[s_plus[q] - mp]
        return found, tests
    # at most three rows (what fine_grid makes): a particle's three runs walked as one, t
    # from 0 to e2, run 1 from t = e0 and run 2 from e1 (a missing row: an empty run). One
    # loop per particle, not three: its end is mispredicted once, not three times (~75 us of
    # the crumpled cloth's 28,700 candidates). Indices as unsigned: numba then does not test
    # them for Python's negative indices
    r0 = reach[0] + 2
    lo1 = hi1 = lo2 = hi2 = r0
    if below >= 1:
        lo1, hi1 = columns - reach[1] + 1, columns + reach[1] + 2
        lo2 = hi2 = hi1
    if below == 2:
        lo2, hi2 = 2 * columns - reach[2] + 1, 2 * columns + reach[2] + 2
    u0, ul1, uh1, ul2, uh2 = (np.uint64(r0), np.uint64(lo1), np.uint64(hi1), np.uint64(lo2),
                              np.uint64(hi2))
    for k in range(n):
        c, p, px, py = np.uint64(s_cell[k]), order[k], sx[k], sy[k]
        mp = minus[np.uint64(p)]
        a0, a1, a2 = k + 1, start[c + ul1], start[c + ul2]      # the runs' first candidates
        e0 = start[c + u0] - a0                                 # and where each ends in t
        e1 = e0 + start[c + uh1] - a1
        e2 = e1 + start[c + uh2] - a2
        b1, b2 = a1 - e0 - a0, a2 - e1 - a1 + e0
        tests += e2
        if found + e2 > cap:
            return -1, tests
        for t in range(e2):
            q = np.uint64(t + a0 + (t >= e0) * b1 + (t >= e1) * b2)
            dx, dy = sx[q] - px, sy[q] - py
            f = np.uint64(found)
            out_i[f], out_j[f] = p, order[q]
            found += dx * dx + dy * dy < limit[np.uint64(s_plus[q] - mp)]
    return found, tests


def _push_apart(xs, ys, i, j, w, dmin, once, over_relax, count, scale, moved):
    """One Jacobi sweep over the pairs: every pair pushed apart to dmin, each end by its share
    w / (w_i + w_j) of the overlap, every particle moved by its pushes times its scale. The
    first sweep (once) also counts each particle's pairs as it goes (pairs with both ends pinned
    left out) and sets scale = over_relax / its pairs (Jacobi's average, over-relaxed) before
    moving anyone: the pushes are summed unscaled. (Some particle pinned or grabbed; all free
    with the same weight: _push_even.)"""
    n, m = xs.size, i.size
    for p in range(n):
        moved[2 * p] = 0.0
        moved[2 * p + 1] = 0.0
        if once:
            count[p] = 0
    for k in range(m):
        a, b = i[k], j[k]
        total = w[a] + w[b]
        if total <= 0:
            continue                                # both pinned: neither moves
        share_a, share_b = w[a] / total, w[b] / total
        if once:
            count[a] += 1
            count[b] += 1
        dx, dy = xs[b] - xs[a], ys[b] - ys[a]
        r = np.sqrt(dx * dx + dy * dy)
        if r < 1e-6 * dmin:                 # at one point: as if 1e-6 dmin apart along x
            dx, dy, r = 1e-6 * dmin, 0.0, 1e-6 * dmin
        push = max(dmin - r, 0.0) / r                   # the overlap per unit of d
        mx, my = dx * push, dy * push
        moved[2 * b] += mx * share_b
        moved[2 * b + 1] += my * share_b
        moved[2 * a] -= mx * share_a
        moved[2 * a + 1] -= my * share_a
    for p in range(n):
        if once:
            scale[p] = over_relax / count[p] if count[p] > 0 else 0.0
        xs[p] += moved[2 * p] * scale[p]
        ys[p] += moved[2 * p + 1] * scale[p]


def _push_even(xs, ys, i, j, dmin, tiny, once, over_relax, count, scale, moved, fx, fy):
    """_push_apart's sweep with every particle free and of the same weight (nothing pinned or
    grabbed): every share is 1/2 (in scale), no weights read. In three loops: d gathered pair
    by pair; the pushes, a loop with no gather and no branch that the compiler turns into
    vector instructions (8 pairs at a time), in the positions' precision as NumPy's pass
    computes them; then summed per particle. The first sweep counts the pairs in a loop of
    its own."""
    n, m = xs.size, i.size
    for k in range(m):
        a, b = i[k], j[k]
        fx[k] = xs[b] - xs[a]
        fy[k] = ys[b] - ys[a]
    zero = np.float32(0.0)
    for k in range(m):
        dx, dy = fx[k], fy[k]
        r = np.sqrt(dx * dx + dy * dy)
        same = r < tiny                     # at one point: as if tiny apart along x (tiny is
        dx = tiny if same else dx           # 1e-6 dmin in the positions' type: push_apart)
        dy = zero if same else dy
        r = tiny if same else r
        over = dmin - r
        push = (over if over > 0 else zero) / r         # the overlap per unit of d
        fx[k] = dx * push
        fy[k] = dy * push
    for p in range(2 * n):
        moved[p] = 0.0
    if once:
        for p in range(n):
            count[p] = 0
        for k in range(m):
            count[i[k]] += 1
            count[j[k]] += 1
        for p in range(n):
            scale[p] = 0.5 * over_relax / count[p] if count[p] > 0 else 0.0
    for k in range(m):                                  # (x and y side by side in `moved`:
        a, b = np.uint64(i[k]), np.uint64(j[k])         # a particle's two sums in one line
        a, b, y = a + a, b + b, np.uint64(1)            # of the cache, one array)
        mx, my = np.float64(fx[k]), np.float64(fy[k])
        moved[b] += mx
        moved[b + y] += my
        moved[a] -= mx
        moved[a + y] -= my
    for p in range(n):
        xs[p] += moved[2 * p] * scale[p]
        ys[p] += moved[2 * p + 1] * scale[p]


def _all_same(w):
    """True if every weight is w[0] and that is above 0 (every particle free, none grabbed)."""
    for p in range(w.size):
        if w[p] != w[0]:
            return False
    return w.size > 0 and w[0] > 0


def _jit(fn):
    """fn compiled by numba on its first call (with Ctrl-C held back: app/ctrl_c.py). NumPy's
    error model: a division by zero gives inf or NaN as NumPy's pass does, with no test and
    branch before each division (which kept the compiler from vector instructions)."""
    def make():
        import numba as nb
        return nb.njit(cache=True, nogil=True, error_model="numpy")(fn)
    return compiled(make)


_find = _jit(_find_pairs)
_push = _jit(_push_apart)
_push_same = _jit(_push_even)
_same = _jit(_all_same)


class Buffers:
    """What the compiled pass keeps between steps: the pair arrays (grown when a step finds
    more pairs than they hold), the search's work arrays and the per-particle sums."""

    def __init__(self, n: int):
        self.i = np.empty(8 * n, np.uint32)             # (unsigned: no test for Python's
        self.j = np.empty(8 * n, np.uint32)             # negative indices in the sweeps)
        self.moved = np.empty(2 * n)                    # each particle's sums, x then y
        self.count = np.zeros(n, np.int64)
        self.scale = np.zeros(n)
        self.cell = np.empty(n, np.int32)               # (32-bit: the cell table's passes
        self.order = np.empty(n, np.uint32)             # over memory half as long)
        self.s_cell = np.empty(n, np.int32)
        self.s_plus = np.empty(n, np.int32)
        self.start = np.empty(0, np.int32)              # per cell (grown with the grid)
        self.sorted: dict = {}                          # positions in cell order, by dtype
        self.pushes: dict = {}                          # each pair's push, x and y, by dtype
        self.limit: tuple = (None, None, None)          # (joined table, r2_max, limit)
        self.reach: tuple = (None, None)                # (the stencil, as an array)


def find_pairs(xs, ys, distance: float, joined: tuple, buf: Buffers
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """(i, j, tests): the pairs closer than `distance` that are not joined (joined: cloth_contact's
    joined_table, (plus, minus, table)), on fine_pairs's grid (app/physics/neighbours.py)."""
    n = xs.size
    grid = fine_grid(xs, ys, distance)
    if grid is None:                                    # a point not finite: the runner says so
        return buf.i[:0], buf.j[:0], 0
    lo_x, lo_y, cell_w, cell_h, nx, ny, reach, _ = grid   # (_find clamps every point)
    pad, below = max(reach), len(reach) - 1
    cells = (nx + 2 * pad) * (ny + below)
    if buf.start.size < cells + 2:
        buf.start = np.empty(cells + 2 + cells // 2, np.int32)
    sx, sy = buf.sorted.get(xs.dtype, (None, None))
    if sx is None or sx.size != n:
        sx, sy = buf.sorted[xs.dtype] = np.empty_like(xs), np.empty_like(ys)
    real = np.result_type(xs, ys, np.float32)           # fine_pairs's rounding: the same pairs
    plus, minus, table = joined
    r2_max = real.type(distance * distance)
    if buf.limit[0] is not table or buf.limit[1] != r2_max or buf.limit[2].dtype != real:
        buf.limit = (table, r2_max, np.where(table, real.type(-1), r2_max).astype(real))
    if buf.reach[0] != reach:
        buf.reach = (reach, np.asarray(reach, np.int64))
    args = (xs, ys, real.type(lo_x), real.type(lo_y), real.type(1 / cell_w),
            real.type(1 / cell_h), nx, ny, buf.reach[1], buf.limit[2], plus, minus, buf.cell,
            buf.start, buf.order, sx, sy, buf.s_cell, buf.s_plus)
    found, tests = _find(*args, buf.i, buf.j)
    while found < 0:                        # more than ever before (tests: those seen until
        size = 2 * max(tests, buf.i.size)   # the arrays were full): grow, search again
        buf.i, buf.j = np.empty(size, np.uint32), np.empty(size, np.uint32)
        found, tests = _find(*args, buf.i, buf.j)
    return buf.i[:found], buf.j[:found], tests


def push_apart(xs, ys, i, j, w, dmin: float, over_relax: float, sweeps: int, between,
               buf: Buffers) -> None:
    """`sweeps` sweeps of self-collision's Jacobi projection over the pairs (i, j), in place on
    xs, ys, calling between() before each (the obstacles' projection, or None)."""
    even = _same(w)                                     # every particle free, the same weight
    if even:
        fx, fy = buf.pushes.get(xs.dtype, (None, None))
        if fx is None or fx.size < i.size:
            size = i.size + i.size // 2
            fx, fy = buf.pushes[xs.dtype] = np.empty(size, xs.dtype), np.empty(size, xs.dtype)
        dmin = xs.dtype.type(dmin)                      # (the pushes in the positions' precision)
        tiny = xs.dtype.type(1e-6 * float(dmin))        # (a pair at one point: _push_even)
    for sweep in range(sweeps):
        if between is not None:
            between()
        if even:
            _push_same(xs, ys, i, j, dmin, tiny, sweep == 0, float(over_relax), buf.count,
                       buf.scale, buf.moved, fx, fy)
        else:
            _push(xs, ys, i, j, w, float(dmin), sweep == 0, float(over_relax), buf.count,
                  buf.scale, buf.moved)
