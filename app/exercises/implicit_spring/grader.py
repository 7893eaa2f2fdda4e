"""Grader of exercises/implicit_spring.py: one backward (implicit) Euler step of a damped spring
system, Baraff & Witkin's linear system built and solved for a few particles.

Reference: app.physics.integrators.implicit_euler on a ParticleSystem with the lab's Gravity and
Springs (app/physics/forces.py: their Jacobians as products, solved by conjugate gradients), and
the same Jacobians as dense matrices for A and rhs. Each measure sends back what the student's
functions returned (positions, velocities, A and rhs); each judge does the physics:
  free fall        no springs: v' = v + h g and x' = x + h v' exactly (backward Euler moves with
                   the NEW velocity); the pinned particle (w = 0) stays where it is
  energy factor    one undamped spring along its axis (omega = 10/s) at h = 1 s, omega h = 10
                   (five times past the explicit limit omega h = 2): each step keeps exactly
                   1/(1 + (omega h)^2) = 1/101 of the energy (+- 1e-6 relative), the backward
                   Euler amplification of a linear oscillator
  A and rhs        5 particles, 7 damped springs (one squashed), one pinned, gravity, h = 0.1 s:
                   A dv = rhs gives the lab's linearised step's dv (1e-9 relative: the exact
                   linearisation, but for a squashed spring's transverse part, clamped at 0 as
                   the lab does); a correct system in another form (M - h D - h^2 K, with M's
                   rows) gives it too
  the step         the same system: (x', v') from implicit_euler_step agree with the lab's to 1e-9
  far past limit   a stiff chain (ks 5000, omega_max 138/s) hanging, disturbed, at h = 0.2 s (14x
                   the explicit limit 2/omega_max): for 40 steps its energy above rest never rises
                   and ends below 1% of the start (explicit Euler blows up here in a few steps)
  inputs kept      x and v are not changed
A failed step is compared with the usual mistakes (explicit Euler, rhs without h K v, h K for
h^2 K, K without its transverse part, ...: hints.py) and the hint names the one it matches.
  random systems   4 random systems (seeded; pins at rest, gravity any way): A and rhs and the
                   step against the lab's linear system, within eps x cond(A) x |dv|
Every pinned particle of these checks is at rest (v = 0): the starter's 'it won't move' and the
lab's step agree, and a step that holds the pin still passes.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.base import (EPS, BadAnswer, Check, Exercise, Raw, Result, Student, array_of,
                                cases_rng, fmt, within)
from app.exercises.implicit_spring import hints
from app.exercises.implicit_spring.hints import _springs, name_mistake


# ----- the lab's answer --------------------------------------------------------------------------
def particle_system(x, v, w, a, b, ks, kd, rest, g):
    from app.physics.forces import Gravity, Springs
    from app.physics.particles import ParticleSystem
    w = np.asarray(w, dtype=float)
    mass = np.where(w > 0, 1.0 / np.where(w > 0, w, 1.0), 1.0)     # pinned: any mass, w = 0
    forces = [Gravity(g)] + ([Springs(a, b, ks, kd, rest)] if len(a) else [])
    return ParticleSystem(x, v, mass, forces, pinned=np.flatnonzero(w == 0))


def dense(product, n: int) -> np.ndarray:
    """A Jacobian product w -> J w (w of shape (n, 2)) as the 2n x 2n matrix J."""
    cols = [product(np.eye(2 * n)[k].reshape(n, 2)).ravel() for k in range(2 * n)]
    return np.array(cols).T


def reference() -> SimpleNamespace:
    from app.physics.integrators import implicit_euler

    def linear_system(x, v, w, a, b, ks, kd, rest, g, h):
        ps = particle_system(x, v, w, a, b, ks, kd, rest, g)
        n = ps.n
        f0 = ps.force(ps.x, ps.v).copy()
        K, D = ps.force_jacobians(ps.x, ps.v)
        Kd, Dd = dense(K, n), dense(D, n)
        W = np.diag(np.repeat(ps.inv_mass, 2))
        A = np.eye(2 * n) - h * W @ Dd - h * h * W @ Kd
        return A, h * W @ (f0.ravel() + h * Kd @ ps.v.ravel())

    def implicit_euler_step(x, v, w, a, b, ks, kd, rest, g, h):
        ps = particle_system(x, v, w, a, b, ks, kd, rest, g)
        implicit_euler(ps, h)
        return ps.x, ps.v
    return SimpleNamespace(linear_system=linear_system, implicit_euler_step=implicit_euler_step)


# ----- the usual mistakes, for the hints: in hints.py --------------------------------------------
mistaken_step = hints.mistaken_step         # imported from here too (tests/test_exercises.py)


# ----- the systems the checks use ----------------------------------------------------------------
G = np.array([0.0, 900.0])
NO_SPRINGS = (np.zeros(0, np.intp), np.zeros(0, np.intp), 0.0, 0.0, np.zeros(0))


def free_fall_inputs() -> tuple:
    x = np.array([[100.0, 50.0], [300.0, 80.0], [200.0, 10.0]])
    v = np.array([[20.0, -40.0], [0.0, 0.0], [-5.0, 30.0]])
    a, b, ks, kd, rest = NO_SPRINGS
    return x, v, np.array([1.0, 0.0, 0.5]), a, b, ks, kd, rest, G, 0.05


OMEGA, ONE_H = 10.0, 1.0         # one spring: ks 100, mass 1


def one_spring_inputs() -> tuple:
    x = np.array([[0.0, 0.0], [120.0, 0.0]])       # rest 100, stretched 20 along x
    return (x, np.zeros((2, 2)), np.array([0.0, 1.0]), np.array([0]), np.array([1]),
            OMEGA ** 2, 0.0, np.array([100.0]), np.zeros(2), ONE_H)


def random_inputs() -> tuple:
    rng = np.random.default_rng(4)
    x = rng.uniform(0.0, 200.0, (5, 2))
    v = rng.normal(0.0, 30.0, (5, 2))
    a, b = np.array([0, 1, 2, 3, 0, 1, 2]), np.array([1, 2, 3, 4, 2, 3, 4])
    rest = 0.8 * np.linalg.norm(x[a] - x[b], axis=1)          # stretched, but for one:
    rest[6] *= 1.5                                            # squashed, 1.2x its length
    w = np.array([0.0, 1.0, 0.5, 2.0, 1.0])
    v[w == 0] = 0.0         # the starter: a pinned particle "won't move" (no velocity to keep)
    return x, v, w, a, b, 400.0, 3.0, rest, G, 0.1


CHAIN_N, CHAIN_KS, CHAIN_L, CHAIN_H, CHAIN_STEPS = 8, 5000.0, 40.0, 0.2, 40


def chain_inputs() -> tuple:
    """A chain hanging from its pinned top at rest (each spring stretched by the weight below
    it), then disturbed: the bottom pulled down, a sideways swing."""
    n = CHAIN_N
    a, b = np.arange(n - 1), np.arange(1, n)
    stretch = (n - 1 - np.arange(n - 1)) * G[1] / CHAIN_KS
    y = np.concatenate([[100.0], 100.0 + np.cumsum(CHAIN_L + stretch)])
    x = np.stack([np.full(n, 480.0), y], axis=1)
    rest_x = x.copy()
    x[-1, 1] += 12.0
    x[3, 1] -= 6.0
    v = np.zeros_like(x)
    v[1:, 0] = 150.0 * np.sin(0.7 * np.arange(1, n))
    w = np.ones(n)
    w[0] = 0.0
    return (x, v, w, a, b, CHAIN_KS, 0.0, np.full(n - 1, CHAIN_L), G, CHAIN_H), rest_x


def energy(x, v, w, a, b, ks, rest, g) -> float:
    """Kinetic + spring + gravity energy of the free particles (y down: potential -m g y)."""
    m = np.where(w > 0, 1.0 / np.where(w > 0, w, 1.0), 0.0)
    length = np.linalg.norm(x[a] - x[b], axis=1) if len(a) else np.zeros(0)
    return float(0.5 * (m[:, None] * v * v).sum() + 0.5 * ks * ((length - rest) ** 2).sum()
                 - (m[:, None] * g * x).sum())


# ----- calling the student's functions -----------------------------------------------------------
def step(m: Student, inputs: tuple) -> tuple[np.ndarray, np.ndarray]:
    x, v = inputs[0], inputs[1]
    out = m.implicit_euler_step(x.copy(), v.copy(), *inputs[2:])
    if not isinstance(out, tuple) or len(out) != 2:
        raise BadAnswer(f"implicit_euler_step returned {type(out).__name__}; expected a pair "
                        "(x_new, v_new)" + (" (no return statement?)" if out is None else ""))
    return (array_of(out[0], x.shape, "implicit_euler_step's x_new"),
            array_of(out[1], x.shape, "implicit_euler_step's v_new"))


def mismatch(raw: Raw, inputs: tuple) -> tuple[float, str]:
    """Relative difference of the sent (x', v') from the lab's step, and the mistake named."""
    x, v = inputs[0], inputs[1]
    got = (raw.array("x", x.shape), raw.array("v", v.shape))
    want = reference().implicit_euler_step(*inputs)
    scale = max(float(np.abs(want[1] - v).max()), 1e-300)
    err = max(float(np.abs(got[1] - want[1]).max()) / scale,
              float(np.abs(got[0] - want[0]).max()) / (inputs[-1] * scale))
    return (err if np.isfinite(err) else math.nan), name_mistake(got, inputs)


