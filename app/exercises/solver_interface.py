"""Grader of exercises/solver_interface.py: the derivative evaluation (clear, accumulate, gather).

Reference: app.physics.particles.ParticleSystem.derivative, with the exercise's forces plugged in
as force objects. A force here is a function force(x, v, f) that ADDS its force into f (n, 2).
Checks, on 4 particles with gravity, drag and two springs:
  matches the lab     the derivative agrees with the lab's particle system to 1e-12 (relative)
  dx/dt = v           the first half of the result is the velocities, in the state's order
  clears forces       two calls on the same state give the same result
  a = f / m           doubling every mass halves the accelerations (springs only)
  state kept          the state vector passed in is not changed
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from app.exercises.base import Check, Exercise, Result, Student, array_of, fmt

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
    return [gravity(masses), drag(0.3),
            springs(np.array([0, 1, 2]), np.array([1, 2, 3]), 40.0, np.array([30.0, 40.0, 25.0]))]


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


def state(seed: int = 5) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.uniform(0, 100, 2 * N), rng.normal(0, 30, 2 * N)])


def deriv(m: Student, y, masses, forces) -> np.ndarray:
    return array_of(m.derivative(y.copy(), masses.copy(), forces), y.shape, "derivative")


LAYOUT = ("gather [v, f/m] flattened like the state: all positions' derivatives (the "
          "velocities x1, y1, x2, y2, ...) first, then all accelerations.")


def matches(m: Student) -> Result:
    y = state()
    ref = reference().derivative(y, MASSES, forces_for(MASSES))
    d = deriv(m, y, MASSES, forces_for(MASSES))
    err = float(np.abs(d - ref).max() / np.abs(ref).max())
    return Result(err < 1e-12, f"largest difference {fmt(err)} of the largest entry",
                  "< 1e-12 (relative)", "clear f, call every force(x, v, f), then " + LAYOUT)


def velocity_first(m: Student) -> Result:
    y = state()
    d = deriv(m, y, MASSES, forces_for(MASSES))
    err = float(np.abs(d[:2 * N] - y[2 * N:]).max())
    return Result(err == 0.0, f"|dx/dt - v| = {fmt(err)}", "0", LAYOUT)


def clears(m: Student) -> Result:
    y = state()
    first = deriv(m, y, MASSES, forces_for(MASSES))
    second = deriv(m, y, MASSES, forces_for(MASSES))
    diff = float(np.abs(second - first).max())
    return Result(diff == 0.0, f"two calls differ by {fmt(diff)}", "0",
                  "clear the force accumulator (f = np.zeros((n, 2))) at the start of EVERY "
                  "call: forces left from the last call were added again.")


def divides_by_mass(m: Student) -> Result:
    y = state()
    only_springs = forces_for(MASSES)[2:]
    light = deriv(m, y, MASSES, only_springs)[2 * N:]
    heavy = deriv(m, y, 2 * MASSES, only_springs)[2 * N:]
    ratio = float(np.abs(heavy).sum() / np.abs(light).sum())
    return Result(abs(ratio - 0.5) < 1e-12, f"accelerations x {fmt(ratio)} when the masses "
                  "double", "0.5", "the gather returns f / m (Newton's second law), not f.")


def state_kept(m: Student) -> Result:
    y = state()
    y0 = y.copy()
    m.derivative(y, MASSES.copy(), forces_for(MASSES))
    changed = float(np.abs(y - y0).max())
    return Result(changed == 0.0, f"the state changed by {fmt(changed)}", "0",
                  "read x and v from the state; write the forces into a new array f.")


EXERCISE = Exercise(
    name="solver_interface",
    title="The solver interface: derivative evaluation",
    slide="Physics in Computer Animations and Games: 'Solver Interface' and 'Derivation "
          "Evaluation Loop' (clear forces, calculate forces, gather [v, f/m])",
    functions=("derivative",),
    reference=reference,
    checks=(Check("matches the lab", matches), Check("dx/dt = v", velocity_first),
            Check("clears forces", clears), Check("a = f / m", divides_by_mass),
            Check("state kept", state_kept)),
)
