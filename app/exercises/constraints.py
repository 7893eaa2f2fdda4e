"""Grader of exercises/constraints.py: Jakobsen's rod relaxation with inverse masses.

Reference: app.physics.jakobsen.satisfy_rods. Checks:
  pinned never move   a chain with both ends pinned (w = 0), stretched at random, 20 sweeps:
                      the pinned particles move by exactly 0
  one rod, one pass   one rod of length 50, rest 20: after one sweep its length is 20 (+- 1e-9)
  shares by mass      the same rod with w = 1 and 3: the centre of mass (masses 1/w) stays put
  stretch falls       a hanging 6 x 6 cloth (top row pinned) for 1/3 s at 60 Hz, stepped by the
                      lab's Verlet: the mean stretch after 1, 5, 25 sweeps per step falls
  coincident          two particles at one point, rest 10: the result is finite (no 0/0)
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from app.exercises.base import Check, Exercise, Result, Student, array_of, fmt


def reference() -> SimpleNamespace:
    from app.physics.jakobsen import satisfy_rods
    return SimpleNamespace(satisfy_rods=satisfy_rods)


def relax(m: Student, x, a, b, rest, w, iterations) -> np.ndarray:
    out = m.satisfy_rods(x.copy(), a, b, rest, w, iterations)
    return array_of(out, x.shape, "satisfy_rods")


WEIGHT_HINT = ("move each end by its share w_a / (w_a + w_b) of the correction (w = 0: pinned, "
               "it never moves). Did you split it 50/50?")


def pinned(m: Student) -> Result:
    rng = np.random.default_rng(2)
    n = 8
    x = np.stack([np.arange(n) * 15.0, np.zeros(n)], axis=1) + rng.normal(0, 4, (n, 2))
    a, b = np.arange(n - 1), np.arange(1, n)
    w = np.ones(n)
    w[[0, n - 1]] = 0.0
    out = relax(m, x, a, b, np.full(n - 1, 10.0), w, 20)
    moved = float(np.abs(out[[0, n - 1]] - x[[0, n - 1]]).max())
    return Result(moved == 0.0, f"pinned particles moved {fmt(moved)} px", "0 px", WEIGHT_HINT)


def _one_rod(m: Student) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    x = np.array([[0.0, 0.0], [30.0, 40.0]])            # length 50
    w = np.array([1.0, 3.0])
    out = relax(m, x, np.array([0]), np.array([1]), np.array([20.0]), w, 1)
    return x, w, out


def one_rod(m: Student) -> Result:
    x, _, out = _one_rod(m)
    err = abs(float(np.linalg.norm(out[1] - out[0])) - 20.0)
    along = x[1] - x[0]
    length = float((out[1] - out[0]) @ along / np.linalg.norm(along))   # < 0: ends crossed
    hint = ("one rod alone is satisfied exactly by one correction: diff = (|delta| - rest) / "
            "|delta| (divide by the length), then the ends move by delta * diff * their shares "
            "w_a / (w_a + w_b) and w_b / (w_a + w_b), which add up to 1.")
    if length > 50.0 + 1e-9:
        hint = "the rod got LONGER (50 -> " + f"{length:.3g}): a sign is flipped. " + hint
    elif length < 20.0 - 1e-9:
        hint = (f"the ends moved too far (50 px -> {length:.3g} along the old rod, rest 20; "
                "below 0 they crossed): did you forget to divide by w_a + w_b? " + hint)
    return Result(err < 1e-9, f"|length - rest| = {fmt(err)} px after one pass", "< 1e-09 px",
                  hint)


def shares(m: Student) -> Result:
    x, w, out = _one_rod(m)
    mass = 1.0 / w
    before = (mass[:, None] * x).sum(0) / mass.sum()
    after = (mass[:, None] * out).sum(0) / mass.sum()
    moved = float(np.linalg.norm(after - before))
    return Result(moved < 1e-9, f"centre of mass moved {fmt(moved)} px", "< 1e-09 px",
                  "the heavier end (smaller w) moves less: " + WEIGHT_HINT)


def hanging_stretch(m: Student, iterations: int, rows: int = 6, spacing: float = 20.0) -> float:
    """Mean |length / rest - 1| of a hanging cloth after 1/3 s (the lab's Verlet, your rods)."""
    from app.physics.jakobsen import verlet_step
    r, c = np.mgrid[0:rows, 0:rows]
    idx = r * rows + c
    a = np.concatenate([idx[:, :-1].ravel(), idx[:-1, :].ravel()])
    b = np.concatenate([idx[:, 1:].ravel(), idx[1:, :].ravel()])
    x = np.stack([c.ravel() * spacing, r.ravel() * spacing], axis=1).astype(float)
    rest = np.full(len(a), spacing)
    w = np.ones(len(x))
    w[:rows] = 0.0                                      # the top row is pinned
    acc = np.where(w[:, None] > 0, np.array([0.0, 900.0]), 0.0)
    x_prev, h = x.copy(), 1 / 60
    for _ in range(20):
        x, x_prev = verlet_step(x, x_prev, acc, h, 0.01)
        x = relax(m, x, a, b, rest, w, iterations)
    return float(np.abs(np.linalg.norm(x[b] - x[a], axis=1) / rest - 1).mean())


def stretch_falls(m: Student) -> Result:
    s = [hanging_stretch(m, k) for k in (1, 5, 25)]
    ok = bool(np.all(np.isfinite(s)) and s[0] > s[1] > s[2])
    hint = ("each sweep must start from the corrections of the one before (work on x in place, "
            "sweep `iterations` times).")
    if not np.all(np.isfinite(s)) or max(s) > 1.0:
        hint = ("the cloth blows up: the corrections push the ends the wrong way or too far "
                "(see 'one rod, one pass').")
    elif min(s) < 1e-12:
        hint = ("the stretch is already 0, so it cannot fall: does the cloth still hang from "
                "its pinned top row? Fix the other checks first ('pinned never move', 'one rod, "
                "one pass').")
    return Result(ok, f"mean stretch {', '.join(map(fmt, s))} at 1, 5, 25 iterations",
                  "falling as iterations rise", hint)


def coincident(m: Student) -> Result:
    x = np.array([[5.0, 5.0], [5.0, 5.0], [25.0, 5.0]])
    out = relax(m, x, np.array([0, 1]), np.array([1, 2]), np.array([10.0, 10.0]),
                np.ones(3), 3)
    ok = bool(np.isfinite(out).all())
    return Result(ok, "finite" if ok else "NaN or inf in the positions", "finite",
                  "two particles at one point have |delta| = 0: divide by max(|delta|, 1e-9).")


EXERCISE = Exercise(
    name="constraints",
    title="Jakobsen's rods: relaxing distance constraints",
    slide="Cloth Simulation: 'Verlet cloth' (rods, not springs; solve by local iteration) and "
          "the slide's satisfyConstraints()",
    functions=("satisfy_rods",),
    reference=reference,
    checks=(Check("pinned never move", pinned), Check("one rod, one pass", one_rod),
            Check("shares by inverse mass", shares), Check("stretch falls", stretch_falls),
            Check("coincident particles", coincident)),
)
