"""Grader of exercises/constraints.py: Jakobsen's rod relaxation with inverse masses.

Reference: app.physics.jakobsen.satisfy_rods. Each measure sends back the positions the
student's satisfy_rods returned; each judge measures:
  pinned never move   a chain with both ends pinned (w = 0), stretched at random, and a rod
                      between the two pinned ends (skipped: w_a + w_b = 0), 20 sweeps: the
                      pinned particles move by exactly 0
  one rod, one pass   one rod of length 50, rest 20: after one sweep its length is 20 (+- 1e-9)
  squashed rod        one rod of length 10, rest 20: after one sweep its length is 20 too (a rod
                      pushes as well as pulls)
  shares by mass      the rod of length 50 with w = 1 and 3: the centre of mass (masses 1/w)
                      stays put
  each rod its rest   three rods sharing no particle, rests 20, 35, 12: one sweep satisfies
                      each exactly
  stretch falls       a hanging 6 x 6 cloth (top row pinned) for 1/3 s at 60 Hz, stepped by the
                      lab's Verlet: the mean stretch after 1, 5, 25 sweeps per step falls
  coincident          two particles at one point, rest 10: the result is finite (no 0/0)
  random rods      4 random sets of rods (seeded; pins, masses, zero-length rods, ends at one
                   point): the slide's sweeps in one of the orders of the rods, within rounding
"""

from __future__ import annotations

import itertools
import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import (Check, Exercise, Raw, Result, Student, array_of, cases_rng, fmt,
                                rounding, within)


def reference() -> SimpleNamespace:
    from app.physics.jakobsen import satisfy_rods
    return SimpleNamespace(satisfy_rods=satisfy_rods)


def relax(m: Student, x, a, b, rest, w, iterations) -> np.ndarray:
    out = m.satisfy_rods(x.copy(), a, b, rest, w, iterations)
    return array_of(out, x.shape, "satisfy_rods")


SWAPPED_HINT = ("each end moved by the OTHER end's share: x_a moves by w_a / (w_a + w_b) of the "
                "correction, x_b by w_b / (w_a + w_b) (the light end, large w, moves most; a "
                "pinned end, w = 0, not at all).")


def relax_with(kind: str, x, a, b, rest, w, iterations) -> np.ndarray:
    """The slide's sweeps with one of the usual mistakes (in the parent): 'equal shares', 'swapped
    shares', 'no share sum' (w, not w / (w_a + w_b)), 'no length' (diff not divided by |delta|),
    'no pinned skip' (0 / 0 for a rod between two pinned particles)."""
    x = np.array(x, dtype=float)
    for _ in range(iterations):
        for k in range(len(a)):
            i, j = a[k], b[k]
            total = w[i] + w[j]
            if total == 0 and kind != "no pinned skip":
                continue
            delta = x[j] - x[i]
            d = max(float(np.linalg.norm(delta)), 1e-9)
            c = delta * (d - rest[k]) / (1.0 if kind == "no length" else d)
            with np.errstate(all="ignore"):
                si, sj = ((0.5, 0.5) if kind == "equal shares" else
                          (w[i], w[j]) if kind == "no share sum" else
                          (w[j] / total, w[i] / total) if kind == "swapped shares" else
                          (w[i] / total, w[j] / total))
            x[i] += c * si
            x[j] -= c * sj
    return x


WEIGHT_HINT = ("move each end by its share w_a / (w_a + w_b) of the correction (w = 0: pinned, "
               "it never moves). Did you split it 50/50?")


# ----- pinned -----------------------------------------------------------------------------------
def chain() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(2)
    n = 8
    x = np.stack([np.arange(n) * 15.0, np.zeros(n)], axis=1) + rng.normal(0, 4, (n, 2))
    w = np.ones(n)
    w[[0, n - 1]] = 0.0
    # the chain's rods, and one between the two pinned ends: both w = 0, so it is skipped
    return x, np.append(np.arange(n - 1), 0), np.append(np.arange(1, n), n - 1), w


