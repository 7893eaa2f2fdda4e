"""Self-collision compiled with numba: an optional path behind cloth_contact.self_collide, taken
when the cloth's `kernel` is "numba" (the rods' option, app/physics/rods_compiled.py; off by
default, named in the HUD). The physics is the NumPy pass's, written per pair (the slide's loop):

    find the pairs closer than self_distance (a grid of cells at least that wide, each pair
    once: a particle's own cell after it and 4 of its 8 neighbours, the half stencil), leaving
    out pairs joined by a rod of an active set or a cell's sides and diagonals;
    SELF_SWEEPS times: every pair pushed apart to self_distance, each end by its share
    w / (w_i + w_j), every particle moved by the average of its pairs' pushes x OVER_RELAX.

Why: the NumPy pass costs about 25 array operations per candidate pair and per pair found (sort,
runs of candidates, distances, the rod table, gathers, bincounts); on a crumpled 64 x 64 cloth
(some 65,000 candidates, 15,000 pairs) that is about twice the whole step without it, however
the operations are fused (`python -m app bench cloth`). A compiled loop visits each candidate
once, in registers. The pairs are the same; positions agree with the NumPy pass to rounding.
"""

from __future__ import annotations

import numpy as np

from app.ctrl_c import compiled


def _find_pairs(xs, ys, lo_x, lo_y, scale_x, scale_y, nx, ny, r2_max, row, col, joined,
                out_i, out_j):     # compiled by numba on first use
    """(pairs found, candidate tests): pairs closer than sqrt(r2_max) into out_i, out_j; if
    they have fewer than tests + 1 places, nothing is searched and found is -1 (the caller
    grows them and asks again). row, col: each particle's place in the cloth's grid."""
    n = xs.size
    cell = np.empty(n, np.int64)
    cell_x = np.empty(n, np.int64)
    cell_y = np.empty(n, np.int64)
    count = np.zeros(nx * ny + 1, np.int64)
    for p in range(n):                                  # 1. each particle's cell
        cell_x[p] = min(max(int(np.floor((xs[p] - lo_x) * scale_x)), 0), nx - 1)
        cell_y[p] = min(max(int(np.floor((ys[p] - lo_y) * scale_y)), 0), ny - 1)
        cell[p] = cell_y[p] * nx + cell_x[p]
        count[cell[p] + 1] += 1
    for c in range(nx * ny):                            # 2. sorted by cell (a counting sort)
        count[c + 1] += count[c]
    start = count[:-1].copy()
    fill = start.copy()
    order = np.empty(n, np.int64)                       # sorted copies: a cell's particles
    sx, sy = np.empty_like(xs), np.empty_like(ys)       # side by side in memory
    s_row, s_col = np.empty_like(row), np.empty_like(col)
    for p in range(n):
        k = fill[cell[p]]
        order[k], sx[k], sy[k], s_row[k], s_col[k] = p, xs[p], ys[p], row[p], col[p]
        fill[cell[p]] += 1
    # 3. candidates, the half stencil: the rest of its own cell, the cell to its right, the
    # three below; first only counted (the output must hold them all: see below)
    first = np.empty((n, 5), np.int64)
    last = np.empty((n, 5), np.int64)
    tests = 0
    for k in range(n):
        p = order[k]
        cx, cy = cell_x[p], cell_y[p]
        first[k, 0], last[k, 0] = k + 1, count[cell[p] + 1]
        for oc in range(1, 5):
            ox, oy = (1, 0) if oc == 1 else (oc - 3, 1)   # right; below-left, below, right
            qx, qy = cx + ox, cy + oy
            if qx < 0 or qx >= nx or qy >= ny:
                first[k, oc] = last[k, oc] = 0
            else:
                first[k, oc], last[k, oc] = start[qy * nx + qx], count[qy * nx + qx + 1]
        for oc in range(5):
            tests += last[k, oc] - first[k, oc]
    if out_i.size < tests + 1:
        return -1, tests
    # every candidate is written and `found` steps on only for a close pair that no rod joins:
    # no branch to mispredict (half the candidates are close: an `if` cost more than the test)
    found = 0
    for k in range(n):
        p, px, py, pr, pc = order[k], sx[k], sy[k], s_row[k], s_col[k]
        for oc in range(5):
            for s in range(first[k, oc], last[k, oc]):
                dx, dy = sx[s] - px, sy[s] - py
                dr, dc = min(abs(pr - s_row[s]), 3), min(abs(pc - s_col[s]), 3)
                out_i[found], out_j[found] = p, order[s]
                found += (dx * dx + dy * dy < r2_max) & ~joined[dr * 4 + dc]
    return found, tests


