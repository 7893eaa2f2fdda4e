"""Grader of exercises/neighbour_grid.py: the particle dance's cell grid, the pairs within a
cut-off found without testing all pairs.

Reference: app.physics.neighbours.grid_pairs (the particle dance's grid); the pairs it must find
are those of app.physics.neighbours.all_pairs (every pair tested). Each measure sends back the
pairs (i, j) and the test count the student's grid_pairs returned; each judge compares them, as
sets of unordered pairs, with all pairs closer than the cut-off:
  random           400 particles spread over a 600 x 400 box, cut-off 40
  clustered        five tight clusters of 60 (many particles in one cell) and 50 strays
  on the borders   a lattice 0.97 cut-offs apart laid over cell borders and the box's edges
                   (x = 0, x = w, y = h included), and pairs exactly one cut-off apart (not
                   pairs: |d| < cut-off)
  few particles    0, 1 and 2 particles: no pairs, no error
  pair tests       2000 particles at the particle dance's density (its box's area, 960 x 720,
                   stretched to 1440 x 480: a grid cut with w and h swapped shows), cut-off 40:
                   the count of tests the function reports must be the candidate count of a cell
                   grid on these particles, which the grader computes itself (GRIDS below: the
                   starter's cells floor(w / R) with 3 x 3, cells R, R/2 or R/3 wide searched 1,
                   2 or 3 cells around; each pair once or both ways, with or without itself).
                   Why this and not a count the student could invent: see the comment at GRIDS
A miss or an extra is named: pairs across a cell border missed, a particle on the far edge, a
distance test with <= or none at all, a pair given twice or a particle paired with itself.
  random boxes     4 random boxes, cut-offs and particle sets (seeded): every pair, and a grid's
                   count of tests
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import BadAnswer, Check, Exercise, Raw, Result, Student, cases_rng, counted

CUTOFF = 40.0


def reference() -> SimpleNamespace:
    from app.physics.neighbours import grid_pairs
    return SimpleNamespace(grid_pairs=grid_pairs)


# ----- the particles -----------------------------------------------------------------------------
def random_case() -> tuple[np.ndarray, float, tuple[float, float]]:
    rng = np.random.default_rng(11)
    return rng.uniform(0.0, 1.0, (400, 2)) * (600.0, 400.0), CUTOFF, (600.0, 400.0)


def clustered_case() -> tuple[np.ndarray, float, tuple[float, float]]:
    rng = np.random.default_rng(12)
    centres = rng.uniform(60.0, 540.0, (5, 2)) * (1.0, 340.0 / 540.0)
    blobs = [c + rng.normal(0.0, 8.0, (60, 2)) for c in centres]
    strays = rng.uniform(0.0, 1.0, (50, 2)) * (600.0, 400.0)
    x = np.clip(np.concatenate(blobs + [strays]), 0.0, [600.0, 400.0])
    return x, CUTOFF, (600.0, 400.0)


def border_case() -> tuple[np.ndarray, float, tuple[float, float]]:
    box = (610.0, 410.0)                 # cells of 40.67 x 41 (the grid's: box / cells)
    step = 0.97 * CUTOFF
    gx = np.concatenate([np.arange(0.0, box[0], step), [box[0]]])
    gy = np.concatenate([np.arange(0.0, box[1], step), [box[1]]])
    lattice = np.stack(np.meshgrid(gx, gy), axis=-1).reshape(-1, 2)
    cells = np.array([[k * box[0] / 15, m * box[1] / 10] for k in range(16) for m in range(11)])
    exact = np.array([[5.0, 200.0], [45.0, 200.0], [300.0, 5.0], [300.0, 45.0]])  # |d| = 40
    # pairs 39.5 apart that span a whole cell of a grid whose cells are narrower than the
    # cut-off (nx = ceil(w / R): 38.1 x 37.3) but only a border of the right one (40.7 x 41)
    narrow = np.array([[38.0, 380.0], [77.5, 380.0], [590.0, 37.0], [590.0, 76.5]])
    x = np.concatenate([lattice, cells + (0.3, 0.7), exact, narrow])
    return np.clip(x, 0.0, box), CUTOFF, box


PAIR_N, PAIR_BOX = 2000, (1440.0, 480.0)     # the dance's area (960 x 720), but 3:1


def tests_case() -> tuple[np.ndarray, float, tuple[float, float]]:
    rng = np.random.default_rng(13)
    return rng.uniform(0.0, 1.0, (PAIR_N, 2)) * PAIR_BOX, CUTOFF, PAIR_BOX


FEW = [np.zeros((0, 2)), np.array([[10.0, 10.0]]), np.array([[10.0, 10.0], [300.0, 300.0]])]


# ----- calling the student's function ------------------------------------------------------------
def pairs_of(m: Student, x: np.ndarray, cutoff: float, box) -> dict:
    out = m.grid_pairs(x.copy(), cutoff, box)
    if not isinstance(out, tuple) or len(out) != 3:
        raise BadAnswer(f"grid_pairs returned {type(out).__name__}; expected (i, j, tests)"
                        + (" (no return statement?)" if out is None else ""))
    i, j, tests = out
    try:
        ia, ja = np.asarray(i), np.asarray(j)
        if ia.size == 0:
            ia = ia.astype(np.intp)
        if ja.size == 0:
            ja = ja.astype(np.intp)
        if ia.ndim != 1 or ja.ndim != 1 or len(ia) != len(ja):
            raise ValueError
        if ia.dtype.kind not in "iu" or ja.dtype.kind not in "iu":
            raise TypeError
        if isinstance(tests, bool) or not isinstance(tests, (int, np.integer)) and not (
                isinstance(tests, (float, np.floating)) and float(tests).is_integer()):
            raise TypeError
    except (TypeError, ValueError, OverflowError):
        raise BadAnswer("grid_pairs must return (i, j, tests): two integer arrays of the same "
                        f"length (the pairs' particle indices) and an integer; got "
                        f"{described(i)}, {described(j)}, {type(tests).__name__}") from None
    count = counted(tests, "grid_pairs's tests (the third value)")
    n = len(x)
    if len(ia) and (min(ia.min(), ja.min()) < 0 or max(ia.max(), ja.max()) >= n):
        raise BadAnswer(f"grid_pairs returned particle indices outside 0..{n - 1} (from "
                        f"{min(ia.min(), ja.min())} to {max(ia.max(), ja.max())}): i and j are "
                        "rows of x, not cell numbers or coordinates")
    return {"i": ia.astype(np.int64), "j": ja.astype(np.int64), "tests": count}


def described(value) -> str:
    """What a returned value is, for a message: 'ndarray of float64 (12,)', 'list (3,)'."""
    try:
        arr = np.asarray(value)
        return f"{type(value).__name__} of {arr.dtype} {arr.shape}"
    except (TypeError, ValueError):
        return type(value).__name__


def measure_case(case):
    def measure(m: Student) -> dict:
        return pairs_of(m, *case())
    return measure


# ----- judging: the pairs as sets ----------------------------------------------------------------
def true_pairs(x: np.ndarray, cutoff: float) -> set[tuple[int, int]]:
    from app.physics.neighbours import all_pairs
    i, j, _ = all_pairs(x, cutoff)
    return {(int(p), int(q)) for p, q in zip(np.minimum(i, j), np.maximum(i, j))}


def compare(raw: Raw, x: np.ndarray, cutoff: float, box) -> tuple[bool, str, str]:
    """(passed, measured text, hint) for the pairs sent against all pairs within the cut-off."""
    n = len(x)
    i, j = raw.array("i", (None,), dtype=np.int64), raw.array("j", (None,), dtype=np.int64)
    if len(i) != len(j):
        return False, "i and j of different lengths", "return two arrays, one entry per pair"
    if len(i) and (min(i.min(), j.min()) < 0 or max(i.max(), j.max()) >= n):
        return False, f"indices outside 0..{n - 1}", "i and j are particle indices (0..n-1)"
    want = true_pairs(x, cutoff)
    lo, hi = np.minimum(i, j), np.maximum(i, j)
    got = list(zip(lo.tolist(), hi.tolist()))
    seen = set(got)
    self_pairs = int((lo == hi).sum())
    twice = len(got) - len(seen)
    missed = want - seen
    extra = {p for p in seen - want if p[0] != p[1]}
    measured = (f"{len(seen - {(k, k) for k in range(n)})} pairs found of {len(want)}: "
                f"{len(missed)} missed, {len(extra)} too many, {twice} twice, {self_pairs} with "
                "itself")
    ok = not missed and not extra and not twice and not self_pairs
    kept = [math.dist(x[p], x[q]) for p, q in seen & want]
    reach = max(kept, default=0.0)           # the farthest pair found within the cut-off
    return ok, measured, "" if ok else hint_for(x, cutoff, box, missed, extra, twice, self_pairs,
                                                reach)


def hint_for(x, cutoff, box, missed, extra, twice, self_pairs, reach=math.inf) -> str:
    hints = []
    if self_pairs:
        hints.append("a particle is paired with itself: in its own cell, pair it only with the "
                     "particles after it")
    if twice:
        hints.append("a pair comes twice ((i, j) and (j, i), or from two cells): each pair once, "
                     "e.g. own cell with the ones after it plus half the neighbours (right, and "
                     "the row below), or keep only i < j")
    if extra:
        d = [math.dist(x[p], x[q]) for p, q in extra]
        if all(abs(v - cutoff) < 1e-9 for v in d):
            hints.append(f"pairs exactly {cutoff:g} apart are not within the cut-off: "
                         "|d| < cutoff, not <=")
        else:
            hints.append(f"pairs farther apart than the cut-off (up to {max(d):.3g}): a shared or "
                         "neighbouring cell is only a candidate; test |x_j - x_i| < cutoff")
    if missed:
        from app.physics.neighbours import grid_shape
        nx, ny = grid_shape(box, cutoff)
        cell = np.stack([np.clip(np.floor(x[:, 0] * nx / box[0]), 0, nx - 1),
                         np.clip(np.floor(x[:, 1] * ny / box[1]), 0, ny - 1)], axis=1)
        steps = {tuple(np.abs(cell[q] - cell[p]).astype(int)) for p, q in missed}
        def edge(p: int) -> bool:
            return bool(x[p, 0] >= box[0] - 1e-9 or x[p, 1] >= box[1] - 1e-9)
        if all(edge(p) or edge(q) for p, q in missed):
            hints.append("a particle on the far edge (x = w or y = h) falls in cell number "
                         "nx (or ny), one past the last: clamp the cell index into 0..nx-1")
        nearest_missed = min(math.dist(x[p], x[q]) for p, q in missed)
        if (0, 0) in steps and reach <= math.sqrt(cutoff) * (1 + 1e-9) < 0.9 * cutoff:
            hints.append(f"no pair farther apart than {reach:.3g} was kept, even in one cell: "
                         "the distance test is off. Keep |x_j - x_i| < cutoff (or d . d < "
                         "cutoff^2: the square on both sides)")
        elif (0, 0) in steps and reach < nearest_missed:
            hints.append(f"your pairs are exactly those closer than about {reach:.4g} (every "
                         f"pair missed is {nearest_missed:.4g} or more apart), not the cut-off "
                         f"{cutoff:.6g} the function was given: is the cut-off a fixed number in "
                         "your code (the checks and the scenes use many)? Use the argument "
                         "`cutoff` everywhere")
        elif narrow_grid(x, cutoff, box, missed):
            hints.append(narrow_grid(x, cutoff, box, missed))
        elif steps <= {(0, 0)}:
            hints.append("pairs in the same cell were missed: pair each particle with every "
                         "other particle of its own cell")
        elif steps <= {(1, 1)}:
            hints.append("only pairs across a CORNER were missed: the diagonal neighbour cells "
                         "count too (8 neighbours, or 4 in a half stencil)")
        elif (0, 0) not in steps:
            hints.append(f"{len(missed)} pairs in NEIGHBOURING cells were missed, none in one "
                         "cell: two particles closer than the cut-off may sit in neighbouring "
                         "cells, so search the 3 x 3 block of cells around each particle's cell")
        else:
            p, q = min(missed)
            hints.append(f"{len(missed)} pairs within the cut-off missed, e.g. particles {p} and "
                         f"{q}, {math.dist(x[p], x[q]):.4g} apart, at ({x[p, 0]:.4g}, "
                         f"{x[p, 1]:.4g}) and ({x[q, 0]:.4g}, {x[q, 1]:.4g})")
    return "; ".join(hints) + "."


def narrow_grid(x, cutoff, box, missed) -> str:
    """The hint if the pairs missed are exactly those two or more cells apart in a grid of cells
    narrower than the cut-off (nx = round(w / cutoff) or ceil), else ''."""
    want = true_pairs(x, cutoff)
    for count in (round, math.ceil):
        nx, ny = max(1, count(box[0] / cutoff)), max(1, count(box[1] / cutoff))
        if (nx, ny) == (max(1, int(box[0] // cutoff)), max(1, int(box[1] // cutoff))):
            continue
        cell = np.stack([np.clip(np.floor(x[:, 0] * nx / box[0]), 0, nx - 1),
                         np.clip(np.floor(x[:, 1] * ny / box[1]), 0, ny - 1)], axis=1)
        apart = {(p, q) for p, q in want if np.abs(cell[p] - cell[q]).max() > 1}
        if apart and apart == set(missed):
            return (f"the pairs missed are those two cells apart in a grid of {nx} x {ny} cells "
                    f"({box[0] / nx:.4g} x {box[1] / ny:.4g} px: w / cutoff rounded up, as round() "
                    "or ceil() do): cells "
                    f"narrower than the cut-off {cutoff:.4g}. Cells must be at least a cut-off "
                    "wide: nx = floor(w / cutoff)")
    return ""


def judge_case(case):
    def judge(raw: Raw) -> Result:
        x, cutoff, box = case()
        ok, measured, hint = compare(raw, x, cutoff, box)
        return Result(ok, measured, "every pair with |d| < cut-off, once", hint)
    return judge


def measure_few(m: Student) -> dict:
    return {str(k): pairs_of(m, x, CUTOFF, (400.0, 400.0)) for k, x in enumerate(FEW)}


def judge_few(raw: Raw) -> Result:
    problems = []
    for k, x in enumerate(FEW):
        ok, measured, _ = compare(Raw(raw.values.get(str(k))), x, CUTOFF, (400.0, 400.0))
        if not ok:
            problems.append(f"{len(x)} particles: {measured}")
    return Result(not problems, "; ".join(problems) or "no pairs, no error", "no pairs",
                  "with 0 or 1 particles there are no pairs: empty arrays (np.zeros(0, int)); "
                  "an empty cell is no error")


def block_candidates(x: np.ndarray, cutoff: float, box) -> int:
    """Particles in the 3 x 3 cells around each particle's cell (itself included), summed: the
    tests of a grid that tries every candidate of the full stencil, both ways round."""
    from app.physics.neighbours import grid_shape
    nx, ny = grid_shape(box, cutoff)
    cx = np.clip(np.floor(x[:, 0] * nx / box[0]), 0, nx - 1).astype(int)
    cy = np.clip(np.floor(x[:, 1] * ny / box[1]), 0, ny - 1).astype(int)
    count = np.zeros((ny + 2, nx + 2), int)              # a border of empty cells around
    np.add.at(count, (cy + 1, cx + 1), 1)
    block = sum(count[1 + dy:ny + 1 + dy, 1 + dx:nx + 1 + dx]
                for dx in (-1, 0, 1) for dy in (-1, 0, 1))
    return int(block[cy, cx].sum())


# ----- the count of pair tests: measured here, from the particles ---------------------------------
# The count a student's grid_pairs reports is not believed: the grader computes, from the same
# particles, the candidate count of every cell grid the starter describes or allows, and the
# reported count must be one of them exactly. Why this and not arrays that count their reads: a
# NumPy answer reads x once and computes thousands of distances by broadcasting, and np.asarray
# strips any counting wrapper, so reads say nothing about distances; a grid's candidates are
# fixed by its cells, and cells at least a cut-off wide (or a 1/k of it, searched k cells around)
# are what the starter asks for. An invented number (pairs found + 1000, a fraction of all pairs)
# lands on one of these few exact counts only by computing a grid, which is the exercise.
GRIDS = (("cells floor(w / cutoff) across, 3 x 3", "fit", 1, 1),
         ("cells exactly a cut-off wide (x // cutoff), 3 x 3", "size", 1, 1),
         ("cells half a cut-off wide, 5 x 5", "size", 2, 2),
         ("cells a third of a cut-off wide, 7 x 7", "size", 3, 3),
         ("cells floor(2 w / cutoff) across, 5 x 5", "fit", 2, 2))


def grid_cells(x: np.ndarray, cutoff: float, box, kind: str, k: float) -> np.ndarray:
    """Each particle's cell (column, row) in a grid: 'fit' (nx = floor(k w / cutoff) cells across
    the box, clamped), 'size' (cells cutoff / k wide from 0, unclamped), 'swapped' (a 'fit' grid
    that reads the box as (h, w): a mistake's)."""
    if kind in ("fit", "swapped"):
        bw, bh = box[::-1] if kind == "swapped" else box
        nx, ny = max(1, int(k * bw // cutoff)), max(1, int(k * bh // cutoff))
        return np.stack([np.clip(np.floor(x[:, 0] * nx / bw), 0, nx - 1),
                         np.clip(np.floor(x[:, 1] * ny / bh), 0, ny - 1)], 1).astype(np.int64)
    return np.floor(x / (cutoff / k)).astype(np.int64)


def stencil_counts(cells: np.ndarray, reach: int, label: str) -> dict[int, str]:
    """The counts of distance tests a grid with these cells makes when each particle meets those
    up to `reach` cells away: own-cell pairs S and neighbouring-cell pairs N (each once), counted
    once or both ways round, with or without each particle tested against itself."""
    n = len(cells)
    cells = cells - (cells.min(axis=0) - reach)            # a border of empty cells
    count = np.zeros(tuple(cells.max(axis=0) + reach + 1), np.int64)
    np.add.at(count, (cells[:, 0], cells[:, 1]), 1)
    own = int((count * (count - 1) // 2).sum())
    near = 0
    for dx in range(-reach, reach + 1):
        for dy in range(0, reach + 1):
            if dy == 0 and dx <= 0:
                continue                                  # half the stencil: each pair once
            shifted = np.roll(np.roll(count, -dx, 0), -dy, 1)
            near += int((count * shifted).sum())
    out: dict[int, str] = {}
    for o, o_text in ((own, "own cell once"), (own + n, "own cell once, itself too"),
                      (2 * own, "own cell both ways"), (2 * own + n, "own cell both ways, "
                                                        "itself too")):
        for m, m_text in ((near, "neighbours once"), (2 * near, "neighbours both ways")):
            out.setdefault(o + m, f"{label}: {o_text}, {m_text}")
    return out


def grid_counts(x: np.ndarray, cutoff: float, box, grids=GRIDS) -> dict[int, str]:
    """Every count of distance tests a grid of `grids` makes on these particles."""
    if len(x) == 0:
        return {0: "no particles"}
    out: dict[int, str] = {}
    for label, kind, k, reach in grids:
        for count, text in stencil_counts(grid_cells(x, cutoff, box, kind, k), reach,
                                          label).items():
            out.setdefault(count, text)
    return out


MISTAKEN_GRIDS = {
    "big": (("cells two cut-offs wide", "fit", 0.5, 1),),
    "swapped": (("the box read as (h, w)", "swapped", 1, 1),),
}


def mistaken_counts(x: np.ndarray, cutoff: float, box) -> dict[int, list[str]]:
    """The counts of tests of the usual mistakes on these particles, each with its hint."""
    from app.physics.neighbours import all_pair_tests, grid_shape
    nx, ny = grid_shape(box, cutoff)
    n, every = len(x), all_pair_tests(len(x))
    hints = {
        "all": "that is testing all pairs: the grid's point is to test only the particles of "
               "the 3 x 3 cells around each particle's cell",
        "swapped": f"your count is that of a grid with w and h (or x and y) swapped: nx = floor(w "
                   f"/ cutoff) = {nx} cells across, {ny} down, with box = (w, h) = ({box[0]:g}, "
                   f"{box[1]:g}); a particle's cell is (floor(x nx / w), floor(y ny / h))",
        "big": f"your count is that of cells two cut-offs wide: cells larger than the cut-off "
               f"hold more candidates; nx = floor(w / cutoff) = {nx} cells across, {ny} down"}
    out: dict[int, list[str]] = {}
    for count in {every, 2 * every, n * n}:
        out.setdefault(count, []).append(hints["all"])
    for kind in ("swapped", "big"):
        for count in grid_counts(x, cutoff, box, MISTAKEN_GRIDS[kind]):
            if hints[kind] not in out.setdefault(count, []):
                out[count].append(hints[kind])
    return out


def judge_count(x, cutoff, box, tests: int, found: int, ok_pairs: bool, measured: str,
                hint: str) -> Result:
    """The pairs and the count of tests against the counts of GRIDS on these particles."""
    from app.physics.neighbours import all_pair_tests, grid_shape
    counts = grid_counts(x, cutoff, box)
    most = block_candidates(x, cutoff, box)      # every particle of the 9 cells around each
    every = all_pair_tests(len(x))
    text = (f"{tests:,} pair tests ({100 * tests / max(every, 1):.1f}% of all {every:,} pairs)")
    lab = min(counts)
    bound = (f"the count of a cell grid's candidates: {lab:,} for the starter's grid each pair "
             f"once, {2 * lab:,} both ways (or another grid's, {len(counts)} counts in all)")
    if not ok_pairs:
        return Result(False, f"{text}; {measured}", "the right pairs; " + bound, hint)
    if tests in counts:
        return Result(True, f"{text}: {counts[tests]}", bound)
    nearest = min(counts, key=lambda c: abs(c - tests))
    nx, ny = grid_shape(box, cutoff)
    n = len(x)
    if tests <= found:
        hint = (f"{'as few tests as' if tests == found else 'fewer tests than'} pairs found "
                f"({found:,}): "
                "count every distance you compute (every candidate from the cells, also those "
                "too far apart), not only the pairs kept")
    elif tests in mistaken_counts(x, cutoff, box):
        named = mistaken_counts(x, cutoff, box)[tests]
        hint = (named[0] if len(named) == 1 else "your count matches more than one usual "
                "mistake on these particles: " + "; or ".join(named))
    else:
        hint = (f"{tests:,} is the count of no cell grid on these particles: the nearest, "
                f"{nearest:,} ({counts[nearest]}), is {abs(tests - nearest):,} away. tests is "
                "the number of distances your code computed, one per candidate pair")
    return Result(False, text, bound, hint)


def judge_tests(raw: Raw) -> Result:
    x, cutoff, box = tests_case()
    ok_pairs, measured, hint = compare(raw, x, cutoff, box)
    found = len(set(zip(raw.array("i", (None,), np.int64).tolist(),
                        raw.array("j", (None,), np.int64).tolist())))
    return judge_count(x, cutoff, box, raw.integer("tests"), found, ok_pairs, measured, hint)


# ----- random boxes, cut-offs and particles (a new seed each run) --------------------------------
RANDOM_CASES = 4


def random_cases() -> list[tuple[np.ndarray, float, tuple[float, float]]]:
    """Boxes of any shape, cut-offs that do and do not divide them (w / cutoff with a fraction of
    0.5 to 0.95 in the first: round() gives one cell too many, each narrower than the cut-off),
    from none to 500 particles, some on the edges x = 0, x = w, y = h."""
    rng = cases_rng("neighbour_grid random")
    cases = []
    for k in range(RANDOM_CASES):
        w, h = rng.uniform(80.0, 1500.0, 2)
        cells = rng.integers(1, 16) + (rng.uniform(0.5, 0.95) if k == 0 else rng.uniform())
        cutoff = float(w / cells)
        n = int(rng.integers(150, 500)) if k < 2 else int(rng.integers(0, 200))
        x = rng.uniform(0.0, 1.0, (n, 2)) * (w, h)
        for p in np.flatnonzero(rng.random(n) < 0.05):        # on an edge of the box
            axis = int(rng.integers(0, 2))
            x[p, axis] = (w, h)[axis] * int(rng.integers(0, 2))
        x = np.clip(x, 0.0, (w, h))
        cases.append((x, cutoff, (float(w), float(h))))
    return cases


def measure_random(m: Student) -> dict:
    return {str(k): pairs_of(m, *case) for k, case in enumerate(random_cases())}


def judge_random(raw: Raw) -> Result:
    for k, (x, cutoff, box) in enumerate(random_cases()):
        one = Raw(raw.values.get(str(k)))
        ok_pairs, measured, hint = compare(one, x, cutoff, box)
        found = len(set(zip(one.array("i", (None,), np.int64).tolist(),
                            one.array("j", (None,), np.int64).tolist())))
        r = judge_count(x, cutoff, box, one.integer("tests"), found, ok_pairs, measured, hint)
        if not r.passed:
            where = (f"case {k + 1} of {RANDOM_CASES}: {len(x)} particles, box "
                     f"{box[0]:.6g} x {box[1]:.6g}, cut-off {cutoff:.6g} (w / cutoff = "
                     f"{box[0] / cutoff:.3g})")
            return Result(False, f"{where}: {r.measured}", r.bound, r.hint)
    return Result(True, f"{RANDOM_CASES} random boxes and cut-offs: every pair, a grid's count",
                  "every pair with |d| < cut-off, once; a grid's count of tests")


EXERCISE = Exercise(
    name="neighbour_grid",
    title="The neighbour grid: pairs within a cut-off without testing all pairs",
    slide="Physics in Computer Animations and Games: 'Spatial forces' (forces between any pairs "
          "of particles, depending on their positions) and the particle dance's cell grid",
    functions=("grid_pairs",),
    reference=reference,
    checks=(Check("random particles", measure_case(random_case), judge_case(random_case)),
            Check("clustered particles", measure_case(clustered_case),
                  judge_case(clustered_case)),
            Check("on the cell borders", measure_case(border_case), judge_case(border_case)),
            Check("few particles", measure_few, judge_few),
            Check("pair tests", measure_case(tests_case), judge_tests),
            Check("random boxes and cut-offs", measure_random, judge_random)),
)
