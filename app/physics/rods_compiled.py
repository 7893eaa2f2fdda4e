"""The rods' Gauss-Seidel sweeps compiled with numba: an optional path behind Cloth.relax (the
cloth's param `kernel`, "numpy" by default; the HUD names the kernel in use).

Why a compiled kernel at all: NumPy solves a batch of rods with a dozen array operations, each a
separate pass over memory and a separate call (~1-2 us). On a 32 x 32 cloth a sweep is 8 batches
of ~500 rods, so the calls, not the arithmetic, set the cost; on a 128 x 128 cloth the dozen
passes do. A compiled loop does each rod once, in registers, and gets within reach of C.

Why numba (not Cython, not a C extension): it compiles this very Python at run time, so nothing
is built when the lab is installed and a machine without it loses nothing but this option; it is
a well-kept NumFOCUS project with wheels for every platform the lab runs on. It is optional:
`pip install numba` (requirements-dev.txt lists it); without it the kernel is refused with a
one-line message.

The arithmetic is rods.solve_batch's, written per rod (the slide's loop), batch after batch in
the same order, in the cloth's precision:

    delta = x2 - x1;  diff = 1 - rest/|delta|
    x1 += delta * diff * ka;  x2 -= delta * diff * kb
"""

from __future__ import annotations

import importlib.util

import numpy as np

from app.ctrl_c import compiled
from app.physics.rods import EPS, Batch

# optional: the lab runs without it, and imports it (~0.5 s) only when the kernel is first used
numba = importlib.util.find_spec("numba")

KERNELS = ("numpy", "numba")


def available() -> bool:
    """True if numba can be imported here."""
    return numba is not None


def why_not() -> str:
    """One line for a refusal: why the numba kernel cannot run here."""
    return "the numba kernel needs numba (pip install numba); use kernel=numpy"


def _sweeps(x, meta, rest, ka, kb, iterations):     # compiled by numba on first use
    X, Y = x[0], x[1]
    eps = X.dtype.type(EPS)
    one = X.dtype.type(1.0)
    for _ in range(iterations):
        for b in range(meta.shape[0]):
            r0, nr, rs, c0, nc, cs, dr, dc, k = meta[b]
            rst = rest[b]
            for i in range(nr):
                ra = r0 + i * rs
                rb = ra + dr
                for j in range(nc):
                    ca = c0 + j * cs
                    cb = ca + dc
                    dx = X[rb, cb] - X[ra, ca]
                    dy = Y[rb, cb] - Y[ra, ca]
                    length = max(np.sqrt(dx * dx + dy * dy), eps)
                    diff = one - rst / length
                    dx *= diff
                    dy *= diff
                    X[ra, ca] += dx * ka[k]
                    Y[ra, ca] += dy * ka[k]
                    X[rb, cb] -= dx * kb[k]
                    Y[rb, cb] -= dy * kb[k]
                    k += 1


def _make():
    import numba as nb
    return nb.njit(cache=True, nogil=True)(_sweeps)


# made on first use, and that first call (the compile) with Ctrl-C held back: app/ctrl_c.py
_kernel = compiled(_make)


class CompiledPlan:
    """The sweep's plan (a list of (batch, rest)) packed for the kernel: one row of ints per
    batch (first rod's row, rows, row step, first column, columns, column step, the rod's
    (dr, dc), where its weights start) and the weights ka, kb of every batch end to end. The
    weights are copied again when they change (pins, grabs, tears): `refresh()`."""

    def __init__(self, plan: list[tuple[Batch, float]], dtype: type):
        meta, start = [], 0
        for bt, _ in plan:
            (ra, ca), (rb, cb) = bt.a, bt.b
            nr, nc = bt.alive.shape
            meta.append((ra.start, nr, ra.step or 1, ca.start, nc, ca.step or 1,
                         rb.start - ra.start, cb.start - ca.start, start))
            start += nr * nc
        self.batches = [bt for bt, _ in plan]
        self.meta = np.array(meta, dtype=np.int64).reshape(-1, 9)
        self.rest = np.array([rest for _, rest in plan], dtype=dtype)
        self.ka = np.empty(start, dtype)
        self.kb = np.empty(start, dtype)
        self.refresh()

    def refresh(self) -> None:
        """Copy every batch's current weights into the packed arrays."""
        if self.batches:
            np.concatenate([bt.ka.ravel() for bt in self.batches], out=self.ka)
            np.concatenate([bt.kb.ravel() for bt in self.batches], out=self.kb)

    def relax(self, x: np.ndarray, iterations: int) -> None:
        """`iterations` sweeps over the plan's batches, in place on x (2, rows, cols)."""
        _kernel(x, self.meta, self.rest, self.ka, self.kb, iterations)
