"""Rods on a grid, batched for Gauss-Seidel sweeps: the Verlet cloth's constraints (and the
mass-spring cloth's spring families, which are the same pairs of grid neighbours).

How NumPy makes it fast (the slide loops over particle objects in Python):
  * the state is grid-shaped: x has shape (2, rows, cols); x[0] holds every particle's x, x[1]
    every y, and x[:, r, c] is particle (r, c);
  * a *family* of rods joins every particle (r, c) to (r + dr, c + dc), e.g. (0, 1) = horizontal;
  * a family is split into *batches* in which no two rods share a particle (horizontal rods from
    even columns, then from odd columns). A batch is two strided slices of x, e.g.
    x[:, :, 0:-1:2] and x[:, :, 1::2], solved at once; batch after batch is still a true
    Gauss-Seidel sweep, because each batch sees the corrections of the ones before it;
  * a torn rod stays in its batch with `alive` = 0 folded into its correction weight, so tearing
    changes numbers, not array shapes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Iterator

import numpy as np

EPS = 1e-9                                      # shortest length we divide by (no 0/0)
SET_NAMES = ("structural", "shear", "bending")  # rod sets, in the order a sweep solves them

Slices = tuple[slice, slice]


# ----- the rods ---------------------------------------------------------------------------------
@dataclass
class Batch:
    """Rods of one family that share no particle: solved together in one array operation."""

    a: Slices                  # rows/cols of the first particle of every rod (into an (R, C) grid)
    b: Slices                  # ... and of the second
    alive: np.ndarray          # view into the family's alive mask (1 = intact, 0 = torn)
    ka: np.ndarray = None      # alive * w_a / (w_a + w_b): share of the correction moving a
    kb: np.ndarray = None      # alive * w_b / (w_a + w_b)
    d: np.ndarray = None       # work buffers (no allocation inside the sweep)
    t: np.ndarray = None
    length: np.ndarray = None
    cells: Slices = None       # where this batch's rods sit in the family's grid

    @property
    def xa(self) -> tuple[slice, slice, slice]:
        return (slice(None),) + self.a

    @property
    def xb(self) -> tuple[slice, slice, slice]:
        return (slice(None),) + self.b


@dataclass
class Family:
    """All rods joining particle (r, c) to (r + dr, c + dc), with one rest length."""

    name: str
    offset: tuple[int, int]
    rest: float
    a: Slices                  # the whole family as two slices (for metrics and tearing)
    b: Slices
    alive: np.ndarray          # shape of the family grid, 1.0 intact / 0.0 torn
    batches: list[Batch] = field(default_factory=list)
    rest_now: np.ndarray | None = None   # per-rod rest lengths while easing in (see set_effects)

    def rest_of(self, cells: Slices) -> float | np.ndarray:
        """The rest length the solver uses now for the batch at `cells`: `rest`, or while the
        family eases in, the per-rod values."""
        return self.rest if self.rest_now is None else self.rest_now[cells]


@dataclass
class RodSet:
    """A named set of rod families (structural, shear, bending): one effect, one cost line."""

    name: str
    families: list[Family]
    sweeps: int = 0            # how many times this set was swept (tests check 'off' costs 0)

    @property
    def count(self) -> int:
        return sum(int(f.alive.size) for f in self.families)


def _family(name: str, dr: int, dc: int, rows: int, cols: int, rest: float,
            dtype: type) -> Family | None:
    """The rods (r, c)-(r+dr, c+dc) of a rows x cols grid, split into particle-disjoint batches.

    Batches: rods along a row (dr = 0) are split by column modulo 2*dc, all others by row modulo
    2*dr; rods whose index differs by that modulus never share a particle."""
    n_rows, n_cols = rows - dr, cols - abs(dc)
    if n_rows <= 0 or n_cols <= 0:
        return None
    a0c = max(0, -dc)                       # column of particle a of rod (0, 0)
    a = (slice(0, n_rows), slice(a0c, a0c + n_cols))
    b = (slice(dr, dr + n_rows), slice(a0c + dc, a0c + dc + n_cols))
    fam = Family(name, (dr, dc), rest, a, b, np.ones((n_rows, n_cols), dtype))
    axis, m = (1, 2 * dc) if dr == 0 else (0, 2 * dr)
    n = (n_rows, n_cols)[axis]
    for k in range(min(m, n)):
        sa, sb, sf = list(a), list(b), [slice(None), slice(None)]
        sa[axis] = slice(a[axis].start + k, a[axis].stop, m)
        sb[axis] = slice(b[axis].start + k, b[axis].stop, m)
        sf[axis] = slice(k, n, m)
        fam.batches.append(Batch(tuple(sa), tuple(sb), fam.alive[tuple(sf)], cells=tuple(sf)))
    return fam


# rod families of each set: (name, dr, dc, rest length in spacings)
FAMILIES = {"structural": [("horizontal", 0, 1, 1.0), ("vertical", 1, 0, 1.0)],
            "shear": [("diagonal", 1, 1, math.sqrt(2.0)), ("antidiagonal", 1, -1, math.sqrt(2.0))],
            "bending": [("horizontal skip-one", 0, 2, 2.0), ("vertical skip-one", 2, 0, 2.0)]}


def rod_sets(rows: int, cols: int, spacing: float, dtype: type = np.float32) -> dict[str, RodSet]:
    """The three rod sets of a grid cloth with the given spacing."""
    sets = {}
    for name, fams in FAMILIES.items():
        built = [_family(fname, dr, dc, rows, cols, rest * spacing, dtype)
                 for fname, dr, dc, rest in fams]
        sets[name] = RodSet(name, [f for f in built if f is not None])
    return sets


def sweep_size(rows: int, cols: int, set_names: tuple[str, ...] = SET_NAMES) -> tuple[int, int]:
    """(rods, batches) of one sweep over the named sets, without building anything: what one
    sweep costs is about rods x (a few ns) + batches x (a NumPy call overhead of ~10 us)."""
    rods = batches = 0
    for name in set_names:
        for _, dr, dc, _ in FAMILIES[name]:
            n_rows, n_cols = rows - dr, cols - abs(dc)
            if n_rows > 0 and n_cols > 0:
                rods += n_rows * n_cols
                batches += min(2 * dc, n_cols) if dr == 0 else min(2 * dr, n_rows)
    return rods, batches


def solve_order(rows: int, cols: int, set_names: tuple[str, ...]
                ) -> Iterator[tuple[tuple[int, int], tuple[int, int], str]]:
    """Every rod as ((r1, c1), (r2, c2), set name) in the order one vectorised sweep solves them
    (batch by batch). The per-object version uses it, so both do exactly the same arithmetic."""
    sets = rod_sets(rows, cols, 1.0, np.float64)
    for name in set_names:
        for fam in sets[name].families:
            for bt in fam.batches:
                ra, ca = (range(s.start, s.stop, s.step or 1) for s in bt.a)
                rb, cb = (range(s.start, s.stop, s.step or 1) for s in bt.b)
                for r1, r2 in zip(ra, rb):
                    for c1, c2 in zip(ca, cb):
                        yield (r1, c1), (r2, c2), name


def solve_batch(x: np.ndarray, bt: Batch, rest: float) -> None:
    """Satisfy every rod of one batch at once (Jakobsen's constraint step, vectorised):

        delta = x2 - x1;  diff = (|delta| - rest) / |delta|
        x1 += delta * diff * w1/(w1+w2);  x2 -= delta * diff * w2/(w1+w2)

    The loop it replaces: `for rod in batch: ...` with the same three lines per rod."""
    xa, xb = x[bt.xa], x[bt.xb]                   # views: writing into them moves the particles
    d = np.subtract(xb, xa, out=bt.d)             # delta, shape (2, ...)
    np.multiply(d, d, out=bt.t)
    length = np.add(bt.t[0], bt.t[1], out=bt.length)
    np.sqrt(length, out=length)
    np.maximum(length, EPS, out=length)           # two particles at one point: no 0/0
    diff = np.divide(rest, length, out=length)
    np.subtract(1.0, diff, out=diff)              # diff = 1 - rest/|delta| = (|delta|-rest)/|delta|
    d *= diff                                     # delta * diff: the whole error
    xa += np.multiply(d, bt.ka, out=bt.t)         # each end takes its share (0 if pinned or torn)
    xb -= np.multiply(d, bt.kb, out=bt.t)


def rod_lengths(x: np.ndarray, fam: Family) -> np.ndarray:
    """|x_b - x_a| for every rod of a family, in the family's grid shape."""
    d = x[(slice(None),) + fam.b] - x[(slice(None),) + fam.a]
    return np.sqrt(d[0] * d[0] + d[1] * d[1])
