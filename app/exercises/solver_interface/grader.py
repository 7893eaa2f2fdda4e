"""Grader of exercises/solver_interface.py: the derivative evaluation (clear, accumulate, gather).

Reference: app.physics.particles.ParticleSystem.derivative, with the exercise's forces plugged in
as force objects. A force here is a function force(x, v, f) that ADDS its force into f (n, 2).
Each measure sends back the derivatives the student's function returned; each judge compares.
On 4 particles with gravity, drag and two springs:
  matches the lab     the derivative agrees with the lab's particle system to 1e-12 (relative)
  dx/dt = v           the first half of the result is the velocities, in the state's order
  clears forces       two calls on the same state give the same result
  a = f / m           doubling every mass halves the accelerations (springs only)
  any number          3 and 6 particles (a chain of springs): agrees with the lab's, as above
                      (and 4, to tell a count written in from a derivative wrong for all)
  state kept          the state vector passed in is not changed
  random systems   4 random systems (seeded): the lab's derivative within its rounding
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from app.exercises.base import (Check, Exercise, Raw, Result, Student, array_of, cases_rng, fmt,
                                rounding, within)

N = 4
MASSES = np.array([1.0, 2.0, 0.5, 1.5])


def gravity(masses: np.ndarray, g=(0.0, 900.0)):
    def force(x, v, f):
        f += masses[:, None] * np.asarray(g)
    return force


def drag(kd: float):
    def force(x, v, f):
        f -= kd * v
    return force


def springs(a, b, ks: float, rest):
    from app.physics.forces import Springs
    s = Springs(a, b, ks, 0.0, rest)

    def force(x, v, f):
        s.accumulate(None, x, v, f)
    return force


def forces_for(masses: np.ndarray) -> list:
    n = len(masses)
    return [gravity(masses), drag(0.3),
            springs(np.arange(n - 1), np.arange(1, n), 40.0, 30.0 + 5.0 * np.arange(n - 1))]


class _Plugged:
    """An exercise force function as a force object of the lab's particle system."""

    def __init__(self, fn):
        self.fn = fn

    def accumulate(self, ps, x, v, f) -> None:
        self.fn(x, v, f)


def reference() -> SimpleNamespace:
    from app.physics.particles import ParticleSystem

    def derivative(state, masses, forces):
        n = len(masses)
        x = state[:2 * n].reshape(n, 2)
        ps = ParticleSystem(x, state[2 * n:].reshape(n, 2), masses, [_Plugged(f) for f in forces])
        return ps.derivative(np.asarray(state, dtype=float))
    return SimpleNamespace(derivative=derivative)


def state(seed: int = 5, n: int = N) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.uniform(0, 100, 2 * n), rng.normal(0, 30, 2 * n)])


def masses_of(n: int) -> np.ndarray:
    return MASSES if n == N else np.linspace(0.5, 2.0, n)


def deriv(m: Student, y, masses, forces) -> np.ndarray:
    return array_of(m.derivative(y.copy(), masses.copy(), forces), y.shape, "derivative")


def lab(y: np.ndarray, masses: np.ndarray, forces=None) -> np.ndarray:
    return reference().derivative(y, masses, forces if forces is not None else forces_for(masses))


def relative(d: np.ndarray, ref: np.ndarray) -> float:
    return float(np.abs(d - ref).max() / np.abs(ref).max())


LAYOUT = ("gather [v, f/m] flattened like the state: all positions' derivatives (the "
          "velocities x1, y1, x2, y2, ...) first, then all accelerations.")


def measure_one(m: Student) -> dict:
    return {"d": deriv(m, state(), MASSES, forces_for(MASSES))}


def judge_matches(raw: Raw) -> Result:
    err = relative(raw.array("d", (4 * N,)), lab(state(), MASSES))
    return Result(within(err, 0.0, 1e-12), f"largest difference {fmt(err)} of the largest entry",
                  "< 1e-12 (relative)", "clear f, call every force(x, v, f), then " + LAYOUT)