def measure_pinned(m: Student) -> dict:
    x, a, b, w = chain()
    return {"x": relax(m, x, a, b, np.full(len(a), 10.0), w, 20),
            "x1": relax(m, x, a, b, np.full(len(a), 10.0), w, 1)}    # where a NaN starts


def judge_pinned(raw: Raw) -> Result:
    x, a, b, w = chain()
    out = raw.array("x", x.shape)
    moved = float(np.abs(out[w == 0] - x[w == 0]).max())
    hint = (f"the pinned particles (w = 0) moved by up to {fmt(moved)} px in 20 sweeps; each "
            "end moves by its share w_a / (w_a + w_b) of the correction, 0 for w = 0.")
    if np.allclose(out, relax_with("swapped shares", x, a, b, np.full(len(a), 10.0), w, 20),
                   atol=1e-9):
        hint = SWAPPED_HINT
    elif np.allclose(out, relax_with("equal shares", x, a, b, np.full(len(a), 10.0), w, 20),
                     atol=1e-9):
        hint = "the ends share each correction 50/50, pinned or not: " + WEIGHT_HINT
    with np.errstate(all="ignore"):
        no_skip = relax_with("no pinned skip", x, a, b, np.full(len(a), 10.0), w, 1)
    first = raw.array("x1", x.shape) if raw.has("x1") else out
    if not np.isfinite(out[w == 0]).all() and np.array_equal(np.isfinite(first),
                                                            np.isfinite(no_skip)):
        hint = ("NaN at the pinned particles: a rod whose two ends are both pinned has "
                "w_a + w_b = 0, and its shares 0 / 0 are NaN. Skip such a rod (if w_a + w_b == 0: "
                "continue). " + hint)
    return Result(moved == 0.0, f"pinned particles moved {fmt(moved)} px", "0 px", hint)


# ----- one rod -----------------------------------------------------------------------------------
ROD_W = np.array([1.0, 3.0])
STRETCHED = np.array([[0.0, 0.0], [30.0, 40.0]])      # length 50
SQUASHED = np.array([[0.0, 0.0], [6.0, 8.0]])         # length 10
REST = 20.0


def measure_rod(x0: np.ndarray):
    def measure(m: Student) -> dict:
        out = {"x": relax(m, x0, np.array([0]), np.array([1]), np.array([REST]), ROD_W, 1)}
        if x0 is SQUASHED:              # and the stretched one: did one pass move anything?
            out["stretched"] = relax(m, STRETCHED, np.array([0]), np.array([1]),
                                     np.array([REST]), ROD_W, 1)
        return out
    return measure


ONE_ROD_HINT = ("one rod alone is satisfied exactly by one correction: diff = (|delta| - rest) / "
                "|delta| (divide by the length), then the ends move by delta * diff * their "
                "shares w_a / (w_a + w_b) and w_b / (w_a + w_b), which add up to 1.")


def judge_one_rod(raw: Raw) -> Result:
    out = raw.array("x", (2, 2))
    err = abs(float(np.linalg.norm(out[1] - out[0])) - REST)
    along = STRETCHED[1] - STRETCHED[0]
    length = float((out[1] - out[0]) @ along / np.linalg.norm(along))   # < 0: ends crossed
    hint = ONE_ROD_HINT
    if np.array_equal(out, STRETCHED):
        hint = ("the rod did not move in one pass (iterations = 1): does the sweep run "
                "`iterations` times? range(iterations), not range(iterations - 1).")
    elif length > 50.0 + 1e-9:
        hint = "the rod got LONGER (50 -> " + f"{length:.3g}): a sign is flipped. " + hint
    elif np.allclose(out, relax_with("no share sum", STRETCHED, [0], [1], [REST], ROD_W, 1),
                     atol=1e-9):
        hint = (f"the ends moved too far (50 px -> {length:.3g} along the old rod, rest 20; "
                "below 0 they crossed): they moved by w times the correction; did you forget "
                "to divide by w_a + w_b? " + hint)
    elif np.allclose(out, relax_with("no length", STRETCHED, [0], [1], [REST], ROD_W, 1),
                     atol=1e-9):
        hint = ("the correction is not divided by the length: diff = (|delta| - rest) / "
                "|delta|, so that delta * diff is (|delta| - rest) along the rod. " + hint)
    else:
        hint = (f"after one pass the rod is {length:.6g} px along its old direction (rest "
                f"{REST:g}, was 50). " + hint)
    return Result(within(err, 0.0, 1e-9), f"|length - rest| = {fmt(err)} px after one pass",
                  "< 1e-09 px", hint)


