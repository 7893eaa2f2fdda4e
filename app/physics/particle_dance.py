"""The particle dance: a particle system of a few species that like or dislike each other.

The lecture sorts the forces of a particle system into three families; this system has one of
each kind it needs, all as force objects of app/physics/particles.py:

* spatial interaction (`PairForce`): attraction and repulsion between ANY two particles closer
  than a cut-off R, whichever they are; which pairs that is changes every step, so each step
  first finds them (app/physics/neighbours.py: all pairs, or a uniform grid);
* unary (`Drag` from app/physics/forces.py, f = -k_d v; and `MouseForce`, a position-dependent
  force field around the cursor): each particle on its own;
* n-ary forces (springs between a FIXED set of particles) are the cloth's; there are none here.

The pair rule (a soft attract/repel rule, bounded everywhere, so no step can blow up on a close
encounter as Lennard-Jones' r^-13 would). For particles i and j at distance r, d = x_j - x_i,
F > 0 pulling i towards j:

    f_i = F(r) d / r,   f_j = -f_i                        (Newton's third law: momentum kept)
    F(r) = k_rep (r / b - 1)                              r < b = CORE * R   (always repulsive)
    F(r) = A[s_i, s_j] k_att (1 - |2 r - R - b| / (R - b))  b <= r < R       (a tent, peak mid-way)
    F(r) = 0                                              r >= R

F is continuous (0 at b and at R), so a pair exactly at the cut-off adds nothing whichever
method found it. A[s_i, s_j] in [-1, 1] says how much species s_i likes species s_j: + attracts,
- repels. A is symmetric (s likes t as much as t likes s): otherwise f_j would not be -f_i, the
total momentum would change, and the particles would chase each other for ever (the popular
"particle life" does that on purpose). Here the pair forces conserve momentum and, with drag,
the dance settles into clusters; the mouse stirs it up again.

Integration: symplectic Euler (app/physics/integrators.py), v' = v + h f/m, x' = x + h v', every
mass 1 (so forces are accelerations, px/s^2). Walls: after the step, a particle that left the box
is reflected back into it and its velocity component flipped (a constraint, not a force).

Energy: the rule has kinks (F's slope jumps at b, at the tent's peak and at R; its direction flips
when two particles pass through each other), and there symplectic Euler's energy error does not
average out: without drag the total energy (kinetic + the pair potentials U, `potential`) drifts,
less the smaller the step (tests/test_particle_dance.py compares 60 Hz with 240 Hz). The
lecture's advice holds: "at least a small amount of drag ... if only to enhance numerical
stability".
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Iterator

import numpy as np

from app.physics.forces import Drag
from app.physics.integrators import symplectic_euler
from app.physics.neighbours import (NEIGHBOUR_METHODS, PairBlock, all_pair_blocks, all_pair_tests,
                                    find_pairs, grid_pair_blocks, sort_into_cells)
from app.physics.particles import ParticleSystem
from app.physics.timing import Stopwatch

CORE = 0.3            # the repulsive core is the inner 30 % of the cut-off radius
RULES = ("random", "like_own", "opposites")


def rule_matrix(rules: str, species: int, rng: np.random.Generator) -> np.ndarray:
    """The symmetric matrix A (species x species): A[s, t] > 0 s and t attract, < 0 repel.
    random: uniform in [-1, 1] from the seed, to one decimal (as the colour key shows it);
    like_own: +1 own species, -0.5 the others; opposites: -0.5 own species, +1 the others."""
    if rules == "random":
        a = rng.uniform(-1.0, 1.0, (species, species))
        return np.round(np.triu(a) + np.triu(a, 1).T, 1)        # mirror the upper triangle
    own, other = {"like_own": (1.0, -0.5), "opposites": (-0.5, 1.0)}[rules]
    return np.where(np.eye(species, dtype=bool), own, other)


@dataclass
class PairRule:
    """The soft attract/repel rule above: cut-off R (px), k_att and k_rep (px/s^2), matrix A."""

    matrix: np.ndarray
    cutoff: float
    attraction: float
    repulsion: float

    def magnitude(self, r: np.ndarray, a: np.ndarray) -> np.ndarray:
        """F(r) for pairs at distances r whose species like each other by a = A[s_i, s_j]."""
        R = self.cutoff
        b = CORE * R
        peak, w = (b + R) / 2.0, (R - b) / 2.0          # the tent's peak and half-width
        core = self.repulsion * np.minimum(r / b - 1.0, 0.0)        # r < b only (0 from b on)
        tent = a * self.attraction * np.maximum(1.0 - np.abs(r - peak) / w, 0.0)  # b < r < R only
        return core + tent

    def potential(self, r: np.ndarray, a: np.ndarray) -> np.ndarray:
        """U(r) = -integral from r to R of F: the pair's potential energy (0 beyond R), so that
        F = dU/dr. The tent's area from r out to R is w z^2/2 for z = (R - r)/w <= 1 and
        w (1 - (2 - z)^2/2) beyond (w = (R - b)/2 its half-width); the core adds
        k_rep (b - r)^2 / (2b)."""
        R = self.cutoff
        b = CORE * R
        w = (R - b) / 2.0
        z = np.clip((R - r) / w, 0.0, 2.0)
        area = np.where(z <= 1.0, z * z / 2.0, 1.0 - (2.0 - z) ** 2 / 2.0)
        core = np.maximum(b - r, 0.0)
        return -a * self.attraction * w * area + self.repulsion * core * core / (2.0 * b)


class PairForce:
    """Spatial interaction: the pair rule over every pair closer than the cut-off, found by
    `method` ("all_pairs" or "grid", switchable at any time). After each evaluation, `tests` is
    the number of pair tests the search made and `pairs` the pairs that interacted;
    `watch.spent["search"]` sums the seconds spent finding pairs (the rest of the interaction's
    time is the force itself)."""

    def __init__(self, rule: PairRule, species: np.ndarray, box: tuple[float, float],
                 method: str = "grid"):
        if method not in NEIGHBOUR_METHODS:
            raise ValueError(f"unknown neighbour method {method!r}; accepted: "
                             + ", ".join(NEIGHBOUR_METHODS))
        self.rule, self.species, self.box, self.method = rule, species, box, method
        self.tests = 0
        self.pairs = 0
        self.watch = Stopwatch()

    @property
    def search_seconds(self) -> float:
        """Seconds spent finding pairs, summed over every evaluation."""
        return self.watch.spent["search"]

    def pair_blocks(self, x: np.ndarray) -> Iterator[PairBlock]:
        """The pairs closer than R, block by block, by the method in use; sets `tests`."""
        R = self.rule.cutoff
        if self.method == "grid":
            cells = sort_into_cells(x, R, self.box)
            self.tests = cells.tests
            return grid_pair_blocks(x, R, self.box, cells)
        self.tests = all_pair_tests(len(x))
        return all_pair_blocks(x, R)

    def forces_of(self, dx: np.ndarray, dy: np.ndarray, r: np.ndarray, i: np.ndarray,
                  j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """f_i = (fx, fy) of each pair (i, j) at separation d = x_j - x_i = (dx, dy), r = |d|
        (f_j = -f_i)."""
        s = self.species
        likes = self.rule.matrix.ravel().take(s.take(i) * len(self.rule.matrix) + s.take(j))
        # (likes = A[s_i, s_j], read from the flattened matrix: half the time of A[s[i], s[j]])
        scale = self.rule.magnitude(r, likes) / np.maximum(r, 1e-12)   # r = 0: d = 0, no NaN
        return scale * dx, scale * dy

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        n = len(x)
        fx_sum, fy_sum = np.zeros(n), np.zeros(n)
        self.pairs = 0
        with self.watch("search"):
            blocks = self.pair_blocks(x)
        for b in timed(blocks, self.watch("search")):
            fx, fy = self.forces_of(b.dx, b.dy, np.sqrt(b.r2), b.i, b.j)   # the search's d
            # f_i += f and f_j -= f for every pair (Newton's third law); bincount sums the
            # repeated indices (replaces `for each pair: f[i] += fi; f[j] -= fi`)
            fx_sum += np.bincount(b.i, fx, n) - np.bincount(b.j, fx, n)
            fy_sum += np.bincount(b.i, fy, n) - np.bincount(b.j, fy, n)
            self.pairs += len(b.i)
        f[:, 0] += fx_sum
        f[:, 1] += fy_sum


def timed(blocks: Iterator[PairBlock], lap) -> Iterator[PairBlock]:
    """The blocks of an iterator, each one's making timed by `lap` (a Stopwatch's context): the
    search's share of the time, measured outside both the search and the force."""
    it = iter(blocks)
    while True:
        with lap:
            block = next(it, None)
        if block is None:
            return
        yield block


