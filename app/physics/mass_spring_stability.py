"""How large a step the mass-spring cloth takes with an explicit integrator: its highest
frequency omega_max by power iteration, the damping rate of that mode, and each integrator's
predicted limit on it (2/omega_max undamped for the Euler family and Verlet, 2.83/omega_max for
RK4; less with damping).

The limit belongs to a state, not to the cloth: a cloth that falls, drapes or is flung shears
its cells and stretches its springs, and its omega_max rises with them. `LimitWatch` follows
it: it re-estimates on the current state as the cloth moves, keeps the lowest limit seen, and
puts a step into a band: stable, marginal or past the limit (MARGINAL, measured)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from app.physics.integrators import INTEGRATORS
from app.physics.particles import ParticleSystem
from app.physics.spring_forces import block_product

if TYPE_CHECKING:                    # an annotation only (mass_spring imports nothing from here)
    from app.physics.mass_spring import MassSpringSystem


# ----- stability: the highest frequency and the explicit limit -----------------------------------
REFINE_ROUNDS = 3       # fixed-point rounds of top_mode's damping rate (within 0.5 % after 3)


def top_mode(ps: MassSpringSystem, iterations: int = 40, start: np.ndarray | None = None,
             rounds: int = REFINE_ROUNDS) -> tuple[float, float, np.ndarray]:
    """(omega_max, c, shapes): the highest angular frequency of the free particles, by power
    iteration on M^-1 K (K = -df/dx, definite blocks); a damping rate c; and the three vectors
    the iterations ended on (the top mode, the fastest-damped mode and the refined one, stacked
    (3, 2, n)): pass them back as `start` to re-estimate on a changed state from where the last
    estimate ended (a warm start: a few iterations and `rounds` rounds are enough).

    c is chosen so that one mode x'' = -omega_max^2 x - c x' has the whole cloth's
    symplectic Euler limit h*: there its step gets the eigenvalue -1, which happens exactly when
    M^-1 (h^2 K + 2 h D) has the eigenvalue 4 (D = -df/dv: spring damping and air). Found by a
    fixed point: start from the worst pairing (c the largest of M^-1 D, a lower bound on h*),
    then a few rounds of h <- the symplectic limit of the top mode of M^-1 (h^2 K + 2 h D) with
    its own stiffness and damping. (The worst pairing alone was up to 10 % low where the
    stiffest and the most damped modes differ, e.g. cotton at x100; the fixed point matches the
    dense eigenvalues of the linearised step within 0.5 %.)"""
    K = ps.stiffness_product(ps.x)             # w -> K w, K = -df/dx (positive semi-definite)
    _, damp = ps.blocks(ps.x)
    m, free = ps.mass[None, :], ps.free.T       # component-major (2, n), as block_product
    cold = start is None
    if cold:
        start = np.repeat(np.random.default_rng(1).standard_normal((1, 2, ps.n)), 3, axis=0)
    w, u, v = (start[k] * free for k in range(3))
    lam = 0.0
    for _ in range(iterations):
        norm = math.sqrt(float(np.vdot(w, m * w)))
        if norm == 0.0:
            return 0.0, 0.0, np.stack((w, u, v))
        w /= norm
        Kw = K(w) * free
        lam = float(np.vdot(w, Kw))             # Rayleigh quotient (w.Kw)/(w.Mw), w.Mw = 1
        w = Kw / m
    w /= math.sqrt(float(np.vdot(w, m * w))) or 1.0
    if cold:                                    # the damping searches start at the top mode
        u, v = w.copy(), w.copy()

    def D(x: np.ndarray) -> np.ndarray:         # D = -df/dv: spring damping and air
        return (block_product(damp, x, ps.rows, ps.cols) + ps.air_drag() * x) * free
    # the worst pairing first: that mode's damping rate, or the fastest-damped mode's if higher
    # (a power iteration on M^-1 D); stiffness and damping need not share their modes
    c = float(np.vdot(w, D(w)))
    for _ in range(iterations):
        u /= math.sqrt(float(np.vdot(u, m * u))) or 1.0
        Du = D(u)
        c = max(c, float(np.vdot(u, Du)))
        u = Du / m
    omega = math.sqrt(max(lam, 0.0))
    if omega == 0.0:
        return 0.0, c, np.stack((w, u, v))
    undamped = 2.0 / omega              # symplectic Euler's limit on the top mode, undamped
    h = undamped
    if c > 0.0:
        h = symplectic_limit(omega, c)
        for _ in range(rounds):         # the fixed point h <- limit of the top mode at h
            for _ in range(iterations):
                v /= math.sqrt(float(np.vdot(v, m * v))) or 1.0
                v = (h * h * K(v) * free + 2.0 * h * D(v)) / m
            v /= math.sqrt(float(np.vdot(v, m * v))) or 1.0
            h = symplectic_limit(math.sqrt(max(float(np.vdot(v, K(v) * free)), 0.0)),
                                 float(np.vdot(v, D(v))))
    h = min(h, undamped)                # damping never raises the limit (rounding aside)
    return omega, (4.0 - (h * omega) ** 2) / (2.0 * h), np.stack((w, u, v))


def symplectic_limit(omega: float, c: float) -> float:
    """Largest h at which symplectic Euler keeps x'' = -omega^2 x - c x' bounded: the step
    matrix has trace 2 - hc - h^2 omega^2 and determinant 1 - hc, stable while
    h^2 omega^2 + 2 c h <= 4, i.e. h <= (sqrt(c^2 + 4 omega^2) - c) / omega^2 (2/omega at c = 0)."""
    if omega <= 0.0:
        return math.inf
    return (math.sqrt(c * c + 4.0 * omega * omega) - c) / (omega * omega)


class _Mode:
    """The force of one normal mode, per unit mass: f = -m (omega^2 x + c v)."""

    def __init__(self, omega: float, c: float):
        self.k, self.c = omega * omega, c

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        f -= ps.mass[:, None] * (self.k * x + self.c * v)

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray):
        return None, None


def amplification(name: str, omega: float, c: float, h: float) -> float:
    """The spectral radius of one step of integrator `name` on x'' = -omega^2 x - c x': the
    step is linear in the state (x, v) (Verlet: (x, v, x_prev)), so stepping each unit state
    once gives its matrix. Radius > 1: the mode grows, the method is unstable at this h."""
    verlet = name == "verlet"
    columns = []
    for unit in np.eye(3 if verlet else 2):
        ps = ParticleSystem([[unit[0]]], [[unit[1]]], 1.0, [_Mode(omega, c)])
        if verlet:
            ps.x_prev, ps.h_prev = np.array([[unit[2]]]), h
        INTEGRATORS[name].step(ps, h)
        columns.append([ps.x[0, 0], ps.v[0, 0]] + ([ps.x_prev[0, 0]] if verlet else []))
    return float(np.abs(np.linalg.eigvals(np.array(columns).T)).max())


def predicted_limit(name: str, omega: float, c: float) -> float | None:
    """The largest step at which integrator `name` keeps the top mode (x'' = -omega^2 x - c x')
    bounded, by bisection on its amplification: undamped, 2/omega for symplectic Euler and
    Verlet, 2.83/omega for RK4, none (None: unstable already at omega h = 1e-3) for forward Euler
    and midpoint; damping lowers the
    first ones (see symplectic_limit) and gives the last two a small stable range. inf for
    implicit Euler and for a cloth with no stiffness."""
    if not INTEGRATORS[name].explicit or omega <= 0.0:
        return math.inf

    def stable(h: float) -> bool:
        return amplification(name, omega, c, h) <= 1.0 + 1e-15      # rounding of eigvals
    lo, hi = 1e-3 / omega, 4.0 / omega        # below omega h = 1e-3 growth drowns in rounding
    if not stable(lo):
        return None
    while stable(hi):
        lo, hi = hi, 2.0 * hi
        if hi > 1e4 / omega:
            return math.inf
    for _ in range(35):                        # bisection on log h: ~2e-10 relative
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


# ----- the limit of a moving cloth: re-estimated, the lowest kept, and the band ---------------
# The limit falls as the cloth deforms. Measured on the scene's default cloth (20 x 24, both top
# corners pinned), every material x every explicit integrator at 0.5-0.99x the limit shown at the
# start (1.5 simulated s, from rest, and from a fling: the bottom-middle particle dragged 500 px
# in 0.2 s and dropped): as it drapes, symplectic Euler's limit on the current state falls to
# 0.62 (rubber, which stretches ~60 %) to 0.82x (silk) of its value at rest, flung to 0.62-0.74x;
# runs blew up or gained energy from 0.6x the limit shown (rubber from rest; denim, leather,
# rubber flung with forward Euler, midpoint or RK4) to 0.9x (silk from rest), and never at 0.5x
# except forward Euler on flung cotton (blew up at 0.5x; not at 0.4x). So a step below
# marginal(name) x the limit is "stable", up to the limit "marginal", beyond it "past the limit".
MARGINAL = 0.5
MARGINAL_OF = {"euler": 0.4}      # forward Euler is stable only through damping: a wider margin


def marginal(name: str) -> float:
    """The fraction of its limit below which integrator `name` stayed stable (measured)."""
    return MARGINAL_OF.get(name, MARGINAL)


# Simulated seconds between two estimates on the moving cloth. Measured (the default cloth, warm
# estimates against 300-iteration ones): re-estimated every 1/60 s the shown limit was at most
# 0.2-4 % too high (cotton falling, cotton flung, rubber falling), every 0.05 s 4-9 %, every 0.1 s
# 11-34 %, every 0.5 s 27-60 %; an estimate costs about as much as an implicit step of the default
# cloth (~7 ms here, loaded), so every 0.05 s adds roughly a third to an implicit run at 60 Hz.
# With an explicit integrator the limit decides everything: every 0.05 s (inside the margin of
# marginal()); with implicit Euler it is only a comparison: every 0.5 s.
ESTIMATE_EVERY = 0.05
ESTIMATE_EVERY_IMPLICIT = 0.5
WARM_ITERATIONS = 20        # power iterations of a warm-started estimate (cold: 60, 3 rounds)


class LimitWatch:
    """The explicit step limit of a mass-spring cloth as it moves.

    `restart(ps)` estimates omega_max and the damping rate on the current state from scratch
    (at a build, a settings change or a rollback); `follow(ps, t)` re-estimates at most every
    ESTIMATE_EVERY simulated seconds, warm-started from the last estimate's vectors. `limit(name)`
    is integrator `name`'s limit on the latest estimate, `rest(name)` on the first one since
    `forget()`, `lowest(name)` the lowest of those `track(name, h)` kept since then: the band of
    a step is judged against the lowest, because what the cloth did once (drape, be flung) it
    can do again."""

    def __init__(self) -> None:
        self.omega, self.damping = 0.0, 0.0
        self.shapes: np.ndarray | None = None
        self.estimated_at = -math.inf
        self.estimates = 0
        self._limits: dict[str, float | None] = {}
        self._rest: dict[str, float | None] = {}
        self._lowest: dict[str, float] = {}
        self._first: tuple[float, float] | None = None

    def forget(self) -> None:
        """The cloth itself changed (material, stiffness, effects, size): forget the rest state
        and the lowest limit seen; the next estimate is the new 'at rest'."""
        self._first = None
        self._rest.clear()
        self._lowest.clear()

    def restart(self, ps: MassSpringSystem, t: float, iterations: int = 60) -> None:
        """A full estimate on the current state (cold start)."""
        self.shapes = None
        self._estimate(ps, t, iterations, REFINE_ROUNDS)

    def follow(self, ps: MassSpringSystem, t: float, every: float = ESTIMATE_EVERY) -> bool:
        """Re-estimate if `every` simulated seconds have passed; True if it did."""
        if t - self.estimated_at < every - 1e-12:
            return False
        self._estimate(ps, t, WARM_ITERATIONS, 1)
        return True

    def _estimate(self, ps: MassSpringSystem, t: float, iterations: int, rounds: int) -> None:
        self.omega, self.damping, self.shapes = top_mode(ps, iterations, self.shapes, rounds)
        self.estimated_at, self.estimates = t, self.estimates + 1
        self._limits = {}
        if self._first is None:
            self._first = (self.omega, self.damping)

    @staticmethod
    def _limit(name: str, omega: float, damping: float) -> float | None:
        if name == "symplectic_euler":              # its closed form (predicted_limit agrees)
            return symplectic_limit(omega, damping)
        return predicted_limit(name, omega, damping)

    def limit(self, name: str) -> float | None:
        """Integrator `name`'s limit on the latest estimate (None: unstable at every h)."""
        if name not in self._limits:
            self._limits[name] = self._limit(name, self.omega, self.damping)
        return self._limits[name]

    def rest(self, name: str) -> float | None:
        """Its limit on the first estimate since forget() (the cloth at rest, usually)."""
        if name not in self._rest:
            self._rest[name] = (self._limit(name, *self._first) if self._first is not None
                                else self.limit(name))
        return self._rest[name]

    def lowest(self, name: str) -> float | None:
        """The lowest limit of `name` kept by track() since forget() (at first: at rest)."""
        if name not in self._lowest:
            start = self.rest(name)
            if start is None:
                return None
            self._lowest[name] = start
        return self._lowest[name]

    def track(self, name: str, h: float) -> None:
        """After an estimate: lower `name`'s lowest limit to the one on the current state,
        unless the step h was already past the lowest (then the state may be the growing
        instability's own doing, a stretched wreck whose limit says nothing about the cloth)."""
        low, now = self.lowest(name), self.limit(name)
        if low is not None and now is not None and h <= low:
            self._lowest[name] = min(low, now)

    def band(self, name: str, h: float) -> str:
        """'stable' (h < marginal(name) x the lowest limit), 'marginal' (up to it), 'past the
        limit', 'unstable' (no stable step at all), or 'no limit' (implicit, or no stiffness)."""
        if not INTEGRATORS[name].explicit or self.omega <= 0.0:
            return "no limit"
        low = self.lowest(name)
        if low is None:
            return "unstable"
        if h > low:
            return "past the limit"
        return "stable" if h < marginal(name) * low else "marginal"