def judge_squashed(raw: Raw) -> Result:
    out = raw.array("x", (2, 2))
    length = float(np.linalg.norm(out[1] - out[0]))
    err = abs(length - REST)
    hint = ("a rod is a distance constraint both ways: diff = (|delta| - rest) / |delta| is "
            "negative for a squashed rod, and the same correction pushes its ends apart. " +
            ONE_ROD_HINT)
    stretched = raw.array("stretched", (2, 2))
    if within(length, 10.0, 1e-9) and np.array_equal(stretched, STRETCHED):
        hint = ("nothing moved in one pass (iterations = 1), stretched or squashed: does the "
                "sweep run `iterations` times? range(iterations), not range(iterations - 1).")
    elif within(length, 10.0, 1e-9):
        hint = ("a squashed rod stays squashed (10 px, rest 20): the correction must push apart "
                "too (no `if |delta| <= rest: continue`; that is a rope, not a rod). " + hint)
    return Result(within(err, 0.0, 1e-9), f"length {length:.6g} px after one pass (was 10)",
                  "20 +- 1e-09 px", hint)


def judge_shares(raw: Raw) -> Result:
    out = raw.array("x", (2, 2))
    mass = 1.0 / ROD_W
    before = (mass[:, None] * STRETCHED).sum(0) / mass.sum()
    after = (mass[:, None] * out).sum(0) / mass.sum()
    moved = float(np.linalg.norm(after - before))
    hint = "the heavier end (smaller w) moves less: " + WEIGHT_HINT
    delta = STRETCHED[1] - STRETCHED[0]
    correction = delta * (np.linalg.norm(delta) - REST) / np.linalg.norm(delta)
    other = STRETCHED + np.array([1.0, -1.0])[:, None] * ROD_W[::-1, None] / ROD_W.sum() * \
        correction                                    # each end moved by the other's share
    if np.allclose(out, other, atol=1e-9):
        hint = SWAPPED_HINT
    return Result(within(moved, 0.0, 1e-9), f"centre of mass moved {fmt(moved)} px",
                  "< 1e-09 px", hint)


# ----- each rod its own rest length ------------------------------------------------------------
RODS_X = np.array([[0.0, 0.0], [30.0, 40.0], [100.0, 0.0], [106.0, 8.0], [0.0, 100.0],
                   [0.0, 130.0]])                      # lengths 50, 10, 30
RODS_A, RODS_B, RODS_REST = np.array([0, 2, 4]), np.array([1, 3, 5]), np.array([20.0, 35.0, 12.0])


def measure_rests(m: Student) -> dict:
    return {"x": relax(m, RODS_X, RODS_A, RODS_B, RODS_REST, np.ones(6), 1)}


def judge_rests(raw: Raw) -> Result:
    out = raw.array("x", RODS_X.shape)
    lengths = np.linalg.norm(out[RODS_B] - out[RODS_A], axis=1)
    err = float(np.abs(lengths - RODS_REST).max())
    hint = "rod k wants its own rest length rest[k]: diff = (|delta| - rest[k]) / |delta|."
    if np.allclose(lengths, RODS_REST[0], atol=1e-9):
        hint = "every rod was given the first rod's rest length (rest[0]). " + hint
    return Result(within(err, 0.0, 1e-9), "lengths " + ", ".join(f"{v:.6g}" for v in lengths)
                  + " after one pass (rests 20, 35, 12)", "each its rest, +- 1e-09 px", hint)


