"""How large a step the mass-spring cloth takes with an explicit integrator: its highest
frequency omega_max by power iteration, the damping rate of that mode, and each integrator's
predicted limit on it (2/omega_max undamped for the Euler family and Verlet, 2.83/omega_max for
RK4; less with damping)."""

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


def top_mode(ps: MassSpringSystem, iterations: int = 40, start: np.ndarray | None = None
             ) -> tuple[float, float, np.ndarray]:
    """(omega_max, c, w): the highest angular frequency of the free particles, by power iteration
    on M^-1 K (K = -df/dx, definite blocks); a damping rate c; and the mode shape w (a warm
    start). c is chosen so that one mode x'' = -omega_max^2 x - c x' has the whole cloth's
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
    w = (np.random.default_rng(1).standard_normal((2, ps.n)) if start is None
         else start.copy()) * free
    lam = 0.0
    for _ in range(iterations):
        norm = math.sqrt(float(np.vdot(w, m * w)))
        if norm == 0.0:
            return 0.0, 0.0, w
        w /= norm
        Kw = K(w) * free
        lam = float(np.vdot(w, Kw))             # Rayleigh quotient (w.Kw)/(w.Mw), w.Mw = 1
        w = Kw / m
    w /= math.sqrt(float(np.vdot(w, m * w))) or 1.0

    def D(u: np.ndarray) -> np.ndarray:         # D = -df/dv: spring damping and air
        return (block_product(damp, u, ps.rows, ps.cols) + ps.air_drag() * u) * free
    # the worst pairing first: that mode's damping rate, or the fastest-damped mode's if higher
    # (a power iteration on M^-1 D); stiffness and damping need not share their modes
    c = float(np.vdot(w, D(w)))
    u = w.copy()
    for _ in range(iterations):
        u /= math.sqrt(float(np.vdot(u, m * u))) or 1.0
        Du = D(u)
        c = max(c, float(np.vdot(u, Du)))
        u = Du / m
    omega = math.sqrt(max(lam, 0.0))
    if omega == 0.0 or c == 0.0:
        return omega, c, w
    h = symplectic_limit(omega, c)
    u = w.copy()
    for _ in range(REFINE_ROUNDS):      # the fixed point h <- limit of the top mode at h
        for _ in range(iterations):
            u /= math.sqrt(float(np.vdot(u, m * u))) or 1.0
            u = (h * h * K(u) * free + 2.0 * h * D(u)) / m
        u /= math.sqrt(float(np.vdot(u, m * u))) or 1.0
        h = symplectic_limit(math.sqrt(max(float(np.vdot(u, K(u) * free)), 0.0)),
                             float(np.vdot(u, D(u))))
    h = min(h, 2.0 / omega)             # damping never raises the limit (rounding aside)
    return omega, (4.0 - (h * omega) ** 2) / (2.0 * h), w     # symplectic_limit(omega, c) = h


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
    for _ in range(50):                        # bisection on log h: ~1e-14 relative
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo
