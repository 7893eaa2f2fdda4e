"""Time integrators for the particle system: the lecture's explicit vs implicit comparison.

Every integrator has the same signature, `step(ps, h)`: advance the ParticleSystem `ps` by h
seconds. Each is written like its formula (y = [x, v] the phase-space point, f(y) = [v, f/m] the
derivative evaluation of app/physics/particles.py, a(x, v) = f/m):

    euler              y' = y + h f(y)                                         1 evaluation
    symplectic_euler   v' = v + h a(x, v);   x' = x + h v'                     1
    verlet             x' = 2x - x_prev + h^2 a(x)      (velocity-less)         1
    midpoint (RK2)     y' = y + h f(y + h/2 f(y))                              2
    rk4                y' = y + h/6 (k1 + 2 k2 + 2 k3 + k4)                    4
    implicit_euler     (M - h df/dv - h^2 df/dx) dv = h (f0 + h df/dx v0)       1 + one Jacobian
                       v' = v + dv;   x' = x + h v'                            product per CG iteration

Implicit (backward) Euler takes y' = y + h f(y') and, as Baraff & Witkin do, linearises f around
the current state once per step (one Newton step), then solves the linear system with conjugate
gradients using only Jacobian-vector products: no dense matrix, so it scales to a cloth.

What the comparison shows (undamped oscillator, omega*h = omega times the step):
  forward Euler gains energy at every h (|1 + i omega h| > 1): it spirals out;
  implicit Euler loses energy at every h: it spirals in, but never blows up;
  symplectic Euler and Verlet keep energy bounded until omega*h = 2, then blow up; bounded is not
    constant: within each swing the energy they report rises and falls by up to a factor
    (1 + omega h/2) / (1 - omega h/2) (1.1 at omega h = 0.1, 19 at 1.8);
  explicit midpoint gains energy at every h, though only by a factor 1 + (omega h)^4 / 4 per step;
  RK4 stays bounded until omega*h = 2.83 (2 sqrt 2) but damps: each step multiplies the energy by
    1 - (omega h)^6/72 + (omega h)^8/576: negligible below ~0.5, 0.9934 at 0.9 (a quarter of the
    energy left after 200 steps), 0.338 at 2.25 (the bob simply stops).
These limits are the linear oscillator's (omega fixed). On a nonlinear problem the local omega
changes along the motion, and there is no one threshold: on the two-body orbit (20 s, measured
2026-11-26) RK4 blew up at hertz 4 (at t = 6.5 s) but not at hertz 3, 5 or 6, where it only
drifts (its energy ratio -0.44, -10.9, -4.4: wrong, bounded).

Orders are global: the error after a fixed time T. Verlet's position error per step is O(h^4)
(the lecture slides call Verlet "4th order accurate", counting that), but the n = T/h steps add
up to an O(h^2) error at T: the lab measures order 2.00 (`python -m app bench integrators`).

`INTEGRATORS` maps each name to an `Integrator` (callable like its step function, and carrying
its theoretical order and stability limit); calling it checks h.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from app.physics.linear_solve import dense_solve, preconditioned_cg, solve
from app.physics.particles import ParticleSystem

StepFunction = Callable[[ParticleSystem, float], None]


# ----- explicit one-step methods on the phase-space point y = [x, v] ------------------------------
def euler(ps: ParticleSystem, h: float) -> None:
    """Forward Euler: y' = y + h f(y)."""
    y = ps.state()
    ps.set_state(y + h * ps.derivative(y))


def symplectic_euler(ps: ParticleSystem, h: float) -> None:
    """Semi-implicit (symplectic) Euler: new velocity first, then move with the new velocity."""
    v = ps.v + h * ps.accel(ps.x, ps.v)
    ps.set_xv(ps.x + h * v, v)


def midpoint(ps: ParticleSystem, h: float) -> None:
    """Explicit midpoint (RK2) on the particle system (midpoint_step)."""
    ps.set_state(midpoint_step(lambda t, y: ps.derivative(y), 0.0, ps.state(), h))


