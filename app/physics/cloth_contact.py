"""Contact for the Verlet cloth: obstacles, friction, tunnelling and self-collision, as passes.

The cloth's step (app/physics/cloth.py) is: Verlet, then `iterations` sweeps over the rods. The
contact passes run after the sweeps, each a separate function, chosen once by the effects that
are on (`contact_passes`): an effect that is off is not in the list, so the step never calls it.

    Verlet step
    rod sweeps
    self_collision        pairs of particles closer than `self_distance` (not joined by a rod)
                          are pushed apart to that distance: Breen's repulsion written as a
                          constraint, projected like a rod that may only grow
    collisions            each obstacle in turn: tunnelling caught (a particle whose path in
                          this substep went through it, or came in from outside further than
                          its half width: it may be past its middle, is put back where it
                          entered it: app/physics/tunnelling.py), then every particle inside it
                          is moved to its surface (Jakobsen's projection). Only the particles
                          whose path's box meets the obstacle's box are looked at (a broad
                          phase), and the distance and normal of their ends are computed once
                          for both tests. After this pass no free particle is inside an
                          obstacle, unless two obstacles overlap around it (then
                          `penetration_max` says how deep)
    friction              Coulomb: the sliding x - x_prev loses at most mu x the correction
                          (then, where two obstacles meet, the touching particles are projected
                          once more)

Why project once, after the sweeps: the step must end with nothing inside, so the last pass is a
projection. Jakobsen projects inside every sweep (his loop satisfies the collision constraints
and the rods in turn, `iterations` times), so that the rods are relaxed around particles that are
already outside; that costs one projection per sweep (10 at the defaults). One projection at the
end leaves the rods next to a contact stretched, for one step, by what the particles moved into
the obstacle in that step (g h^2 = 0.27 px for a cloth resting on it at 60 Hz), and the next
step's sweeps relax them. Measured: the penetration stays under 0.5 px at the end of every step
at the defaults and Coulomb's slope test still sticks exactly when tan(a) < mu
(tests/test_cloth_contact.py); with the cheaper sweep test, the contact passes of a 64 x 64
cloth on three obstacles cost half or less of what a projection and friction before and after
the sweeps did. Each obstacle's paths are tested and its particles projected in one go (one
broad phase, one distance evaluation, the tangent bound of tunnelling.through_one):
app/physics/cloth_obstacles.py, which says what else it leaves out. What is left is some 160
NumPy calls a substep (the box's distance and normal ~35, the ball's ~12, the tunnelling test
~15, Coulomb's rule ~25), on 1,000 to 1,900 particles each in the heap below, each a pass over
its arrays: calls and their arrays, not a Python loop. As a share of the step (the goal: at
most 30 %), in `python -m app bench cloth` (medians of 101 interleaved rounds, 2026-11-26, the
lab machine shared, load 2.6-4.8; eight runs, each beside a run of the pass as it was in the
same minutes): heap 24.3-31.1 %, median of the runs 26.6 % (before 28.1-31.8 %, 29.6 %);
hanging 21.9-26.1 % (before 24.3-29.1 %); of the fastest rounds, heap 22.3-25.4 % (before
26.2-28.4 %). At load 0.7-2.0 (three more runs each): heap 24.0, 24.4, 27.2 % (before 28.7,
29.3, 30.4 %), hanging 22.0-23.7 % (before 25.0-27.2 %). In one process, the two passes
taking turns in the same steps (201 rounds, load 3.4): 323 -> 270 us a step on the heap
(collisions 257 -> 223, friction 66 -> 47), 323 -> 273 hanging; the same positions to the
last bit. The heap's share is NOT robustly under 25 %: what is left is the passes' NumPy calls
themselves. What was measured on the way, and what was tried and not kept (x and y as (2, k)
arrays: neutral; their fancy indexing, a[:, ids], is 4 to 5 times slower than a row's; work
arrays kept for the path boxes and masks: no faster), is in `git log
app/physics/cloth_contact.py app/physics/cloth_obstacles.py`.

Self-collision needs the pairs closer than the minimum distance: the particle dance's neighbour grid
finds them (app/physics/neighbours.py, fine_pairs: cells self_distance/8 wide and /2 high), or all
pairs, the O(n^2) reference (`self_method`). Pairs of one grid cell (its sides and diagonals) and
pairs joined by a rod of an active set are left out: the rods keep them apart, and a cell may shear
freely (as it does without self-collision). Before each of its sweeps the obstacles are projected
(if on: self_obstacles.py), so a pair resting on a floor is parted by moving the upper particle, not
by pushing the lower one in. All pairs found are pushed apart at once (Jacobi: each particle moves
by the average of its pairs' corrections, times OVER_RELAX, so a particle in many pairs is not
thrown out), SELF_SWEEPS times, reusing the pairs found.

What the pair search costs, and what was chosen. The grid is sorted once per substep (a radix sort
of 16-bit cell keys), each pair met once (the half stencil), and a pair of rod neighbours is told by
one table read (close_ij, _joined). The pairs go through a Verlet neighbour list
(app/physics/self_list.py: the pairs within self_distance plus a skin, filtered instead of searched
while no particle has moved half the skin): it pays where the cloth lies still (the fold card's pass
0.29 -> 0.17 ms, a settled 64 x 64 heap 3.9 -> 3.0 ms), not on a crumpled cloth still falling (12-22
px a step against 6.4 px: a plain search every step). On that cloth (17,924 pairs closer than 6.4
px, 14,037 not rod neighbours) cells self_distance wide gave ~64,000 candidates, the finer cells
with their stencil trimmed to the circle give 34,826. The work arrays are kept (neighbours.Scratch)
or small: a fresh 264 kB cell table a call made the allocator hand pages back and fault them in
again (~104 minor page faults, ~0.26 ms a pass; now 0-2). `python -m app bench cloth` (15
consecutive steps, CPU time): 1.26 x the step crumpled on 2026-11-26 (load 1.1; 1.58 x before that
day's changes), 1.08 and 1.09 x on 2026-11-27 (load 0.6-0.8; the day before's code 1.27 and 1.24 x,
in turns; hanging 0.33-0.37 x): NOT met by NumPy crumpled. Later that day the list backs off where
it never pays (self_list.py: no displacement test or copy for 4 substeps after 2 too fast; 2 % of
the crumpled pass, 4-6 % of the hanging one): the bench's self-collision rows, four runs taking
turns with the code before (41 rounds, load 0.9-1.4), crumpled 1.02-1.11 x (before 1.03-1.09 x:
within the noise of the runs), hanging 0.32-0.34 x (0.35-0.38 x); the whole `bench cloth`, twelve
runs each taking turns with the code before (load 1.4-3.8): crumpled 0.97-1.25 x, median 1.025
(before 0.99-1.14 x, median 1.015), hanging 0.30-0.36 x (0.31-0.46 x). At the line, NOT robustly
met. There the ~1.0 ms go to the search ~0.5, the rod filter and the list ~0.1, the 2 sweeps ~0.35
(each one's four bincounts over 14,037 weighted entries the largest part). What 2026-11-27 gained
(each measured in one process against the commit before, the pass over the bench's 15 steps in
101-201 interleaved rounds, load 0.6-3.4; the same positions to the last bit): the arrays' own
methods, a.take, a.repeat (np.take and the like go through a Python wrapper: ~1.2 us a call, ~6 %);
the mask's indices and two takes, not a.compress twice (3 x faster alone, ~4 %); the run's particle
by its index, so i needs no gather through the sort after the search (~4 %); four bincounts over j
and i instead of two over [j, j + n] and [i, i + n] (no 4m index array, ~3 %); the sweeps' 1/2 share
and the coincident test done once, the obstacles projected only when a particle is near one (~4 %).
Tried and not kept: cells R/8 x R/3 or R/4 (fewer candidates, more runs: no faster), fewer cells per
particle (more candidates), blocks over 8,192 candidates (np.repeat's fresh arrays cross glibc's 128
kB: page faults again), blocks of 4,096 (1.03-1.06 x), one repeat of the (owner, first) pairs of a
run (1.04 x: its 16-byte rows cross 128 kB again), the candidates as running sums of their steps
(np.cumsum) instead of np.repeat (15 % faster alone, 0-5 % inside the step), x and y as one complex
number in the sweeps (4 % faster once, 1.02 x on 2026-11-27), the rod filter fused into the search,
read on the sorted positions (1.03 x), int32 index arrays in the search (1.15 x crumpled, 1.6 x
hanging: take and repeat cast int32 indices to intp, a pass each), np.add.at instead of bincount
(1.05 x), a sparse matrix (scipy CSR) for the sweeps' scatter (its mat-vec: 35 us against bincount's
80 alone, but building it from the pairs needs a sort of 2 x 14,037 ends by particle, 112 us a
substep for two sweeps). After the step's own work the pass waits on memory: an operation costs 2-4
x inside the step what it costs alone (the cell table's bincount and cumsum: 18 us alone, ~86 us in
the step), so fewer passes over fewer bytes, not fewer operations, is what counts. The compiled pass
(kernel=numba, optional, app/physics/self_compiled.py: the same grid and pairs, searched every
substep, no list) visits each candidate once and runs with the compiled step (kernel=numba compiles
the rods too: 0.35 ms, not 0.89): 0.88-0.91 x that step crumpled, median 0.90 (four whole bench runs
taking turns with the code before, which gave 1.42-1.50 x; load 5.5-9.2), 0.33-0.35 x hanging: MET
with kernel=numba. Its search, sort, sweeps and what was tried on them: self_compiled.py's
docstring; its figures before (1.33 x on 2026-11-27, load 1.1): git log.

Later on 2026-11-27, the NumPy search itself (neighbours.fine_pairs; the same pairs in the same
order, the same positions to the last bit): the cell table made by one repeat over the gaps between
the sorted cells, not a bincount and a cumsum over its ~30,000 cells (a cumsum waits on its last sum
at every cell: 4x slower alone); one repeat of each run's (owner, first) as two int32s, not two
repeats; all of the crumpled cloth's ~29,000 candidates in one block (not blocks of 8,192: fewer
calls); the table and the repeat's array held until the next search (minor page faults of a crumpled
pass ~9 -> 0). In the step (the bench's 15 steps, 30 rounds, five runs in turns with the code
before, load 4.9-5.2; medians): the search 670 -> 621 us, the crumpled pass 1,116 -> 1,065 us (-5
%); hanging 429-448 -> 374-397 us (three runs). The bench's rows (the whole contact bench, four runs
each in turns, load 4.6-6.0): crumpled 1.11-1.23 x (before 1.10-1.20 x: within the noise), hanging
0.38-0.42 x (0.43-0.44 x). The goal is still NOT met by NumPy crumpled. What is left is work per
element: the search's candidates (~10 passes over each), the rod filter (~0.07 ms) and the sweeps
(~0.3 ms, half of it their bincounts). Not kept: the sweeps' x and y as one complex number again
(one gather per end: the sweeps 301-341 us, without it 297-303 us); two bincounts over [j, j + n]
and [i, i + n] again, written into kept arrays with no 4m array built (each bin the same sum: the
sweeps 363-409 us, the four bincounts 327-348 us, load 5.7); blocks of 16,384-32,768 candidates
(~100 page faults a pass, the pass ~10 % slower); the cell table's cumsum down the columns of a
column-major table (vectorised, but its lookups then cost more: the table and lookups 200 -> 170 us
alone, where the repeat makes the table in 29 us against bincount and cumsum's ~100 us).

Measured later still on 2026-11-27 (the bench's crumpled state, load 0.3-1.3), nothing kept: after
the first sweep 85-91 % of the pairs are still closer than self_distance, so a second sweep over
those alone saves at most ~18 us, what compressing i and j costs alone (21 us); the search's pairs
are grouped by i only within each stencil row (7,873 runs of 3,880 particles), and np.add.reduceat
takes 70 us alone where bincount takes 19. Neither the step nor the pass calls a BLAS product, exp
or hypot here: with NumPy's AVX-512 loops off (NPY_DISABLE_CPU_FEATURES) the step is 7-14 % shorter
and the pass the same (0.88-0.96 ms, default 0.91-0.93); OPENBLAS_CORETYPE=Prescott changes neither.
Nor is it the step before that makes the pass's operations dearer than alone: the pass run again at
once on the same positions costs what it did after the step (929-958 us both times), fine_pairs
alone in a loop 460-560 us, its share in the step: most likely the pass's own other work evicts its
arrays (the cell table and its lookups: 37 us alone in a loop, 46-50 us after the cloth's 10 rod
sweeps, 63-81 us after a 32 MB pass). By perf, np.repeat is 19 % of fine_pairs alone (a branch per
run); each candidate's run found without it (a cumsum of the jumps at the runs' starts, two takes):
11-15 % slower. SELF_SWEEPS = 1 (OVER_RELAX 1.5-2.0): the pass over the bench's 15 steps only 1-5 %
shorter (more pairs stay close), 1.5-3.3 x as many pairs left closer than 95 % of self_distance (120
steps; self_distance 0.5-1, iterations 2-50, substeps 1 and 4), the fold card 8-24 at the end, not
0; at 2.0 tests/test_self_list.py fails (its heap's list reused 5 times, not over 10): 2 sweeps
kept. Also not faster (the same positions; noise +-1.5 %): the cell table in int16, |d|^2 in dp's
bytes, _push_out without project's arrays, the rod filter reading the table only where j - i is an
offset's (25 %); in fine_pairs alone (1.00-1.02 x), the runs' rows with int64 halves, or with the
owner's position in them (16 bytes: no gather of it). Nor a sweep's four bincounts as one sparse
product B^T W (scipy's CSC array, made once a substep: column k holds +1 at j_k and -1 at i_k; W the
pairs' x and y corrections): alone 78 us against 136 (27,233 pairs), but the bench's crumpled pass
took 1.00-1.04 ms against 0.89-0.95 (three bench runs each, in turns, load 0.5-1.0).

Last on 2026-11-27 (the pass over the bench's 15 steps against the code before, in turns in one
process, 61 rounds, medians, load 0.6-0.8; the same positions to the last bit in all five states),
kept: the obstacles' look before a sweep told from the particles' extremes (1-4 reductions, not ~8
passes), none before the second while every particle was further from them than a sweep moves one
(OVER_RELAX x self_distance: each push at most self_distance, averaged, times OVER_RELAX); the
weights' evenness and movable mask asked when the weights change. Crumpled 0.95-0.98 x (12 runs,
median 0.97), hanging 1.00, settled 0.98, fold card 0.99 x; `bench cloth` crumpled 0.98 and 1.03 x
(main between them: 1.06 x; load 0.6-1.0), NOT robustly met. Not kept: the search's d = x_j - x_i
carried to sweep 1 (split by the rod filter 1.03-1.04 x, complex and read strided 1.01-1.03 x,
through hits[kept] 1.00 x: gathers from 16 kB arrays are cheap); a run's (owner, first) split by a
mask and a shift of int64 rows, the rod table kept negated (1.00 x each). Then (crumpled, 61 rounds,
load 0.1-0.4) not kept: a sweep's scatter as one bincount a coordinate over [j, i] (made once a
pass; the i ends' weights negated): 1.035, 1.036 x; the search's extremes to the first look, its
cumsum and cells: self_obstacles.py, neighbours.py. In the step (timers, load 0.2): the search ~545
us, rod filter and list ~95, count and scale ~37, the two sweeps ~280 (8 bincounts ~106).

Evening of 2026-11-27, kept: a sweep adds each end's corrections as one complex number x + i y
(np.add.at, np.subtract.at: one scatter an end for x and y; above, add.at a coordinate and complex
gathers beside bincounts were not faster), and fine_pairs' takes into kept arrays in mode "wrap".
The pass on the bench's 15 crumpled states, the same inputs for both (41 rounds in turns, load
0.6-0.7): 0.90 x the code before. Float32 sums depend on their order (a step of a coordinate, grown
to pixels within 15 steps of a crumpled heap): tests/test_self_list.py compares the list and a plain
search pass by pass. Not kept: |d| by np.abs, ~4 % faster, as hypot's last bit varies with the CPU.

Settled on the floor at 1 substep (400 steps) the crumpled cloth is crushed: a 2D heap ~4 x too
dense for its particles' discs, ~47,000 of ~52,000 pairs still too close (the HUD says so and what
to try), the pass ~2.9-3.0 x the step. Its weight presses the layers together faster than 2 sweeps a
substep part them; at 3 substeps it stands (~2,900 still close): the goal's row, 0.81 x the step,
compiled 0.75 x (2026-11-27, load 0.6; app/bench/cloth_contact.py says how measured).

Self-collision is discrete, like the projection without the sweep test: a particle that moves more
than about self_distance in one substep can pass between two particles of another layer unseen.
Raise substeps (or lower the drop) for fast folds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from app.physics.neighbours import Scratch, all_pair_blocks, fine_pairs
from app.physics.self_list import PairList
from app.physics.self_list import close_pairs as listed_pairs
from app.physics.cloth_obstacles import Touched, may_touch, settle_corners, tunnel_and_project
from app.physics.friction import slide_back
from app.physics.self_obstacles import push_out as _push_out
from app.physics.obstacles import Obstacle, project

CONTACT_EFFECTS = ("collisions", "friction", "self_collision")
MARGIN = 0.25          # px: particles are pushed this far outside a surface (drawn lines touch it)
TOLERANCE = 1.0        # px: a path deeper than this through an obstacle counts as tunnelling
                       # (only paths longer than tunnelling.shortest_dip can: slow particles
                       # cost nothing)
OVERLAP_SLACK = 0.05   # self_overlaps counts pairs closer than 95% of self_distance
SELF_SWEEPS = 2        # Jacobi passes over the self-collision pairs per substep
SELF_DISTANCE = 0.8    # default minimum distance between particles, in rod lengths (spacings):
                       # below ~0.7 the weight of a layer presses it into the gaps of the one below
SELF_METHODS = ("grid", "all_pairs")
OVER_RELAX = 1.5       # Jacobi's averaged corrections times this (successive over-relaxation):
                       # a layer resting on another is held at 0.98 of self_distance, not 0.955
# rod offsets (|dr|, |dc|) of each set: such pairs are joined by a rod, never pushed apart
ROD_OFFSETS = {"structural": ((0, 1), (1, 0)), "shear": ((1, 1),), "bending": ((0, 2), (2, 0))}


@dataclass
class ContactState:
    """What the contact passes read and keep: the settings (obstacles, mu, self_distance in px,
    self_method) and what they found (contacts now, tunnelled paths so far, self pairs)."""

    obstacles: list[Obstacle] = field(default_factory=list)
    mu: float = 0.5
    self_distance: float = 8.0
    self_method: str = "grid"
    margin: float = MARGIN
    tolerance: float = TOLERANCE
    contacts: Touched | None = None       # what the last projection touched
    touching: np.ndarray | None = None    # particles that touched an obstacle in the last substep
    tunneled: int = 0                     # paths caught passing through an obstacle, since build
    self_pairs: int = 0                   # pairs pushed apart in the last self-collision pass
    self_tests: int = 0                   # pair tests the last search (or list filter) took
    start: np.ndarray | None = None       # positions at the start of the substep, (2, n)
    crowded: bool = False                 # two obstacles meet (then corners are settled)
    joined_key: tuple | None = None       # (rows, cols, rod sets) the table below was made for
    joined_at: tuple | None = None        # self-collision's rod-neighbour table (_joined)
    compiled: object = None               # the numba pass's buffers (self_compiled.Buffers)
    scratch: Scratch = field(default_factory=Scratch)   # the grid's work arrays (fine_pairs)
    self_list: PairList = field(default_factory=PairList)   # the grid's Verlet list (self_list)
    touch_key: tuple | None = None        # the obstacles' bounds when `crowded` was last asked
    touch_value: bool = False
    weights_of: tuple | None = None       # (cloth.free, all w equal and > 0, free > 0)
    pushed: bool = False                  # self-collision's last look found particles near one


Pass = Callable[["Cloth", float], None]   # noqa: F821 (the Cloth of app/physics/cloth.py)


def contact_passes(on: set[str], obstacles: list) -> tuple[list[tuple[str, Pass]],
                                                            list[tuple[str, Pass]]]:
    """(before the sweeps, after the sweeps): the passes the effects that are on need, with the
    names their cost is measured under. Collisions without obstacles are no pass at all. Every
    contact pass runs after the sweeps (the module docstring says why); `before` stays empty."""
    before: list[tuple[str, Pass]] = []
    after: list[tuple[str, Pass]] = []
    if "self_collision" in on:
        after.append(("self_collision", self_collide))
    if "collisions" in on and obstacles:
        after.append(("collisions", collide))
        if "friction" in on:
            after.append(("friction", rub_and_settle))
    return before, after


def _points(a: np.ndarray) -> np.ndarray:
    """The (n, 2) view of a (2, rows, cols) array: writing into it moves the cloth."""
    return a.reshape(2, -1).T


# ----- obstacles --------------------------------------------------------------------------------
def collide(c, h: float) -> None:
    """After the sweeps, each obstacle in turn (Jakobsen's loop over the constraints): paths
    through it over the whole substep are put back where they entered it, then every particle
    inside it is projected to its surface: app/physics/cloth_obstacles.py, which says how
    it stays cheap."""
    st, x = c.contact, _points(c.x)
    st.start = c.x_prev.reshape(2, -1)          # where each particle began this substep (a view)
    st.contacts = tunnel_and_project(st, st.start, x, c.free.ravel() > 0)
    st.touching = st.contacts.mask
    st.crowded = len(st.obstacles) > 1 and may_touch(st)
    if st.crowded:
        settle_corners(st, x)


def rub(c, h: float) -> None:
    """Coulomb friction on the last projection's contacts (app/physics/obstacles.py)."""
    st = c.contact
    t = st.contacts
    if t.ids.size and st.mu > 0:
        slide_back(_points(c.x), _points(c.x_prev), t.ids, t.nx, t.ny, t.depth,
                   lambda: t.index, st.mu, st.obstacles, h)


def rub_and_settle(c, h: float) -> None:
    """Friction after the last projection, then, where obstacles meet, the touching particles
    projected once more. (Moving along the surface of one convex obstacle never enters it: the
    obstacle lies behind the tangent line. But it can enter a neighbouring one: a table top
    and its leg.)"""
    rub(c, h)
    st = c.contact
    ids = st.contacts.mask.nonzero()[0] if st.crowded else ()
    if len(ids):
        x = _points(c.x)
        sub = x[ids].copy()
        project(st.obstacles, sub, st.margin)
        x[ids] = sub


# ----- self-collision ---------------------------------------------------------------------------
def close_pairs(c, distance: float, method: str) -> tuple[np.ndarray, ...]:
    """(i, j, dx, dy, r2, tests): pairs of particles closer than `distance` (flat indices, each
    pair once), not joined by a rod of an active set, with d = x_j - x_i and |d|^2."""
    i, j, tests = close_ij(c, distance, method)
    i, j = i.copy(), j.copy()                           # (close_ij's are work arrays)
    x = c.x.reshape(2, -1)
    dx, dy = x[0].take(j) - x[0].take(i), x[1].take(j) - x[1].take(i)
    return i, j, dx, dy, dx * dx + dy * dy, tests


def close_ij(c, distance: float, method: str) -> tuple[np.ndarray, np.ndarray, int]:
    """(i, j, tests): close_pairs without the separations (what self-collision reads: it
    measures them again in each sweep). The grid is the neighbour grid of the particle dance
    (app/physics/neighbours.py) with finer cells (fine_pairs): sorted once by cell, a half
    stencil, so each pair is met once. i and j are the contact state's work arrays (valid until
    the next search: copy them to keep them)."""
    pts = _points(c.x)
    if method == "all_pairs":
        blocks = list(all_pair_blocks(pts, distance))
        tests = len(pts) * (len(pts) - 1) // 2
        if not blocks:
            return np.zeros(0, np.intp), np.zeros(0, np.intp), tests
        i, j = np.concatenate([b.i for b in blocks]), np.concatenate([b.j for b in blocks])
    else:                                               # the grid, over the cloth's own box
        i, j, tests = fine_pairs(pts[:, 0], pts[:, 1], distance, c.contact.scratch)
    keep = np.logical_not(_joined(c, i, j), out=c.contact.scratch.get("keep", i.size, bool))
    kept = keep.nonzero()[0]                            # (faster than i.compress(keep))
    scratch = c.contact.scratch
    return (i.take(kept, out=scratch.get("pair_i", kept.size, np.intp), mode="wrap"),
            j.take(kept, out=scratch.get("pair_j", kept.size, np.intp), mode="wrap"), tests)


def joined_table(c) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(plus, minus, table): pair (i, j) is never pushed apart (a cell's sides and diagonals,
    |dr|, |dc| <= 1, or a rod of an active set) where table[plus[j] - minus[i]] is True. Each
    particle carries the number row * W + col with W = 2 cols, so k_j - k_i = dr W + dc tells
    (dr, dc) apart (|dc| < cols) and one table read per pair answers; it replaces
    `(|row_i - row_j|, |col_i - col_j|) in joined`. Made again when the rod sets change."""
    key = (c.rows, c.cols, tuple(rs.name for rs in c.active_sets))
    st = c.contact
    if st.joined_key != key:
        offsets = {(0, 1), (1, 0), (1, 1)} | {o for rs in c.active_sets
                                              for o in ROD_OFFSETS[rs.name]}
        # (only offsets the cloth holds: two rows have no (2, 0) rods, and their offset would
        # fall past the table's end)
        offsets = {(dr, dc) for dr, dc in offsets if dr < c.rows and dc < c.cols}
        w = 2 * c.cols
        row, col = np.divmod(np.arange(c.rows * c.cols), c.cols)
        reach = (c.rows - 1) * w + c.cols - 1          # the largest |k_j - k_i|
        table = np.zeros(2 * reach + 1, bool)
        for dr, dc in offsets:
            for sr in (1, -1):
                for sc in (1, -1):
                    table[reach + sr * dr * w + sc * dc] = True
        st.joined_key, st.joined_at = key, (row * w + col + reach, row * w + col, table)
    return st.joined_at


def _joined(c, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """True where particles i and j are never pushed apart (joined_table), pair by pair."""
    plus, minus, table = joined_table(c)
    scratch = c.contact.scratch
    k = plus.take(j, out=scratch.get("joined_k", j.size, np.intp), mode="wrap")
    k -= minus.take(i, out=scratch.get("joined_i", i.size, np.intp), mode="wrap")
    return table.take(k, out=scratch.get("joined", j.size, bool), mode="wrap")


def self_collide(c, h: float) -> None:
    """Push every pair closer than self_distance apart to that distance, each end by its share
    w_i / (w_i + w_j) of the overlap (a pinned end does not move), averaged per particle."""
    st = c.contact
    if c.kernel == "numba" and st.self_method == "grid":
        return _self_collide_compiled(c)
    if st.self_method == "grid":        # through a Verlet list (app/physics/self_list.py)
        key = ("grid", c.rows, c.cols, tuple(rs.name for rs in c.active_sets), st.self_distance,
               c.x.dtype)
        i, j, st.self_tests = listed_pairs(st.self_list, c.x.reshape(2, -1), st.self_distance,
                                           key, lambda d: close_ij(c, d, "grid"), st.scratch)
    else:
        i, j, st.self_tests = close_ij(c, st.self_distance, st.self_method)
    st.self_pairs = len(i)
    if len(i) == 0:
        return
    x = c.x.reshape(2, -1)
    xs, ys = x[0], x[1]                                 # views: writing moves the cloth
    w = c.w.ravel()
    # every particle free with the same weight (nothing pinned or grabbed: the usual case):
    # every share is 1/2, with no weights to read pair by pair (asked, with the movable mask,
    # when the weights change: the cloth's update_weights makes a new `free` each time)
    if st.weights_of is None or st.weights_of[0] is not c.free:
        st.weights_of = (c.free, bool(w[0] > 0 and w.min() == w.max()), c.free.ravel() > 0)
    even, movable = st.weights_of[1:]
    if not even:
        wi, wj = w.take(i), w.take(j)
        total = wi + wj
        if not total.all():                             # both ends pinned: nothing to move
            ok = total > 0
            i, j, wi, wj, total = i[ok], j[ok], wi[ok], wj[ok], total[ok]
        even = bool(np.array_equal(wi, wj))             # equal weights at both ends, all pairs
    n, m = xs.size, i.size
    # each sweep adds every particle's corrections up, x and y at once as one complex number
    # x + i y (in the positions' precision: the module docstring says why): + share_j of d
    # times the overlap at the j ends, - share_i of it at the i ends; they replace `for pair:
    # x[j] += share_j * move; x[i] -= share_i * move`. Both ends free (w = 1 each, the usual
    # case): both shares are 1/2, one set of weights.
    scratch = st.scratch
    share_j, share_i = (None, None) if even else (wj / total, wi / total)
    count = np.bincount(j, minlength=n)                # pairs per particle
    count += np.bincount(i, minlength=n)
    cplx = np.complex64 if x.dtype == np.float32 else np.complex128     # x + i y
    # Jacobi's average, over-relaxed (complex, with no imaginary part: `moved *= scale` then
    # scales x and y alike with no cast); both shares 1/2: the 1/2 is taken here, once
    scale = scratch.get("scale", n, cplx)
    np.divide(OVER_RELAX / 2 if even else OVER_RELAX, np.maximum(count, 1, out=count),
              out=scale)
    z, zi, zj = (scratch.get(name, k, cplx) for name, k in (("z", n), ("zi", m), ("zj", m)))
    r, push, flag = (scratch.get(name, m, t) for name, t in (("r", x.dtype), ("push", x.dtype),
                                                             ("same", bool)))
    square = scratch.get("square", 2 * m, x.dtype)     # dx^2 and dy^2 side by side
    corr = scratch.get("corr", m, cplx)                # one end's corrections, d x overlap
    moved = scratch.get("moved", n, cplx)
    dmin = st.self_distance
    floor_too = "collisions" in c.on and st.obstacles      # resting on an obstacle: see below
    # how far every particle is from the obstacles' bounds, less what the sweeps since can have
    # moved it (OVER_RELAX x dmin each: the module docstring): a look only where not > 0
    clear = -math.inf
    for sweep in range(SELF_SWEEPS):
        clear -= OVER_RELAX * dmin * 1.001
        if floor_too and not clear > 0:
            # a pair pushed apart on an obstacle pushes its lower particle into it; projecting
            # before each sweep lets the upper one take the whole correction, as on a floor
            clear = _push_out(st, x.T, movable)
        # d = x_j - x_i for every pair (kept arrays; a.take: np.take's wrapper costs ~1 us)
        z.real, z.imag = xs, ys
        d = np.subtract(z.take(j, out=zj, mode="wrap"), z.take(i, out=zi, mode="wrap"), out=zj)
        # |d| = sqrt(dx^2 + dy^2) (not np.abs(d): the module docstring says why)
        np.square(d.view(x.dtype), out=square)
        np.sqrt(np.add(square[0::2], square[1::2], out=r), out=r)
        if r.min() < 1e-6 * dmin:       # at one point: as if 1e-6 dmin apart along x (dmin's
            same = np.less(r, 1e-6 * dmin, out=flag)     # overlap, not dmin - 1 px or none)
            d[same], r[same] = 1e-6 * dmin, 1e-6 * dmin
        np.subtract(dmin, r, out=push)                  # the overlap, per unit of d
        np.maximum(push, 0.0, out=push)
        push /= r
        f_j, f_i = (push, push) if even else (push * share_j, push * share_i)
        moved.fill(0)
        np.add.at(moved, j, np.multiply(d, f_j, out=corr))          # + at the j ends
        if not even:
            np.multiply(d, f_i, out=corr)
        np.subtract.at(moved, i, corr)                               # - at the i ends
        moved *= scale
        xs += moved.real
        ys += moved.imag


def _self_collide_compiled(c) -> None:
    """self_collide's pass as one compiled loop over the candidates and one per sweep
    (app/physics/self_compiled.py: the cloth's kernel "numba"); the same grid, the same pairs."""
    from app.physics import self_compiled
    st, x = c.contact, c.x.reshape(2, -1)
    dmin, n = st.self_distance, x.shape[1]
    if st.compiled is None or st.compiled.count.size != n:
        st.compiled = self_compiled.Buffers(n)
    i, j, st.self_tests = self_compiled.find_pairs(x[0], x[1], dmin, joined_table(c),
                                                   st.compiled)
    st.self_pairs = len(i)
    if len(i) == 0:
        return
    between = None
    if "collisions" in c.on and st.obstacles:          # as in self_collide: before each sweep
        movable = c.free.ravel() > 0
        between = lambda: _push_out(st, x.T, movable)    # noqa: E731
    self_compiled.push_apart(x[0], x[1], i, j, c.w.ravel(), dmin, OVER_RELAX, SELF_SWEEPS,
                             between, st.compiled)


def self_overlaps(c, distance: float, method: str = "grid", slack: float = OVERLAP_SLACK) -> int:
    """Pairs closer than (1 - slack) x distance, cell and rod neighbours left out (95% of it by
    default: a layer resting under the weight of another sits at about 98%): what self-collision
    did not (yet) resolve, or, with it off, how much the cloth lies on itself."""
    return int(len(close_ij(c, distance * (1 - slack), method)[0]))