# ----- a hanging cloth ---------------------------------------------------------------------------
ROWS, SPACING, SWEEPS = 6, 20.0, (1, 5, 25)


def cloth() -> tuple[np.ndarray, ...]:
    r, c = np.mgrid[0:ROWS, 0:ROWS]
    idx = r * ROWS + c
    a = np.concatenate([idx[:, :-1].ravel(), idx[:-1, :].ravel()])
    b = np.concatenate([idx[:, 1:].ravel(), idx[1:, :].ravel()])
    x = np.stack([c.ravel() * SPACING, r.ravel() * SPACING], axis=1).astype(float)
    w = np.ones(len(x))
    w[:ROWS] = 0.0                                      # the top row is pinned
    return x, a, b, np.full(len(a), SPACING), w


def measure_stretch(m: Student) -> dict:
    """The cloth after 1/3 s (the lab's Verlet, your rods) at each number of sweeps."""
    from app.physics.jakobsen import verlet_step
    out = []
    for iterations in SWEEPS:
        x, a, b, rest, w = cloth()
        acc = np.where(w[:, None] > 0, np.array([0.0, 900.0]), 0.0)
        x_prev = x.copy()
        for _ in range(20):
            x, x_prev = verlet_step(x, x_prev, acc, 1 / 60, 0.01)
            x = relax(m, x, a, b, rest, w, iterations)
        out.append(x)
    return {"x": out}


def judge_stretch(raw: Raw) -> Result:
    _, a, b, rest, _ = cloth()
    xs = raw.array("x", (len(SWEEPS), ROWS * ROWS, 2))
    s = [float(np.abs(np.linalg.norm(x[b] - x[a], axis=1) / rest - 1).mean()) for x in xs]
    ok = bool(np.all(np.isfinite(s)) and s[0] > s[1] > s[2])
    hint = ("each sweep must start from the corrections of the one before (work on x in place, "
            "sweep `iterations` times).")
    if not np.all(np.isfinite(s)) or max(s) > 1.0:
        hint = ("the cloth blows up: the corrections push the ends the wrong way or too far "
                "(see 'one rod, one pass').")
    elif np.allclose(s, s[0], rtol=1e-12, atol=0.0):
        hint = ("the same stretch after 1, 5 and 25 sweeps: `iterations` is not used. The sweep "
                "over all rods runs `iterations` times, each starting from the last one's "
                "positions.")
    elif min(s) < 1e-12:
        hint = ("the stretch is already 0, so it cannot fall: does the cloth still hang from "
                "its pinned top row? Fix the other checks first ('pinned never move', 'one rod, "
                "one pass').")
    return Result(ok, f"mean stretch {', '.join(map(fmt, s))} at 1, 5, 25 iterations",
                  "falling as iterations rise", hint)


# ----- coincident --------------------------------------------------------------------------------
def measure_coincident(m: Student) -> dict:
    x = np.array([[5.0, 5.0], [5.0, 5.0], [25.0, 5.0]])
    return {"x": relax(m, x, np.array([0, 1]), np.array([1, 2]), np.array([10.0, 10.0]),
                       np.ones(3), 3)}


def judge_coincident(raw: Raw) -> Result:
    ok = bool(np.isfinite(raw.array("x", (3, 2))).all())
    return Result(ok, "finite" if ok else "NaN or inf in the positions", "finite",
                  "two particles at one point have |delta| = 0: divide by max(|delta|, 1e-9).")