def rk4(ps: ParticleSystem, h: float) -> None:
    """Classical fourth-order Runge-Kutta on the particle system (rk4_step)."""
    ps.set_state(rk4_step(lambda t, y: ps.derivative(y), 0.0, ps.state(), h))


# ----- the same two methods for any ODE dy/dt = f(t, y) (the exercise `rk4`'s reference) ----------
def midpoint_step(f: Callable[[float, np.ndarray], np.ndarray], t: float, y: np.ndarray,
                  h: float) -> np.ndarray:
    """Explicit midpoint (RK2): a half Euler step to the midpoint, then the full step with the
    midpoint's derivative. Returns the new y."""
    y_mid = y + h / 2 * f(t, y)
    return y + h * f(t + h / 2, y_mid)


def rk4_step(f: Callable[[float, np.ndarray], np.ndarray], t: float, y: np.ndarray,
             h: float) -> np.ndarray:
    """Classical fourth-order Runge-Kutta: y' = y + h/6 (k1 + 2 k2 + 2 k3 + k4). Returns the new y."""
    k1 = f(t, y)
    k2 = f(t + h / 2, y + h / 2 * k1)
    k3 = f(t + h / 2, y + h / 2 * k2)
    k4 = f(t + h, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def rk4_tuple(f: Callable[[tuple[float, ...]], tuple[float, ...]], y: tuple[float, ...],
              h: float) -> tuple[float, ...]:
    """rk4_step's formula on a state of a few plain floats (the pendulum references):
    y' = y + h/6 (k1 + 2 k2 + 2 k3 + k4), k1 = f(y), k2 = f(y + h/2 k1), k3 = f(y + h/2 k2),
    k4 = f(y + h k3). Tuples and the math module, not arrays: for four numbers NumPy's per-call
    overhead makes a step ~10x slower (measured: ~5 us here, ~65 us with 4-element arrays)."""
    k1 = f(y)
    k2 = f(tuple(a + 0.5 * h * b for a, b in zip(y, k1)))
    k3 = f(tuple(a + 0.5 * h * b for a, b in zip(y, k2)))
    k4 = f(tuple(a + h * b for a, b in zip(y, k3)))
    return tuple(a + h / 6.0 * (b1 + 2 * b2 + 2 * b3 + b4) for a, b1, b2, b3, b4 in zip(y, k1, k2, k3, k4))


# ----- Verlet: positions only, the previous positions are the memory -----------------------------
def verlet(ps: ParticleSystem, h: float) -> None:
    """Velocity-less (position) Verlet: x' = 2x - x_prev + a h^2, then x_prev = x.

    The first step (or a step after h changed, or after another method moved the particles)
    makes x_prev from a Taylor step back, x_prev = x - h v + h^2/2 a: starting from x - h v alone
    would cost a whole order. The velocity is not part of the method; we keep the estimate
    v' = (x' - x)/h + a h/2 (second order) for velocity-dependent forces, energy and plots.
    """
    a = ps.accel(ps.x, ps.v)
    if ps.x_prev is None or ps.h_prev != h:
        ps.x_prev = ps.x - h * ps.v + h * h / 2 * a
    x_new = 2 * ps.x - ps.x_prev + a * h * h
    ps.v = (x_new - ps.x) / h + a * (h / 2)
    ps.x_prev, ps.x, ps.h_prev = ps.x, x_new, h


# ----- implicit (backward) Euler, linearised once per step (Baraff & Witkin) ----------------------
def implicit_euler(ps: ParticleSystem, h: float) -> None:
    """Backward Euler with one Newton step: solve (M - h D - h^2 K) dv = h (f0 + h K v0),
    K = df/dx and D = df/dv at the current state, by conjugate gradients; then
    v' = v0 + dv and x' = x0 + h v'. Where CG stops short (an attracting force makes the matrix
    indefinite at a large step), the same system is solved densely for a few unknowns
    (linear_solve.dense_solve) and ps.solve says so (app/physics/linear_solve.py)."""
    x0, v0 = ps.x, ps.v
    f0 = ps.force(x0, v0).copy()
    K, D = ps.force_jacobians(x0, v0)
    M = ps.mass[:, None]

    def A(w: np.ndarray) -> np.ndarray:           # the system matrix's action on w
        return M * w - h * D(w) - h * h * K(w)

    b = h * (f0 + h * K(v0))
    dv, report = solve(A, b, ps.free, None, ps.cg_tolerance, ps.cg_max_iterations,
                       ("dense LU", lambda: dense_solve(A, b, ps.free)))
    ps.record_solve(report)
    v = v0 + dv
    ps.set_xv(x0 + h * v, v)


# ----- the registry -------------------------------------------------------------------------------
@dataclass(frozen=True)
class Integrator:
    """An integrator and the facts the lab checks it against.

    order: global order of accuracy. stability_limit: largest omega*h for which the undamped
    oscillator x'' = -omega^2 x stays bounded (0: unstable at every h; inf: at every h).
    evaluations: derivative evaluations per step (implicit Euler: plus its CG products).
    """

    name: str
    title: str
    step: StepFunction
    order: int
    stability_limit: float
    evaluations: int
    explicit: bool
    note: str

    def __call__(self, ps: ParticleSystem, h: float) -> None:
        self.step(ps, check_step(h))


def check_step(h: float) -> float:
    """Return h as a float if it is a usable time step; raise ValueError otherwise."""
    try:
        h = float(h)
    except (TypeError, ValueError):
        raise ValueError(f"time step must be a number, got {h!r}") from None
    if not math.isfinite(h) or h <= 0.0:
        raise ValueError(f"time step must be finite and > 0, got {h!r}")
    return h


INTEGRATORS: dict[str, Integrator] = {i.name: i for i in (
    Integrator("euler", "forward Euler", euler, 1, 0.0, 1, True,
               "gains energy at every step size (spirals out)"),
    Integrator("symplectic_euler", "symplectic Euler", symplectic_euler, 1, 2.0, 1, True,
               "energy bounded (swinging) for omega*dt < 2"),
    Integrator("verlet", "Verlet", verlet, 2, 2.0, 1, True,
               "velocity-less; energy bounded (swinging) for omega*dt < 2"),
    Integrator("midpoint", "midpoint (RK2)", midpoint, 2, 0.0, 2, True,
               "gains energy at every step size, slowly: x(1 + (omega dt)^4/4) per step"),
    Integrator("rk4", "RK4", rk4, 4, 2.0 * math.sqrt(2.0), 4, True,
               "bounded for omega*dt < 2.83, energy x(1 - (omega dt)^6/72 + ...) per step"),
    Integrator("implicit_euler", "implicit Euler", implicit_euler, 1, math.inf, 1, False,
               "stable at every step size; loses energy (spirals in)"),
)}


def get_integrator(name: str) -> Integrator:
    """The integrator called `name`; ValueError listing the accepted names otherwise."""
    try:
        return INTEGRATORS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown integrator {name!r}; accepted: "
                         + ", ".join(INTEGRATORS)) from None


def integrate(ps: ParticleSystem, name: str, h: float, steps: int) -> ParticleSystem:
    """Advance ps by `steps` steps of h with the integrator `name`; return ps."""
    step = get_integrator(name).step
    h = check_step(h)
    if steps < 0:
        raise ValueError(f"steps must be >= 0, got {steps}")
    for _ in range(int(steps)):
        step(ps, h)
    return ps


__all__ = ["euler", "symplectic_euler", "verlet", "midpoint", "rk4", "rk4_tuple", "implicit_euler",
           "midpoint_step", "rk4_step",
           "preconditioned_cg", "Integrator", "INTEGRATORS", "get_integrator", "integrate",
           "check_step"]
