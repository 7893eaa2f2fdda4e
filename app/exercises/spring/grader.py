"""Grader of exercises/spring.py: damped Hooke springs, summed per particle (an n-ary force).

Reference: app.physics.forces.Springs (its accumulate). Each measure sends back the forces the
student's spring_forces returned (or the state their forces moved); each judge compares:
  Hooke part       5 particles, 8 springs (particles shared by several springs), kd = 0: the
                   forces agree with the lab's to 1e-9 (relative)
  damping part     the same springs with ks = 0, kd = 2: agree to 1e-9
  third law        the forces of all springs add up to zero
  a particle alone 6 particles, the last (the highest index) in no spring: the result has a row
                   for it, and its force is 0
  damping removes  two particles on a stretched damped spring, 2 s of small symplectic Euler
                   steps: the energy falls below half of its start
  inputs kept      x and v are not changed
  random springs   4 random sets (seeded): the lab's forces within its rounding
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from app.exercises.base import (Check, Exercise, Malformed, Raw, Result, Student, array_of,
                                cases_rng, fmt, rounding, within)

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


def system(seed: int = 3, n: int = 5, springs: int = len(A)
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    x = rng.uniform(0, 100, (n, 2))
    v = rng.normal(0, 20, (n, 2))
    rest = rng.uniform(20, 60, springs)
    return x, v, rest


def rel_error(f: np.ndarray, ref: np.ndarray) -> float:
    return float(np.abs(f - ref).max() / np.abs(ref).max())


def measure_forces(ks: float, kd: float):
    def measure(m: Student) -> dict:
        x, v, rest = system()
        return {"f": forces(m, x, v, A, B, ks, kd, rest)}
    return measure


SPRING_MISTAKES = {
    "damping sign": "the damping term has the wrong sign: f_a = -[ks (|l| - rest) + kd (v_a - "
                    "v_b) . u] u, so damping pulls against the relative motion along the spring "
                    "(a plus inside the brackets).",
    "sign flipped": "your forces are the lab's with the sign flipped: f_a = -[...] l/|l| with "
                    "l = x_a - x_b (a stretched spring pulls a towards b), f_b = -f_a.",
    "hooke sign": "the Hooke part pushes a stretched spring apart: its sign is flipped (l = x_b - "
                  "x_a?); with l = x_a - x_b and u = l/|l|, f_a = -ks (|l| - rest) u pulls a "
                  "towards b.",
    "f[a] += fa": "a particle in several springs gets only one of them: f[a] += fa keeps the "
                  "last write for a repeated index. Use np.add.at(f, a, fa) (or a loop over "
                  "springs).",
    "no reaction": "only f_a is added: each spring also pushes b with f_b = -f_a "
                   "(np.add.at(f, b, -fa)).",
    "no rest": "Hooke's law on the whole length, ks |l|: it is ks (|l| - rest), the stretch.",
    "ks kd swapped": "ks and kd are swapped: ks multiplies the stretch (|l| - rest), kd the "
                     "relative speed along the spring.",
    "one length": "one length for all springs: np.linalg.norm(l) without axis=1 is the norm of "
                  "the whole array; each spring needs its own |l| (axis=1, keepdims=True).",
    "not unit": "the direction is l, not the unit vector l/|l|: the force then grows with the "
                "length twice.",
    "v_a only": "the damping uses v_a alone: it damps the RELATIVE velocity, (v_a - v_b) . u.",
    "unprojected": "the damping is kd (v_a - v_b), not projected: only the relative speed ALONG "
                   "the spring is damped, kd ((v_a - v_b) . u) u.",
}


def spring_with(kind: str, x, v, a, b, ks, kd, rest) -> np.ndarray:
    """The forces with one of the usual mistakes (computed here, in the parent)."""
    if kind == "ks kd swapped":
        ks, kd = kd, ks
    l = x[a] - x[b]
    length = (np.full((len(a), 1), np.linalg.norm(l)) if kind == "one length"
              else np.linalg.norm(l, axis=1, keepdims=True))
    u = l if kind == "not unit" else l / length
    dv = v[a] if kind == "v_a only" else v[a] - v[b]
    stretch = length if kind == "no rest" else length - rest[:, None]
    if kind == "damping sign":
        kd = -kd
    if kind == "hooke sign":
        ks = -ks
    if kind == "unprojected":
        fa = -ks * stretch * u - kd * dv
    else:
        fa = -(ks * stretch + kd * np.sum(dv * u, axis=1, keepdims=True)) * u
    f = np.zeros_like(x)
    if kind == "f[a] += fa":
        f[a] += fa
        f[b] -= fa
    else:
        np.add.at(f, a, fa)
        if kind != "no reaction":
            np.add.at(f, b, -fa)
    return -f if kind == "sign flipped" else f


def named_spring_mistake(f, x, v, a, b, ks, kd, rest) -> str:
    """The hint of the usual mistake these forces match ('' if none, or if it is the right
    answer on these inputs too)."""
    right = spring_with("", x, v, a, b, ks, kd, rest)
    for kind, text in SPRING_MISTAKES.items():
        with np.errstate(all="ignore"):
            other = spring_with(kind, x, v, a, b, ks, kd, rest)
        if rel_error(other, right) > 1e-6 and rel_error(f, other) < 1e-9:
            return text
    return ""


def judge_forces(ks: float, kd: float, hint: str):
    def judge(raw: Raw) -> Result:
        x, v, rest = system()
        ref = reference().spring_forces(x, v, A, B, ks, kd, rest)
        f = raw.array("f", x.shape)
        err = rel_error(f, ref)
        text = named_spring_mistake(f, x, v, A, B, ks, kd, rest) or hint
        return Result(within(err, 0.0, 1e-9), f"largest difference {fmt(err)} of the largest "
                      "force", "< 1e-09 (relative)", text)
    return judge


def measure_third_law(m: Student) -> dict:
    x, v, rest = system(4)
    return {"f": forces(m, x, v, A, B, 50.0, 2.0, rest)}


def judge_third_law(raw: Raw) -> Result:
    f = raw.array("f", (5, 2))
    total = float(np.linalg.norm(f.sum(0)) / max(float(np.abs(f).max()), 1e-300))
    return Result(within(total, 0.0, 1e-12), f"|sum of forces| = {fmt(total)} of the largest "
                  "force", "< 1e-12 (zero)", "each spring adds f_a to particle a and -f_a to "
                  "particle b.")


# particles 0..4 in springs, particle 5 (the highest index) in none
ALONE_A, ALONE_B = np.array([0, 1, 2, 3]), np.array([1, 2, 3, 4])


def measure_alone(m: Student) -> dict:
    x, v, rest = system(6, n=6, springs=len(ALONE_A))
    f = m.spring_forces(x.copy(), v.copy(), ALONE_A, ALONE_B, 50.0, 2.0, rest)
    shape = list(np.shape(f)) if f is not None else None
    return {"shape": shape, "f": array_of(f, x.shape, "spring_forces") if shape == [6, 2]
            else None}


def judge_alone(raw: Raw) -> Result:
    x, v, rest = system(6, n=6, springs=len(ALONE_A))
    shape = raw.values.get("shape")
    if shape is not None and not (isinstance(shape, list) and all(
            isinstance(k, int) and not isinstance(k, bool) for k in shape)):
        raise Malformed("'shape' is not a list of integers")
    hint = ("f has a row for every particle, in a spring or not: f = np.zeros_like(x) "
            "(not sized from the largest index in a and b).")
    if shape != [6, 2]:
        shown = "nothing" if shape is None else f"shape {tuple(shape)}"
        if shape == [5, 2]:
            hint = ("the force array has one row too few: it was sized from the largest index "
                    "in the springs (5 rows), and particle 5 is in no spring. " + hint)
        return Result(False, f"{shown} for 6 particles", "shape (6, 2)", hint)
    f = raw.array("f", (6, 2))
    ref = reference().spring_forces(x, v, ALONE_A, ALONE_B, 50.0, 2.0, rest)
    err = rel_error(f, ref)
    if np.all(f[5] == 0.0):             # the lone row is right: the mistake is elsewhere
        hint = (named_spring_mistake(f, x, v, ALONE_A, ALONE_B, 50.0, 2.0, rest) or
                "the lone particle's row is right (0); the springs' forces are not: see 'Hooke "
                "part' and 'damping part'.")
    return Result(within(err, 0.0, 1e-9), f"largest difference {fmt(err)} of the largest force "
                  f"(the lone particle: {fmt(float(np.abs(f[5]).max()))})",
                  "< 1e-09 (relative), 0 on the lone particle", hint)


def damping_run(m: Student) -> tuple[np.ndarray, np.ndarray]:
    x = np.array([[0.0, 0.0], [80.0, 0.0]])
    v = np.zeros_like(x)
    a, b, rest = np.array([0]), np.array([1]), np.array([50.0])
    h = 1e-3
    for _ in range(2000):               # symplectic Euler, unit masses
        v = v + h * forces(m, x, v, a, b, 50.0, 1.0, rest)
        x = x + h * v
    return x, v


DAMPING_START = (np.array([[0.0, 0.0], [80.0, 0.0]]), np.array([[0.0, 0.0], [0.0, 30.0]]))


def measure_damping_removes(m: Student) -> dict:
    x, v = damping_run(m)
    x0, v0 = DAMPING_START             # and one call, moving, for naming a mistake
    return {"x": x, "v": v, "f": forces(m, x0, v0, np.array([0]), np.array([1]), 50.0, 1.0,
                                        np.array([50.0]))}


def judge_damping_removes(raw: Raw) -> Result:
    ks = 50.0

    def energy(x, v):
        return 0.5 * float((v * v).sum()) + 0.5 * ks * (np.linalg.norm(x[1] - x[0]) - 50.0) ** 2
    e0 = energy(np.array([[0.0, 0.0], [80.0, 0.0]]), np.zeros((2, 2)))
    x, v = raw.array("x", (2, 2)), raw.array("v", (2, 2))
    ratio = energy(x, v) / e0
    hint = ("the damping force must oppose the relative velocity along the spring: "
            "-kd ((v_a - v_b) . u) u on a, with u = (x_a - x_b)/|x_a - x_b| (check signs).")
    if not ratio < 0.5:                 # which usual mistake gives their force?
        x0, v0 = DAMPING_START
        hint = named_spring_mistake(raw.array("f", (2, 2)), x0, v0, np.array([0]),
                                    np.array([1]), 50.0, 1.0, np.array([50.0])) or hint
    return Result(bool(ratio < 0.5), f"energy ratio {fmt(ratio)} after 2 s", "< 0.5", hint)


def measure_inputs(m: Student) -> dict:
    x, v, rest = system(5)
    m.spring_forces(x, v, A, B, 50.0, 2.0, rest)
    return {"x": x, "v": v}


def judge_inputs(raw: Raw) -> Result:
    x0, v0, _ = system(5)
    problems = [f"{name} was changed" for name, before in (("x", x0), ("v", v0))
                if not np.array_equal(raw.array(name, before.shape), before)]
    return Result(not problems, "; ".join(problems) or "x and v untouched",
                  "x and v unchanged",
                  "sum the forces into a new array (f = np.zeros_like(x)): x and v are the "
                  "particles' state, which the caller goes on stepping.")


# ----- random springs (a new seed each run) ------------------------------------------------------
RANDOM_CASES = 4


def random_springs() -> list[tuple]:
    """2 to 9 particles, 1 to 14 springs between any two (a particle in several springs, or in
    none, the last one included), ks 0 to 500, kd 0 to 20, rests 0 to 80 px (stretched and
    squashed), velocities any way."""
    rng = cases_rng("spring random")
    cases = []
    for _ in range(RANDOM_CASES):
        n = int(rng.integers(2, 10))
        m = int(rng.integers(1, 15))
        a = rng.integers(0, n, m)
        b = (a + rng.integers(1, n, m)) % n                    # never a spring from a to a
        x = rng.uniform(0.0, 300.0, (n, 2))
        v = rng.normal(0.0, 40.0, (n, 2))
        cases.append((x, v, a.astype(np.intp), b.astype(np.intp), float(rng.uniform(0, 500)),
                      float(rng.uniform(0, 20)), rng.uniform(0.0, 80.0, m)))
    return cases


def measure_random(m: Student) -> dict:
    return {str(k): forces(m, *case) for k, case in enumerate(random_springs())}


def judge_random(raw: Raw) -> Result:
    for k, (x, v, a, b, ks, kd, rest) in enumerate(random_springs()):
        f = raw.array(str(k), x.shape)
        ref = reference().spring_forces(x, v, a, b, ks, kd, rest)
        length = np.linalg.norm(x[a] - x[b], axis=1)
        scale = float((ks * (length + rest) + kd * np.linalg.norm(v[a] - v[b], axis=1)).max())
        tol = rounding(scale, ops=len(a))
        err = float(np.abs(f - ref).max())
        if not err <= tol:
            worst = int(np.nanargmax(np.abs(f - ref).max(axis=1))) if np.isfinite(f).all() else -1
            hint = named_spring_mistake(f, x, v, a, b, ks, kd, rest) or (
                "f_a = -[ks (|l| - rest) + kd (v_a - v_b) . u] u with l = x_a - x_b, u = l/|l|, "
                "f_b = -f_a, summed over every spring a particle is in.")
            return Result(False, f"case {k + 1} of {RANDOM_CASES} ({len(x)} particles, {len(a)} "
                          f"springs, ks {ks:.4g}, kd {kd:.3g}): forces {fmt(err)} off the lab's"
                          + (f" (most at particle {worst})" if worst >= 0 else ""),
                          f"< {tol:.2g} (the lab's rounding)", hint)
    return Result(True, f"{RANDOM_CASES} random sets of springs: the lab's forces within its "
                  "rounding", "the lab's forces, within its rounding")


EXERCISE = Exercise(
    name="spring",
    title="Damped springs: an n-ary force",
    slide="Physics in Computer Animations and Games: 'A Newtonian Particle' / damped springs "
          "(f_a = -[ks(|l| - r) + kd (v_a - v_b).l/|l|] l/|l|, f_b = -f_a)",
    functions=("spring_forces",),
    reference=reference,
    checks=(Check("Hooke part", measure_forces(50.0, 0.0), judge_forces(50.0, 0.0, (
                "f_a = -ks (|l| - rest) l/|l| with l = x_a - x_b: the direction is the UNIT "
                "vector l/|l| (without it the force grows with the length twice), and "
                "f_b = -f_a."))),
            Check("damping part", measure_forces(0.0, 2.0), judge_forces(0.0, 2.0, (
                "the damping term is kd (v_a - v_b) . l/|l|: the relative velocity projected "
                "on the spring, times l/|l| (not kd (v_a - v_b))."))),
            Check("third law", measure_third_law, judge_third_law),
            Check("a particle in no spring", measure_alone, judge_alone),
            Check("damping removes energy", measure_damping_removes, judge_damping_removes),
            Check("inputs kept", measure_inputs, judge_inputs),
            Check("random springs", measure_random, judge_random)),
)