# ----- random rods, masses, pins and sweeps (a new seed each run) --------------------------------
# One sweep fixes the rods one at a time, so its result depends on their order: the slide's loop
# takes them in file order, the lab's batches (app/physics/jakobsen.py) in another. The judge
# therefore replays the slide's sweeps in EVERY order of the rods (at most 5 rods: 120 orders,
# the same order each sweep) and passes the answer that matches one of them, within the
# rounding of those sweeps. A batch of rods that share no particle, solved at once, is one of
# these orders; a sweep that takes every rod's direction at its start (Jacobi), one sweep too
# many or too few, or a guard that leaves the whole sweep at a zero length is none of them.
RANDOM_CASES = 4


def random_cases() -> list[tuple]:
    """3 to 5 particles joined in a chain (so that rods share particles and one sweep does not
    settle them) plus up to 5 rods in all (no two between the same particles), in random order
    and direction; inverse masses from 0.2 to 5, one particle pinned (w = 0) in half the cases;
    rests from 0 (a zero-length rod, at most one) to 60 px; 1 to 4 sweeps; in the last two cases
    a rod whose ends start at one point (placed first or anywhere in the list)."""
    rng = cases_rng("constraints random")
    cases = []
    for k in range(RANDOM_CASES):
        n = int(rng.integers(3, 6))
        path = rng.permutation(n)              # a chain through every particle: rods that
        pairs = [tuple(sorted(p)) for p in zip(path[:-1], path[1:])]   # share particles
        others = [p for p in itertools.combinations(range(n), 2) if p not in pairs]
        extra = int(rng.integers(0, min(5 - len(pairs), len(others)) + 1))
        pairs += [others[c] for c in rng.choice(len(others), extra, replace=False)]
        pairs = [pairs[c] for c in rng.permutation(len(pairs))]
        m = len(pairs)
        ab = np.array(pairs)
        ab = np.where(rng.random((m, 1)) < 0.5, ab, ab[:, ::-1])
        a, b = ab[:, 0].astype(np.intp), ab[:, 1].astype(np.intp)
        x = rng.uniform(0.0, 100.0, (n, 2))
        w = rng.uniform(0.2, 5.0, n)
        if rng.random() < 0.5:
            w[int(rng.integers(0, n))] = 0.0                     # one pinned particle
        rest = rng.uniform(5.0, 60.0, m)
        if rng.random() < 0.5:
            rest[int(rng.integers(0, m))] = 0.0                  # a zero-length rod
        if k >= 2:                                               # ends at one point
            r = 0 if k == 2 else int(rng.integers(0, m))
            x[b[r]] = x[a[r]]
            w[a[r]] = w[a[r]] or 1.0                             # and free to move
        cases.append((x, a, b, rest, w, int(rng.integers(1, 5))))
    return cases


def slide_sweeps(x, a, b, rest, w, iterations, order, mistake: str = "") -> np.ndarray:
    """The slide's sweeps with the rods in `order` (in the parent), or one of the usual mistakes:
    'directions once per sweep', 'one sweep too many', 'one sweep short', 'break at a zero
    length'."""
    x = np.array(x, dtype=float)
    sweeps = iterations + {"one sweep too many": 1, "one sweep short": -1}.get(mistake, 0)
    for _ in range(sweeps):
        start = x.copy()
        for k in order:
            i, j = a[k], b[k]
            total = w[i] + w[j]
            if total == 0:
                continue
            delta = (start if mistake == "directions once per sweep" else x)[j] - \
                (start if mistake == "directions once per sweep" else x)[i]
            d = math.hypot(delta[0], delta[1])
            if d == 0 and mistake == "break at a zero length":
                break
            d = max(d, 1e-9)
            c = delta * (d - rest[k]) / d
            x[i] += c * (w[i] / total)
            x[j] -= c * (w[j] / total)
    return x