def _push_apart(xs, ys, i, j, w, dmin, over_relax, sweeps_done, moved_x, moved_y, count):
    """One Jacobi sweep over the pairs (count: pairs per particle, filled on the first)."""
    n, m = xs.size, i.size
    for p in range(n):
        moved_x[p] = 0.0
        moved_y[p] = 0.0
    for k in range(m):
        a, b = i[k], j[k]
        total = w[a] + w[b]
        if total <= 0:
            continue                                    # both pinned: neither moves
        if sweeps_done == 0:
            count[a] += 1
            count[b] += 1
        dx, dy = xs[b] - xs[a], ys[b] - ys[a]
        r = np.sqrt(dx * dx + dy * dy)
        if r < 1e-6 * dmin:                             # at one point: part them along x
            dx, r = 1.0, 1.0
        push = max(dmin - r, 0.0) / (r * total)         # the overlap per unit of d, / total
        mx, my = dx * push, dy * push
        moved_x[b] += mx * w[b]                         # each end its share w / (w_a + w_b)
        moved_y[b] += my * w[b]
        moved_x[a] -= mx * w[a]
        moved_y[a] -= my * w[a]
    for p in range(n):
        if count[p] > 0:
            xs[p] += moved_x[p] * (over_relax / count[p])
            ys[p] += moved_y[p] * (over_relax / count[p])


def _jit(fn):
    """fn compiled by numba on its first call (with Ctrl-C held back: app/ctrl_c.py)."""
    def make():
        import numba as nb
        return nb.njit(cache=True, nogil=True)(fn)
    return compiled(make)


_find = _jit(_find_pairs)
_push = _jit(_push_apart)


class Buffers:
    """What the compiled pass keeps between steps: the pair arrays (grown when a step finds
    more pairs than they hold) and the per-particle sums."""

    def __init__(self, n: int):
        self.i = np.empty(4 * n, np.int64)
        self.j = np.empty(4 * n, np.int64)
        self.moved_x = np.empty(n)
        self.moved_y = np.empty(n)
        self.count = np.zeros(n, np.int64)
        self.row = self.col = np.zeros(0, np.int64)     # each particle's (row, column)
        self.cols = 0
        self.joined_key: tuple | None = None            # the rod sets `joined` was made for
        self.joined = np.zeros(16, bool)


def find_pairs(xs, ys, grid, distance: float, cols: int, joined: np.ndarray,
               buf: Buffers) -> tuple[np.ndarray, np.ndarray, int]:
    """(i, j, tests): the pairs closer than `distance`, not joined (joined: the (16,) table,
    (|dr|, |dc|) capped at 3), on the grid (lo_x, lo_y, nx / width, ny / height, nx, ny)."""
    lo_x, lo_y, sx, sy, nx, ny = grid
    if buf.row.size != xs.size or buf.cols != cols:
        buf.row, buf.col = np.divmod(np.arange(xs.size), cols)
        buf.cols = cols
    args = (xs, ys, xs.dtype.type(lo_x), ys.dtype.type(lo_y), xs.dtype.type(sx),
            ys.dtype.type(sy), nx, ny, xs.dtype.type(distance) ** 2, buf.row, buf.col, joined)
    found, tests = _find(*args, buf.i, buf.j)
    if found < 0:                                       # more than ever before: grow, again
        buf.i, buf.j = np.empty(2 * tests + 1, np.int64), np.empty(2 * tests + 1, np.int64)
        found, tests = _find(*args, buf.i, buf.j)
    return buf.i[:found], buf.j[:found], tests


def push_apart(xs, ys, i, j, w, dmin: float, over_relax: float, sweep: int,
               buf: Buffers) -> None:
    """One sweep of self-collision's Jacobi projection, in place on xs, ys."""
    if sweep == 0:
        buf.count[:] = 0
    _push(xs, ys, i, j, w, float(dmin), float(over_relax), sweep, buf.moved_x, buf.moved_y,
         buf.count)