def judge_velocity_first(raw: Raw) -> Result:
    y = state()
    err = float(np.abs(raw.array("d", (4 * N,))[:2 * N] - y[2 * N:]).max())
    return Result(err == 0.0, f"|dx/dt - v| = {fmt(err)}", "0", LAYOUT)


def measure_twice(m: Student) -> dict:
    y = state()
    return {"first": deriv(m, y, MASSES, forces_for(MASSES)),
            "second": deriv(m, y, MASSES, forces_for(MASSES))}


def judge_clears(raw: Raw) -> Result:
    diff = float(np.abs(raw.array("second", (4 * N,)) - raw.array("first", (4 * N,))).max())
    return Result(diff == 0.0, f"two calls differ by {fmt(diff)}", "0",
                  "clear the force accumulator (f = np.zeros((n, 2))) at the start of EVERY "
                  "call: forces left from the last call were added again.")


def measure_masses(m: Student) -> dict:
    y = state()
    only_springs = forces_for(MASSES)[2:]
    return {"light": deriv(m, y, MASSES, only_springs), "heavy": deriv(m, y, 2 * MASSES,
                                                                       only_springs)}


def judge_masses(raw: Raw) -> Result:
    light = raw.array("light", (4 * N,))[2 * N:]
    heavy = raw.array("heavy", (4 * N,))[2 * N:]
    ratio = float(np.abs(heavy).sum() / np.abs(light).sum())
    hint = "the gather returns f / m (Newton's second law), not f."
    if within(ratio, 2.0, 1e-9):
        hint = "the accelerations grow with the mass: f * m, not f / m. " + hint
    elif within(ratio, 0.25, 1e-9):
        hint = "the forces are divided by the mass twice (f / m / m, or m^2). " + hint
    elif within(ratio, 1.0, 1e-9):
        hint = "the masses change nothing: the forces are not divided by them. " + hint
    return Result(within(ratio, 0.5, 1e-12), f"accelerations x {fmt(ratio)} when the masses "
                  "double", "0.5", hint)


OTHER_N = (3, 6)


def measure_counts(m: Student) -> dict:
    """The derivative for each number of particles, or what went wrong (a code written for four
    particles raises or returns the wrong length: the hint names that)."""
    out = {}
    for n in (N,) + OTHER_N:
        masses = masses_of(n)
        try:
            out[str(n)] = deriv(m, state(7 + n, n), masses, forces_for(masses))
        except NotImplementedError:
            raise
        except Exception as e:      # noqa: BLE001 - reported in the measurement, named by the hint
            out[str(n)] = f"{type(e).__name__}: {e}"[:300]
    return out


def judge_counts(raw: Raw) -> Result:
    parts, right = [], {}
    for n in (N,) + OTHER_N:
        if isinstance(raw.values.get(str(n)), str):
            parts.append(f"{n} particles: {raw.text(str(n))}")
            right[n] = False
            continue
        e = relative(raw.array(str(n), (4 * n,)), lab(state(7 + n, n), masses_of(n)))
        parts.append(f"{n} particles: {fmt(e)} off")
        right[n] = within(e, 0.0, 1e-12)
    ok = all(right.values())
    hint = ("the number of particles is n = len(masses) (or len(state) // 4): a fixed 4 "
            "(state[:8], reshape(4, 2)) works only for four. " + LAYOUT)
    if not right[N]:                  # wrong for four as well: not a matter of the count
        hint = "wrong for 4 particles too: see 'matches the lab'. " + LAYOUT
    return Result(ok, "; ".join(parts), "< 1e-12 (relative) for each", hint)


def measure_state_kept(m: Student) -> dict:
    y = state()
    m.derivative(y, MASSES.copy(), forces_for(MASSES))
    return {"y": y}


def judge_state_kept(raw: Raw) -> Result:
    changed = float(np.abs(raw.array("y", (4 * N,)) - state()).max())
    return Result(changed == 0.0, f"the state changed by {fmt(changed)}", "0",
                  "read x and v from the state; write the forces into a new array f.")


