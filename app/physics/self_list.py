"""A Verlet neighbour list for the cloth's self-collision: the pairs found once, then reused.

The technique comes from molecular dynamics: Verlet kept, for each particle, the list of its
neighbours within the cut-off plus a margin, and searched again only every few steps (L. Verlet,
"Computer 'experiments' on classical fluids. I", Phys. Rev. 159, 98, 1967; M. P. Allen and
D. J. Tildesley, "Computer Simulation of Liquids", section 5.3, with the displacement test used
here). For self-collision, with R = self_distance and a skin s:

    build:   the pairs closer than R + s (the grid's search, close_ij), and every particle's
             position x0 at that moment;
    reuse:   while every particle has moved less than s / 2 since (|x - x0| < s / 2 for all:
             one subtract, square and max over the positions), the pairs closer than R are
             those of the list closer than R: a filter, not a search.

Why it is exact: a pair not in the list was at least R + s apart at the build; each end has
moved less than s / 2, so they are still more than R + s - s / 2 - s / 2 = R apart. The filter
computes |x_j - x_i|^2 with the same float operations as the search (so the same pairs, not
only to rounding), and the test keeps a margin of 1e-4 of R + s for the rounding of the
distances themselves. The displacement is measured, not predicted: a mouse drag, a restore of a
snapshot, a particle put back by the tunnelling test all count. The list is also rebuilt when
anything else that decides which pairs count changes (its `key`: the cloth's size, R, the active
rod sets whose neighbours are left out, the method, the positions' precision). Tearing does not:
the pairs left out are those of the rod sets (torn rods included), not of the intact rods.

When does it pay? Only when the list lasts: each build searches R + s (more candidates, more
pairs to filter later) and each reuse filters the whole list. So the skin is chosen at each
build: SKIN x R again if the last list was reused at least once; after a plain search, if the
fastest particle moved slowly enough that the list would last LIFE substeps; else none (a
plain search, exactly the pass without a list, plus one displacement test and one copy of the
positions a substep: 0.013 ms at 4,096 particles, 1-3 % of the pass).
Measured (20 consecutive steps from the bench's states, one substep each, CPU ms of the pass
per step, load 1.6; skin 0 is the pass without a list):

    state                            pairs    skin 0   0.5 R   0.75 R  1 R    builds (0.75 R)
    fold card (0.25 px a step)         195     0.29    0.16    0.17    0.17   2 of 20
    64 x 64 heap settled (step 400)  54200     3.88    3.88    3.04    3.17   2 of 20
    64 x 64 crumpled, falling         6-14k    1.14    1.12    1.14    1.13   20 of 20
    64 x 64 hanging, swinging            0     0.38    0.39    0.35    0.36   18 of 20

(0.5 R on the heap: its fastest particles move ~1 px a step, so LIFE's test never tries it.)
The crumpled cloth falling onto the floor (the bench's goal state) has particles moving 12-22
px a step, 8-16 px relative to the whole cloth's fall, against R = 6.4 px: no skin short of
~3 R lasts one step, and without the gate a skin only adds to the search (0.25-1 R: 1.57-2.74
ms a step, rebuilt every step). There the list is a plain search, as before.

Back-off: where the list never pays, its displacement test and its copy of the positions still
cost something every substep. After MISSES plain searches in a row whose particles were too fast
for a skin, the next WAIT substeps search with neither; the next test then measures the speed
over all of them (x0 is kept), so a cloth that comes to rest gets its list at most WAIT
substeps late (after lists that did not pay, up to COOL_MAX: below). Measured on 2026-11-27
(the bench's runs of 15 steps, 31 and 41 interleaved rounds in one process against WAIT = 0,
load 1.6-1.9; the same positions to the last bit): the crumpled cloth's pass 1.9-2.1 % shorter,
the hanging cloth's 4-6 %.

A list that did not pay: in the crumpled 64 x 64 cloth settled on the floor at 1 substep (`bench
cloth`'s "crumpled, crushed" row: ~52,000 pairs, the median particle 0.01 px a step, 6-13 of the
4,096 shaking 1-2.3 px a step back and forth: 20 steps from step 400, 2026-11-27) the fastest
particle's net move over the back-off's substeps is small, so a skin was tried every ~7
substeps, and no such list outlived a substep: ~40 searches over R + skin in 300 steps (the
grid's search alone: 2.75 ms over R + skin, ~143,000 pairs, against 1.11 ms over R; load 0.5).
Now a list built with a skin and never reused starts a back-off of COOL substeps, twice as long
after each such list in a row (up to COOL_MAX), and a list reused at least once resets it;
nothing else does (a fast fall, a key change, a restore of a snapshot in between keep it).
Measured on 2026-11-27 (one process, the two versions taking turns, five runs of 60 steps each,
load 0.8; the same positions to the last bit): the settled heap's pass 3.03 -> 2.75 ms (6
skinned builds in one run of 300 steps, not ~40; five runs of 60 from a fresh list make 3 each,
3.32 -> 3.10 ms, load 0.9; a plain search every step: 2.57 ms); the falling crumpled cloth 1.21
-> 1.19, the fold card 0.129 -> 0.130, the hanging cloth 0.260 -> 0.256 ms (their lists as
before in those runs). The price, over a whole run: in the crumpled 64 x 64 cloth from step 0
the list was reused from step ~777 on, when the cloth had settled; now it waits out a back-off
of 256 that began at step ~745, until step ~1000 (reused 236 times in 1,000 steps before, 37
now). Measured on 2026-11-27 (one process, the versions taking turns, three runs each): the pass
over steps 780-1000 2.57 -> 2.71 ms (load 2.6-3.2), over steps 0-1000 2.88 -> 2.62 ms (load 0.9;
with COOL_MAX = 32: reused 200 times, 2.71 ms); the same positions to the last bit.

The compiled pass (kernel=numba, app/physics/self_compiled.py) does not use the list: its
search is one loop over the candidates (~0.1 ms of a 0.33 ms pass on the crumpled cloth,
2026-11-27, load 4-7), and where the list pays (a cloth lying still) it would save a fraction
of that.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from app.physics.neighbours import Scratch

SKIN = 0.75         # the skin, in self_distances (chosen by measurement: the table above)
LIFE = 2            # after a plain search, a skin only if the list would last this many substeps
ROUNDING = 1e-4     # of R + s: kept back from s / 2 for the rounding of distances (float32)
MISSES = 2          # after this many plain searches in a row whose particles were too fast...
WAIT = 4            # ...the next WAIT substeps search with no displacement test and no copy
COOL = 8            # after a list built with a skin and never reused, the next COOL substeps
COOL_MAX = 256      # search with no test (no skin tried); twice as many after each such list
                    # in a row, up to COOL_MAX

Search = Callable[[float], tuple[np.ndarray, np.ndarray, int]]


@dataclass
class PairList:
    """The list (pairs i, j closer than R + skin at the build), the positions at the build and
    what it has cost: builds and reuses since the cloth was made."""

    key: tuple | None = None
    skin: float = 0.0                   # px; 0: the last build was a plain search
    x0: np.ndarray | None = None        # (2, n) positions at the build
    i: np.ndarray | None = None
    j: np.ndarray | None = None
    age: int = 0                        # substeps since the build (since x0)
    misses: int = 0                     # plain searches in a row whose particles were too fast
    wait: int = 0                       # substeps left without a displacement test (back-off)
    cool: int = COOL                    # the next back-off after a list that did not pay
    builds: int = 0
    reuses: int = 0
    store: Scratch = field(default_factory=Scratch)     # the list's own arrays (kept)


def moved(lst: PairList, x: np.ndarray) -> float:
    """The largest distance any particle has moved since the build, squared (px^2); NaN or inf
    for a cloth that has blown up (then the list is rebuilt: the search decides)."""
    d = lst.store.get("d", x.size, x.dtype).reshape(x.shape)
    with np.errstate(invalid="ignore", over="ignore"):          # (inf - inf, a huge square)
        np.subtract(x, lst.x0, out=d)
        np.square(d, out=d)
        return float(np.add(d[0], d[1], out=d[0]).max(initial=0.0))


def close_pairs(lst: PairList, x: np.ndarray, distance: float, key: tuple, search: Search,
                scratch: Scratch) -> tuple[np.ndarray, np.ndarray, int]:
    """(i, j, tests): the pairs closer than `distance`, as search(distance) finds them (as a
    set; their order may differ), from the list while it is valid, else from a new search
    (with a skin if the particles have been moving slowly enough). x: the positions (2, n).
    tests: the pair distances computed (the list's length when it was filtered). i and j are
    work arrays, valid until the next call."""
    skin = 0.0
    if lst.key == key and lst.x0 is not None and lst.x0.shape == x.shape:
        lst.age += 1
        if lst.wait > 0:                # backing off: a plain search, x0 kept (so the next
            lst.wait -= 1               # test measures the speed over all these substeps)
            lst.builds += 1
            return search(distance)
        far = moved(lst, x)
        limit = lst.skin / 2 - ROUNDING * (distance + lst.skin)
        if lst.skin > 0 and far < limit * limit:
            lst.reuses += 1
            return within(lst.i, lst.j, x, distance, scratch)
        if lst.skin > 0:                # a list that was reused at least once: again; one
            lasted = lst.age > 1        # that never was: back off, longer each time
            if lasted:
                lst.cool = COOL
            else:
                lst.wait, lst.cool = lst.cool, min(2 * lst.cool, COOL_MAX)
        else:                           # after a plain search: if the particles moved slowly
            lasted = math.sqrt(far) / lst.age * LIFE < SKIN * distance / 2
            lst.misses = 0 if lasted else lst.misses + 1
            if lst.misses >= MISSES:    # too fast again and again: back off
                lst.wait = WAIT
        skin = SKIN * distance if lasted else 0.0
    i, j, tests = search(distance + skin)
    lst.key, lst.skin, lst.age = key, skin, 0
    lst.builds += 1
    lst.x0 = _kept(lst.store, "x0", x)
    if skin == 0:
        return i, j, tests
    lst.i, lst.j = _kept(lst.store, "i", i), _kept(lst.store, "j", j)
    return within(lst.i, lst.j, x, distance, scratch)[:2] + (tests,)


def _kept(store: Scratch, name: str, a: np.ndarray) -> np.ndarray:
    """A copy of `a` in the store's array `name` (kept between builds: no fresh memory)."""
    out = store.get(name, a.size, a.dtype).reshape(a.shape)
    np.copyto(out, a)
    return out


def within(i: np.ndarray, j: np.ndarray, x: np.ndarray, distance: float, scratch: Scratch
           ) -> tuple[np.ndarray, np.ndarray, int]:
    """(i, j, tests): the pairs of (i, j) closer than `distance`, |x_j - x_i|^2 computed as the
    grid's search computes it (neighbours.fine_pairs: in the positions' precision, x then y),
    so a pair is kept exactly when the search would find it."""
    m, real = i.size, x.dtype
    dx = np.subtract(x[0].take(j, out=scratch.get("list_xj", m, real), mode="wrap"),
                     x[0].take(i, out=scratch.get("list_xi", m, real), mode="wrap"),
                     out=scratch.get("list_dx", m, real))
    dy = np.subtract(x[1].take(j, out=scratch.get("list_xj", m, real), mode="wrap"),
                     x[1].take(i, out=scratch.get("list_xi", m, real), mode="wrap"),
                     out=scratch.get("list_dy", m, real))
    r2 = np.add(np.square(dx, out=dx), np.square(dy, out=dy), out=dx)
    hit = np.less(r2, real.type(distance * distance), out=scratch.get("list_hit", m, bool))
    kept = hit.nonzero()[0]                             # (faster than i.compress(hit))
    return (i.take(kept, out=scratch.get("list_i", kept.size, np.intp), mode="wrap"),
            j.take(kept, out=scratch.get("list_j", kept.size, np.intp), mode="wrap"), m)