SWEEP_MISTAKES = {
    "directions once per sweep": "each rod's delta is taken at the START of the sweep (all "
        "directions at once, then every correction added: Jacobi): a rod must see the positions "
        "the rods before it in this sweep left ('fix one rod at a time'); read delta = x[b] - "
        "x[a] inside the loop over the rods, from the array you are changing",
    "one sweep too many": "one sweep too many: the loop runs iterations + 1 times (range("
        "iterations + 1), or a sweep before the loop as well as in it); it runs `iterations` "
        "times",
    "one sweep short": "one sweep short: range(iterations - 1); it runs `iterations` times",
    "break at a zero length": "the sweep stops at a rod of length 0 (`break` in the guard): "
        "that leaves every rod after it unfixed in that sweep. Skip only that rod (continue), "
        "or divide by max(|delta|, 1e-9), which moves nothing when delta = 0",
}


def measure_random(m: Student) -> dict:
    return {str(k): relax(m, *case) for k, case in enumerate(random_cases())}


def judge_random(raw: Raw) -> Result:
    for k, (x, a, b, rest, w, iterations) in enumerate(random_cases()):
        out = raw.array(str(k), x.shape)
        tol = rounding(float(np.abs(x).max() + rest.max()), ops=8 * iterations * len(a))
        orders = list(itertools.permutations(range(len(a))))
        errs = [float(np.abs(out - slide_sweeps(x, a, b, rest, w, iterations, o)).max())
                for o in orders]
        err = min(errs) if all(map(math.isfinite, errs)) else math.inf
        if err <= tol:
            continue
        hint = ("one sweep fixes every rod once, in some order, each rod from the positions the "
                "rods before it left; `iterations` sweeps; ends move by their shares w / (w_a + "
                "w_b); a pinned end (w = 0) never moves.")
        named = [text for mistake, text in SWEEP_MISTAKES.items()
                 if any(np.allclose(out, slide_sweeps(x, a, b, rest, w, iterations, o, mistake),
                                    rtol=0, atol=tol) for o in orders)]
        if len(named) == 1:
            hint = named[0] + "."
        elif named:
            hint = ("this matches more than one usual mistake here: " + "; or ".join(named)
                    + ".")
        if not np.isfinite(out).all():
            hint = ("NaN or inf: a rod of length 0 (two particles at one point) divides by "
                    "|delta| = 0; divide by max(|delta|, 1e-9). " + hint)
        pinned = w == 0
        moved = float(np.abs(out[pinned] - x[pinned]).max()) if pinned.any() else 0.0
        return Result(False, f"case {k + 1} of {RANDOM_CASES} ({len(x)} particles, {len(a)} rods, "
                      f"{iterations} sweeps, {int(pinned.sum())} pinned): {fmt(err)} px off the "
                      f"slide's sweeps in the nearest of the {len(orders)} orders of the rods"
                      + (f"; pinned particles moved {fmt(moved)} px" if moved else ""),
                      f"< {tol:.2g} px (the sweeps' own rounding)", hint)
    return Result(True, f"{RANDOM_CASES} random sets of rods: each the slide's sweeps in an order "
                  "of the rods", "the slide's sweeps, within their rounding")


EXERCISE = Exercise(
    name="constraints",
    title="Jakobsen's rods: relaxing distance constraints",
    slide="Cloth Simulation: 'Verlet cloth' (rods, not springs; solve by local iteration) and "
          "the slide's satisfyConstraints()",
    functions=("satisfy_rods",),
    reference=reference,
    checks=(Check("pinned never move", measure_pinned, judge_pinned),
            Check("one rod, one pass", measure_rod(STRETCHED), judge_one_rod),
            Check("a squashed rod pushes", measure_rod(SQUASHED), judge_squashed),
            Check("shares by inverse mass", measure_rod(STRETCHED), judge_shares),
            Check("each rod its rest", measure_rests, judge_rests),
            Check("stretch falls", measure_stretch, judge_stretch),
            Check("coincident particles", measure_coincident, judge_coincident),
            Check("random rods and sweeps", measure_random, judge_random)),
)
