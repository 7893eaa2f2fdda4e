"""Grader of exercises/spring.py: damped Hooke springs, summed per particle (an n-ary force).

Reference: app.physics.forces.Springs (its accumulate). Checks:
  Hooke part       5 particles, 8 springs (particles shared by several springs), kd = 0: the
                   forces agree with the lab's to 1e-9 (relative)
  damping part     the same springs with ks = 0, kd = 2: agree to 1e-9
  third law        the forces of all springs add up to zero
  damping removes  two particles on a stretched damped spring, 2 s of small symplectic Euler
                   steps: the energy falls below half of its start
  inputs kept      x and v are not changed
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from app.exercises.base import Check, Exercise, Result, Student, array_of, fmt

A = np.array([0, 1, 2, 3, 0, 1, 4, 2])
B = np.array([1, 2, 3, 4, 2, 3, 0, 4])


def reference() -> SimpleNamespace:
    from app.physics.forces import Springs

    def spring_forces(x, v, a, b, ks, kd, rest):
        f = np.zeros_like(np.asarray(x, dtype=float))
        Springs(a, b, ks, kd, rest).accumulate(None, x, v, f)   # Springs never reads the system
        return f
    return SimpleNamespace(spring_forces=spring_forces)


def forces(m: Student, x, v, a, b, ks, kd, rest) -> np.ndarray:
    return array_of(m.spring_forces(x.copy(), v.copy(), a, b, ks, kd, rest), x.shape,
                    "spring_forces")


def system(seed: int = 3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    x = rng.uniform(0, 100, (5, 2))
    v = rng.normal(0, 20, (5, 2))
    rest = rng.uniform(20, 60, len(A))
    return x, v, rest


def rel_error(f: np.ndarray, ref: np.ndarray) -> float:
    return float(np.abs(f - ref).max() / np.abs(ref).max())


def _compare(m: Student, ks: float, kd: float, hint: str) -> Result:
    x, v, rest = system()
    ref = reference().spring_forces(x, v, A, B, ks, kd, rest)
    f = forces(m, x, v, A, B, ks, kd, rest)
    err = rel_error(f, ref)
    # a common slip: f[a] += fa with repeated indices keeps one write per particle
    spring_force = reference().spring_forces
    fa = np.array([spring_force(x, v, A[k:k + 1], B[k:k + 1], ks, kd, rest[k:k + 1])[A[k]]
                   for k in range(len(A))])
    lost = np.zeros_like(x)
    lost[A] += fa
    lost[B] -= fa
    if rel_error(f, -ref) < 1e-9:
        hint = ("your forces are the lab's with the sign flipped: f_a = -[...] l/|l| with "
                "l = x_a - x_b (a stretched spring pulls a towards b), f_b = -f_a.")
    elif rel_error(f, lost) < 1e-9:
        hint = ("a particle in several springs gets only one of them: f[a] += fa keeps the last "
                "write for a repeated index. Use np.add.at(f, a, fa) (or a loop over springs).")
    return Result(err < 1e-9, f"largest difference {fmt(err)} of the largest force",
                  "< 1e-09 (relative)", hint)


def hooke(m: Student) -> Result:
    return _compare(m, 50.0, 0.0, "f_a = -ks (|l| - rest) l/|l| with l = x_a - x_b: the "
                    "direction is the UNIT vector l/|l| (without it the force grows with the "
                    "length twice), and f_b = -f_a.")


def damping(m: Student) -> Result:
    return _compare(m, 0.0, 2.0, "the damping term is kd (v_a - v_b) . l/|l|: the relative "
                    "velocity projected on the spring, times l/|l| (not kd (v_a - v_b)).")


def third_law(m: Student) -> Result:
    x, v, rest = system(4)
    f = forces(m, x, v, A, B, 50.0, 2.0, rest)
    total = float(np.linalg.norm(f.sum(0)) / max(np.abs(f).max(), 1e-300))
    return Result(total < 1e-12, f"|sum of forces| = {fmt(total)} of the largest force",
                  "< 1e-12 (zero)", "each spring adds f_a to particle a and -f_a to particle b.")


def damping_removes(m: Student) -> Result:
    x = np.array([[0.0, 0.0], [80.0, 0.0]])
    v = np.zeros_like(x)
    a, b, rest, ks, kd = np.array([0]), np.array([1]), np.array([50.0]), 50.0, 1.0
    h = 1e-3

    def energy(x, v):
        return 0.5 * float((v * v).sum()) + 0.5 * ks * (np.linalg.norm(x[1] - x[0]) - 50.0) ** 2

    e0 = energy(x, v)
    for _ in range(2000):               # symplectic Euler, unit masses
        v = v + h * forces(m, x, v, a, b, ks, kd, rest)
        x = x + h * v
    ratio = energy(x, v) / e0
    return Result(ratio < 0.5, f"energy ratio {fmt(ratio)} after 2 s", "< 0.5",
                  "the damping force must oppose the relative velocity along the spring: "
                  "-kd ((v_a - v_b) . u) u on a, with u = (x_a - x_b)/|x_a - x_b| (check signs).")


def inputs_kept(m: Student) -> Result:
    x, v, rest = system(5)
    x0, v0 = x.copy(), v.copy()
    m.spring_forces(x, v, A, B, 50.0, 2.0, rest)
    problems = [f"{name} was changed" for name, now, before in (("x", x, x0), ("v", v, v0))
                if not np.array_equal(now, before)]
    return Result(not problems, "; ".join(problems) or "x and v untouched",
                  "x and v unchanged",
                  "sum the forces into a new array (f = np.zeros_like(x)): x and v are the "
                  "particles' state, which the caller goes on stepping.")


EXERCISE = Exercise(
    name="spring",
    title="Damped springs: an n-ary force",
    slide="Physics in Computer Animations and Games: 'A Newtonian Particle' / damped springs "
          "(f_a = -[ks(|l| - r) + kd (v_a - v_b).l/|l|] l/|l|, f_b = -f_a)",
    functions=("spring_forces",),
    reference=reference,
    checks=(Check("Hooke part", hooke), Check("damping part", damping),
            Check("third law", third_law), Check("damping removes energy", damping_removes),
            Check("inputs kept", inputs_kept)),
)