# ----- random systems (a new seed each run) ------------------------------------------------------
RANDOM_CASES = 4


def random_systems() -> list[tuple[np.ndarray, np.ndarray, list, str]]:
    """1 to 8 particles, masses 0.1 to 10, and 0 to 4 forces in any order: gravity of any size
    pointing any way, drag, springs between random pairs, a force that reads x and v and sets
    nothing but its own share (a swirl)."""
    rng = cases_rng("solver_interface random")
    cases = []
    for _ in range(RANDOM_CASES):
        n = int(rng.integers(1, 9))
        masses = rng.uniform(0.1, 10.0, n)
        y = np.concatenate([rng.uniform(0, 300, 2 * n), rng.normal(0, 40, 2 * n)])
        kinds = list(rng.choice(["gravity", "drag", "springs", "swirl"], int(rng.integers(0, 5))))
        forces, names = [], []
        for kind in kinds:
            if kind == "gravity":
                forces.append(gravity(masses, tuple(rng.normal(0.0, 600.0, 2))))
            elif kind == "drag":
                forces.append(drag(float(rng.uniform(0.0, 2.0))))
            elif kind == "springs" and n > 1:
                m = int(rng.integers(1, 2 * n))
                a = rng.integers(0, n, m)
                forces.append(springs(a, (a + rng.integers(1, n, m)) % n,
                                      float(rng.uniform(1, 100)), rng.uniform(0, 80, m)))
            elif kind == "swirl":
                c = float(rng.uniform(-3.0, 3.0))
                def swirl(x, v, f, c=c):
                    f += c * np.stack([-x[:, 1] + v[:, 0], x[:, 0] - v[:, 1]], axis=1)
                forces.append(swirl)
            else:
                continue
            names.append(str(kind))
        cases.append((y, masses, forces, ", ".join(names) or "no forces"))
    return cases


def measure_random(m: Student) -> dict:
    return {str(k): deriv(m, y, masses, forces)
            for k, (y, masses, forces, _) in enumerate(random_systems())}


def judge_random(raw: Raw) -> Result:
    for k, (y, masses, forces, names) in enumerate(random_systems()):
        d = raw.array(str(k), y.shape)
        ref = lab(y, masses, forces)
        n = len(masses)
        f_scale = float(np.abs(ref[2 * n:]).max() * masses.max()) if n else 0.0
        tol = rounding(float(np.abs(y).max()) + f_scale / masses.min() * 4, ops=4 + 2 * n)
        err = float(np.abs(d - ref).max())
        if not err <= tol:
            half = 2 * n
            part = ("dx/dt (the first half)" if not np.allclose(d[:half], ref[:half], rtol=0,
                                                               atol=tol) else
                    "dv/dt (the second half)")
            return Result(False, f"case {k + 1} of {RANDOM_CASES} ({n} particles, {names}): "
                          f"{fmt(err)} off the lab's derivative, in {part}",
                          f"< {tol:.2g} (the lab's rounding)",
                          f"{part} is {fmt(err)} off: clear f, call every force(x, v, f) in the "
                          "list (whatever their number), then " + LAYOUT)
    return Result(True, f"{RANDOM_CASES} random systems: the lab's derivative within its "
                  "rounding", "the lab's derivative, within its rounding")


EXERCISE = Exercise(
    name="solver_interface",
    title="The solver interface: derivative evaluation",
    slide="Physics in Computer Animations and Games: 'Solver Interface' and 'Derivation "
          "Evaluation Loop' (clear forces, calculate forces, gather [v, f/m])",
    functions=("derivative",),
    reference=reference,
    checks=(Check("matches the lab", measure_one, judge_matches),
            Check("dx/dt = v", measure_one, judge_velocity_first),
            Check("clears forces", measure_twice, judge_clears),
            Check("a = f / m", measure_masses, judge_masses),
            Check("any number of particles", measure_counts, judge_counts),
            Check("state kept", measure_state_kept, judge_state_kept),
            Check("random systems", measure_random, judge_random)),
)