class MouseForce:
    """Unary, position-dependent: particles within `radius` of the point are pulled towards it
    (strength > 0, the LMB) or pushed away (< 0, the RMB), f = 4 s (1 - d/rho) (p - x) / rho,
    d = |p - x| < rho: zero at the point and at the rim, |f| at most |s| (half-way out)."""

    def __init__(self, point: tuple[float, float], strength: float, radius: float):
        self.point = np.asarray(point, dtype=float)
        self.strength, self.radius = float(strength), float(radius)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        to_point = self.point - x
        d = np.sqrt(np.einsum("ij,ij->i", to_point, to_point))
        near = d < self.radius
        rho = self.radius
        f[near] += (4.0 * self.strength / rho * (1.0 - d[near] / rho))[:, None] * to_point[near]


def reflect_into_box(x: np.ndarray, v: np.ndarray, box: tuple[float, float]) -> None:
    """Walls: fold every coordinate back into [0, w] x [0, h] as a mirror would (however far out
    it went: the fold repeats with period 2w) and flip the velocity component of each particle
    reflected an odd number of times. In place; only the coordinates outside are touched."""
    size = np.asarray(box, dtype=float)
    row, axis = np.nonzero((x < 0.0) | (x > size))            # the coordinates outside
    if len(row) == 0:
        return
    side = size[axis]
    period = np.floor(x[row, axis] / side)                     # +-1, +-2, ... outside
    folded = np.mod(x[row, axis], 2.0 * side)
    x[row, axis] = np.where(folded > side, 2.0 * side - folded, folded)
    v[row, axis] *= np.where(np.mod(period, 2.0) == 1.0, -1.0, 1.0)