STEP_HINT = ("dv solves (I - h W D - h^2 W K) dv = h W (f0 + h K v) (+ h g for each free "
             "particle); v' = v + dv, x' = x + h v'.")


# ----- the checks --------------------------------------------------------------------------------
def measure_free_fall(m: Student) -> dict:
    x, v = step(m, free_fall_inputs())
    return {"x": x, "v": v}


def judge_free_fall(raw: Raw) -> Result:
    inputs = free_fall_inputs()
    x, v, w, h = inputs[0], inputs[1], inputs[2], inputs[-1]
    free = (w > 0)[:, None]
    v_want = v + h * G * free
    x_want = x + h * v_want
    got_x, got_v = raw.array("x", x.shape), raw.array("v", v.shape)
    err = max(float(np.abs(got_x - x_want).max()), float(np.abs(got_v - v_want).max()))
    hint = name_mistake((got_x, got_v), inputs) or STEP_HINT
    pinned = w == 0
    if not (np.isfinite(got_x[pinned]).all() and np.isfinite(got_v[pinned]).all()):
        hint = ("NaN at the pinned particle (w = 0): a mass 1/w is infinite there, and 0 x inf "
                "is NaN. Add h g only where w > 0 (np.where(w > 0, ...)); never divide by w. "
                + STEP_HINT)
    return Result(within(err, 0.0, 1e-9), f"{fmt(err)} off v + h g and x + h v'",
                  "< 1e-09 (exact)", hint)


def measure_energy(m: Student) -> dict:
    inputs = one_spring_inputs()
    x, v = inputs[0], inputs[1]
    states = []
    for _ in range(3):
        x, v = step(m, (x, v, *inputs[2:]))
        states.append((x, v))
    return {"x": [s[0] for s in states], "v": [s[1] for s in states]}


def judge_energy(raw: Raw) -> Result:
    inputs = one_spring_inputs()
    x0, v0, w, a, b, ks, _, rest, g, h = inputs
    xs, vs = raw.array("x", (3, 2, 2)), raw.array("v", (3, 2, 2))
    energies = [energy(x0, v0, w, a, b, ks, rest, g)] + [
        energy(x, v, w, a, b, ks, rest, g) for x, v in zip(xs, vs)]
    ratios = [e1 / e0 if e0 > 0 else math.nan for e0, e1 in zip(energies, energies[1:])]
    z = OMEGA * h
    want = 1.0 / (1.0 + z * z)
    good = [within(r, want, 1e-6 * want) for r in ratios]
    ok = all(good)
    hint = STEP_HINT
    if not ok:                          # name the mistake from the first step that is off
        k = good.index(False)
        before = (x0, v0) if k == 0 else (xs[k - 1], vs[k - 1])
        hint = name_mistake((xs[k], vs[k]), (*before, *inputs[2:])) or STEP_HINT
        finite = [r for r in ratios if math.isfinite(r)]
        if finite and all(r > 1.0 for r in finite):
            hint = ("the energy GROWS (backward Euler only ever takes energy out of a spring): "
                    + hint)
    return Result(ok, f"energy x {', '.join(f'{r:.6g}' for r in ratios)} per step at omega h = "
                  f"{z:g}", f"{want:.6g} = 1/(1 + (omega h)^2) each, +- 1e-6 relative", hint)


def measure_system(m: Student) -> dict:
    inputs = random_inputs()
    x, v = inputs[0], inputs[1]
    out = m.linear_system(x.copy(), v.copy(), *inputs[2:])
    if not isinstance(out, tuple) or len(out) != 2:
        raise BadAnswer(f"linear_system returned {type(out).__name__}; expected a pair (A, rhs)")
    n2 = x.size
    return {"A": array_of(out[0], (n2, n2), "linear_system's A"),
            "rhs": array_of(out[1], (n2,), "linear_system's rhs")}