class Timed:
    """Wraps a force and adds the seconds its accumulate() takes to spent[name]: the HUD's cost of
    each effect, measured here so the force's own code stays the formula."""

    def __init__(self, name: str, force, spent: dict[str, float]):
        self.name, self.force, self.spent = name, force, spent

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        t0 = time.perf_counter()
        self.force.accumulate(ps, x, v, f)
        self.spent[self.name] += time.perf_counter() - t0


EFFECTS = ("interaction", "drag", "walls")


class ParticleDance:
    """n particles of `species` kinds in a box (w, h), from a seed: the state (x, v in a
    ParticleSystem, every mass 1), the forces that are on, and the step.

    `on` names the effects simulated: "interaction" (the pair forces), "drag", "walls". An effect
    that is off is not in the force list at all (no search, no zero force)."""

    def __init__(self, n: int, species: int, box: tuple[float, float], rule: PairRule,
                 rng: np.random.Generator, on: set[str], drag: float = 1.0,
                 method: str = "grid", speed: float = 30.0):
        self.box = (float(box[0]), float(box[1]))
        x = rng.uniform(0.0, 1.0, (n, 2)) * self.box
        v = rng.normal(0.0, speed, (n, 2))
        self.species = rng.integers(0, species, n)
        self.ps = ParticleSystem(x, v, 1.0)
        self.pair_force = PairForce(rule, self.species, self.box, method)
        self.drag = Drag(drag)
        self.mouse: MouseForce | None = None
        self.spent = {name: 0.0 for name in (*EFFECTS, "mouse")}
        self.set_effects(on)

    def set_effects(self, on: set[str]) -> None:
        """Build the force list from the effects that are on (and the mouse, while held)."""
        self.on = set(on)
        forces = [("interaction", self.pair_force), ("drag", self.drag), ("mouse", self.mouse)]
        self.ps.forces = [Timed(name, force, self.spent) for name, force in forces
                          if force is not None and (name in self.on or name == "mouse")]
        if "interaction" not in self.on:
            self.pair_force.tests = self.pair_force.pairs = 0

    def set_mouse(self, force: MouseForce | None) -> None:
        """Start (a MouseForce) or stop (None) the cursor's pull or push."""
        self.mouse = force
        self.set_effects(self.on)

    def step(self, h: float) -> None:
        """One symplectic Euler step of h seconds, then the walls."""
        symplectic_euler(self.ps, h)               # v' = v + h f(x, v) / m;  x' = x + h v'
        if "walls" in self.on:
            t0 = time.perf_counter()
            reflect_into_box(self.ps.x, self.ps.v, self.box)
            self.spent["walls"] += time.perf_counter() - t0

    def kinetic_energy(self) -> float:
        """Sum of m v^2 / 2 (every mass 1), px^2/s^2."""
        return 0.5 * float(np.einsum("ij,ij->", self.ps.v, self.ps.v))

    def potential_energy(self) -> float:
        """Sum of the pair potentials U(r) over the pairs within the cut-off, px^2/s^2."""
        pf = self.pair_force
        i, j, _ = find_pairs("grid", self.ps.x, pf.rule.cutoff, self.box)
        d = self.ps.x[j] - self.ps.x[i]
        r = np.sqrt(np.einsum("ij,ij->i", d, d))
        return float(pf.rule.potential(r, pf.rule.matrix[self.species[i], self.species[j]]).sum())

    def momentum(self) -> np.ndarray:
        """Total momentum, sum of m v (every mass 1)."""
        return self.ps.v.sum(axis=0)


__all__ = ["CORE", "RULES", "EFFECTS", "rule_matrix", "PairRule", "PairForce", "MouseForce",
           "reflect_into_box", "Timed", "ParticleDance", "NEIGHBOUR_METHODS"]