def judge_system(raw: Raw) -> Result:
    inputs = random_inputs()
    x, v, h = inputs[0], inputs[1], inputs[-1]
    n2 = x.size
    A, rhs = raw.array("A", (n2, n2)), raw.array("rhs", (n2,))
    A_ref, rhs_ref = reference().linear_system(*inputs)
    dv_ref = np.linalg.solve(A_ref, rhs_ref)
    try:
        dv = np.linalg.solve(A, rhs)
    except np.linalg.LinAlgError:
        return Result(False, "A is singular", "A dv = rhs solvable", "A = I - h W D - h^2 W K is "
                      "never singular for springs that pull (its free rows are I plus positive "
                      "terms): check the blocks' rows and columns (2i, 2i+1).")
    err = float(np.abs(dv - dv_ref).max() / np.abs(dv_ref).max())
    v_new = v + dv.reshape(v.shape)
    hint = name_mistake((x + h * v_new, v_new), inputs)
    def blocks(M: np.ndarray) -> np.ndarray:     # which 2 x 2 blocks (particle pairs) hold values
        return np.abs(M).reshape(n2 // 2, 2, n2 // 2, 2).max(axis=(1, 3)) > \
            1e-12 * np.abs(A_ref).max()
    misplaced = np.argwhere(blocks(A) != blocks(A_ref))
    if not hint and len(misplaced):
        i, j = misplaced[0]
        mine, lab = ("empty", "filled") if blocks(A_ref)[i, j] else ("filled", "empty")
        hint = (f"A's block for particles ({i}, {j}) is {mine} where the lab's is {lab}: "
                "block (i, j) is rows 2i, 2i+1 and columns 2j, 2j+1 (the particle index doubled), "
                "K[2*i:2*i+2, 2*j:2*j+2]; a pinned particle's rows are those of I.")
    elif not hint and within(float(np.abs(A - A_ref).max()), 0.0,
                             1e-9 * np.abs(A_ref).max()):
        hint = "A is right; rhs is not: rhs = h W (f0 + h K v), plus h g for each free particle."
    elif not hint and within(float(np.abs(rhs - rhs_ref).max()), 0.0, 1e-9 * np.abs(rhs_ref).max()):
        hint = ("rhs is right; A is not: A = I - h W D - h^2 W K, block (i, j) in rows 2i, 2i+1 "
                "and columns 2j, 2j+1; each spring adds K_aa to (a, a) and (b, b), -K_aa to "
                "(a, b) and (b, a).")
    return Result(within(err, 0.0, 1e-9), f"the solution of A dv = rhs is {fmt(err)} off the "
                  "linearised step's", "< 1e-09 (relative)", hint or STEP_HINT)


def measure_step(m: Student) -> dict:
    x, v = step(m, random_inputs())
    return {"x": x, "v": v}


def judge_step(raw: Raw) -> Result:
    err, hint = mismatch(raw, random_inputs())
    return Result(within(err, 0.0, 1e-9), f"{fmt(err)} off the lab's linearised step (relative)",
                  "< 1e-09", hint or STEP_HINT)


def measure_chain(m: Student) -> dict:
    inputs, _ = chain_inputs()
    x, v = inputs[0], inputs[1]
    xs, vs = [], []
    for _ in range(CHAIN_STEPS):
        x, v = step(m, (x, v, *inputs[2:]))
        xs.append(x)
        vs.append(v)
        if not (np.isfinite(x).all() and np.isfinite(v).all()):
            break                    # blown up: no need for more
    return {"x": xs, "v": vs}


def omega_max(inputs: tuple) -> float:
    x, v, w, a, b, ks, kd, rest = inputs[:8]
    _, K, _ = _springs(x, v, a, b, ks, kd, rest)
    return math.sqrt(max(float(np.linalg.eigvals(-np.diag(np.repeat(w, 2)) @ K).real.max()), 0))


def judge_chain(raw: Raw) -> Result:
    inputs, rest_x = chain_inputs()
    x0, v0, w, a, b, ks, _, rest, g, h = inputs
    xs, vs = raw.array("x", (None, CHAIN_N, 2)), raw.array("v", (None, CHAIN_N, 2))
    e_rest = energy(rest_x, np.zeros_like(v0), w, a, b, ks, rest, g)
    e = [energy(x0, v0, w, a, b, ks, rest, g) - e_rest] + [
        energy(x, v, w, a, b, ks, rest, g) - e_rest for x, v in zip(xs, vs)]
    e = np.array(e)
    limit = 2.0 / omega_max(inputs)
    done = len(xs) == CHAIN_STEPS and np.isfinite(e).all()
    rises = int((np.diff(e) > 1e-9 * e[0]).sum()) if done else -1
    end = float(e[-1] / e[0]) if done else math.nan
    ok = done and rises == 0 and end < 0.01
    hint = ""
    if not done:
        hint = "the chain blew up (NaN or inf): "
    elif rises:
        hint = "the energy rose: "
    hint += (f"backward Euler is stable at any step: at h = {h:g} s, {h / limit:.0f}x the "
             f"explicit limit 2/omega_max = {1000 * limit:.1f} ms, it only loses energy. "
             "The checks 'A and rhs' and 'the step' compare one step with the lab's and name "
             "the usual mistakes. " + STEP_HINT)
    measured = (f"energy above rest rose in {rises} of {CHAIN_STEPS} steps, ends at "
                f"{fmt(end)} of the start" if done else f"non-finite after {len(xs)} steps")
    return Result(bool(ok), measured + f" (h = {h / limit:.0f}x the explicit limit)",
                  "never rising, < 0.01 of the start after 40 steps", hint)


def measure_inputs(m: Student) -> dict:
    inputs = random_inputs()
    x, v = inputs[0].copy(), inputs[1].copy()
    m.implicit_euler_step(x, v, *inputs[2:])
    m.linear_system(x, v, *inputs[2:])
    return {"x": x, "v": v}


def judge_inputs(raw: Raw) -> Result:
    inputs = random_inputs()
    problems = [f"{name} was changed" for name, k in (("x", 0), ("v", 1))
                if not np.array_equal(raw.array(name, inputs[k].shape), inputs[k])]
    return Result(not problems, "; ".join(problems) or "x and v untouched", "x and v unchanged",
                  "compute into new arrays (v + dv, x + h * v_new): x += ... changes the "
                  "caller's state, which it may still need (to draw, to measure the energy).")


# ----- random systems (a new seed each run) ------------------------------------------------------
RANDOM_CASES = 4


def random_systems() -> list[tuple]:
    """2 to 6 particles, 1 to 8 springs (stretched and squashed: rest 0.5 to 1.5 of the length),
    ks 10 to 5000, kd 0 to 10, inverse masses 0.2 to 3 or 0 (pinned, at rest), gravity of any
    size (0 to 1500 px/s^2) pointing any way, h from 1 ms to 0.5 s."""
    rng = cases_rng("implicit_spring random")
    cases = []
    for _ in range(RANDOM_CASES):
        n = int(rng.integers(2, 7))
        pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
        m = int(rng.integers(1, min(8, len(pairs)) + 1))
        ab = np.array([pairs[c] for c in rng.choice(len(pairs), m, replace=False)])
        a, b = ab[:, 0].astype(np.intp), ab[:, 1].astype(np.intp)
        x = rng.uniform(0.0, 300.0, (n, 2))
        w = np.where(rng.random(n) < 0.25, 0.0, rng.uniform(0.2, 3.0, n))
        w[int(rng.integers(0, n))] = float(rng.uniform(0.2, 3.0))      # one free at least
        v = rng.normal(0.0, 50.0, (n, 2)) * (w > 0)[:, None]
        rest = np.linalg.norm(x[a] - x[b], axis=1) * rng.uniform(0.5, 1.5, m)
        angle = rng.uniform(0.0, 2 * math.pi)
        g = rng.uniform(0.0, 1500.0) * np.array([math.cos(angle), math.sin(angle)])
        cases.append((x, v, w, a, b, float(10 ** rng.uniform(1.0, 3.7)),
                      float(rng.uniform(0.0, 10.0)) * (rng.random() < 0.7), rest, g,
                      float(10 ** rng.uniform(-3.0, -0.3))))
    return cases


def measure_random(m: Student) -> dict:
    out = {}
    for k, inputs in enumerate(random_systems()):
        x, v = inputs[0], inputs[1]
        system = m.linear_system(x.copy(), v.copy(), *inputs[2:])
        if not isinstance(system, tuple) or len(system) != 2:
            raise BadAnswer(f"linear_system returned {type(system).__name__}; expected a pair "
                            "(A, rhs)")
        xn, vn = step(m, inputs)
        out[str(k)] = {"A": array_of(system[0], (x.size, x.size), "linear_system's A"),
                       "rhs": array_of(system[1], (x.size,), "linear_system's rhs"),
                       "x": xn, "v": vn}
    return out


def judge_random(raw: Raw) -> Result:
    """Each system's dv from the student's A and rhs (solved here) and their step, against the
    lab's linear system solved directly, within its rounding: eps x cond(A) x the size of dv and
    v, times 64 and the system's size, or 4x the distance of the lab's own step (conjugate
    gradients, to their tolerance) from that solution, whichever is larger."""
    worst = 0.0
    for k, inputs in enumerate(random_systems()):
        x, v, w, h, g = inputs[0], inputs[1], inputs[2], inputs[-1], inputs[-2]
        one = Raw(raw.values.get(str(k)))
        n2 = x.size
        A, rhs = one.array("A", (n2, n2)), one.array("rhs", (n2,))
        xs, vs = one.array("x", x.shape), one.array("v", v.shape)
        A_ref, rhs_ref = reference().linear_system(*inputs)
        dv_ref = np.linalg.solve(A_ref, rhs_ref).reshape(v.shape)
        scale = float(np.abs(dv_ref).max() + np.abs(v).max())
        tol_v = 64 * EPS * float(np.linalg.cond(A_ref)) * scale * n2
        # the lab's own step solves by conjugate gradients, to its tolerance: where that is
        # looser than the direct solve's rounding, the lab's own distance (x4) is the bound
        lab_x, lab_v = reference().implicit_euler_step(*inputs)
        tol_v = max(tol_v, 4 * float(np.abs(lab_v - v - dv_ref).max()))
        tol_x = max(h * tol_v + 64 * EPS * float(np.abs(x).max()),
                    4 * float(np.abs(lab_x - x - h * (v + dv_ref)).max()))
        try:
            dv = np.linalg.solve(A, rhs).reshape(v.shape)
        except np.linalg.LinAlgError:
            dv = np.full(v.shape, math.nan)
        errs = {"A and rhs": float(np.abs(dv - dv_ref).max()) / tol_v,
                "the step": max(float(np.abs(vs - v - dv_ref).max()) / tol_v,
                                float(np.abs(xs - x - h * (v + dv_ref)).max()) / tol_x)}
        bad = [name for name, e in errs.items() if not e <= 1.0]
        worst = max([worst] + [e for e in errs.values() if math.isfinite(e)])
        if bad:
            got = (x + h * (v + dv), v + dv) if bad[0] == "A and rhs" else (xs, vs)
            hint = name_mistake(got, inputs) or STEP_HINT
            off = float(np.abs(got[1] - v - dv_ref).max())
            where = (f"case {k + 1} of {RANDOM_CASES} ({len(x)} particles, {len(inputs[3])} "
                     f"springs, {int((w == 0).sum())} pinned, ks {inputs[5]:.4g}, kd "
                     f"{inputs[6]:.3g}, g ({g[0]:.4g}, {g[1]:.4g}), h {h:.3g} s)")
            return Result(False, f"{where}: {' and '.join(bad)} {fmt(off)} px/s off the lab's "
                          f"dv ({fmt(off / max(float(np.abs(dv_ref).max()), 1e-300))} relative)",
                          f"< {tol_v:.2g} px/s (the lab's own accuracy here)", hint)
    return Result(True, f"{RANDOM_CASES} random systems: A and rhs and the step within "
                  f"{worst:.2g} of the rounding bound", "within the lab's rounding")


EXERCISE = Exercise(
    name="implicit_spring",
    title="Implicit Euler: Baraff & Witkin's linear system for a spring system",
    slide="Cloth Simulation: 'Backwards Euler' (first-order approximation, grouping all v terms) "
          "and 'Baraff/Witkin: Large Steps in Cloth Simulation' (force derivatives; mass "
          "modification)",
    functions=("linear_system", "implicit_euler_step"),
    reference=reference,
    checks=(Check("free fall", measure_free_fall, judge_free_fall),
            Check("energy factor per step", measure_energy, judge_energy),
            Check("A and rhs", measure_system, judge_system),
            Check("the step", measure_step, judge_step),
            Check("stable far past the limit", measure_chain, judge_chain),
            Check("inputs kept", measure_inputs, judge_inputs),
            Check("random systems", measure_random, judge_random)),
)
