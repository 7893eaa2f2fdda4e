"""A particle system behind a solver interface (the lecture's "Particle Systems" and "Solver Interface").

The state of n particles is a point in phase space: their positions x and velocities v, which the
solver sees as one flat state vector y = [x, v] (2 * n * dim numbers). The solver asks the system
for the derivative of that point, and the system answers with the lecture's three-step
*derivative evaluation*:

    1. clear forces        f = 0                          (zero the force accumulator)
    2. accumulate forces   f += force(x, v) for each force object (gravity, drag, springs, ...)
    3. gather              return [v, f / m]              (dx/dt = v, dv/dt = f/m)

Force objects live in app/physics/forces.py; integrators (which only ever call `derivative`,
`accel` and, for implicit Euler, the force Jacobian products) live in app/physics/integrators.py.

Arrays: x, v and f have shape (n, dim) (dim = 2 for the scenes, 1 for a pendulum written in its
arc-length coordinate). A pinned particle has inverse mass 0: it gathers zero acceleration, so it
stays where it is, and implicit Euler leaves its row out of the linear solve.
"""

from __future__ import annotations

from typing import Callable, Optional, Protocol, Sequence

import numpy as np

from app.physics.linear_solve import SolveReport

# A Jacobian's action: w (n, dim) -> J w (n, dim). An AddProduct adds J w into `out` instead.
JacobianProduct = Callable[[np.ndarray], np.ndarray]
AddProduct = Callable[[np.ndarray, np.ndarray], None]


class Force(Protocol):
    """What a force object provides (see app/physics/forces.py)."""

    def accumulate(self, ps: "ParticleSystem", x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        """Add this force into the accumulator f (shape (n, dim))."""

    def jacobian(self, ps: "ParticleSystem", x: np.ndarray, v: np.ndarray
                 ) -> tuple[Optional[AddProduct], Optional[AddProduct]]:
        """At (x, v): two functions (w, out) -> out += (df/dx) w and out += (df/dv) w, or None
        where that derivative is zero. The Jacobian's action on w, never the matrix itself."""


class ParticleSystem:
    """n particles: positions x, velocities v, masses m (inf or pinned -> inverse mass 0), forces.

    Counters (for the work-precision report): `evals` counts derivative evaluations (force
    accumulations), `jac_products` counts Jacobian-vector products (implicit Euler's CG).
    """

    def __init__(self, x: np.ndarray, v: np.ndarray, mass: np.ndarray | float,
                 forces: Sequence[Force] = (), pinned: Sequence[int] = ()):
        self.x = np.array(x, dtype=float)
        if self.x.ndim == 1:
            self.x = self.x[:, None]
        self.v = np.array(v, dtype=float).reshape(self.x.shape)
        n = self.x.shape[0]
        self.mass = np.broadcast_to(np.asarray(mass, dtype=float), (n,)).copy()
        if not (self.mass > 0).all():
            raise ValueError("every particle mass must be positive")
        self.inv_mass = 1.0 / self.mass
        self.inv_mass[list(pinned)] = 0.0          # pinned: gathers no acceleration
        self.free = (self.inv_mass > 0).astype(float)[:, None]   # 1 free, 0 pinned, per row
        self.forces: list[Force] = list(forces)
        self.f = np.zeros_like(self.x)             # the force accumulator
        self.evals = 0
        self.jac_products = 0
        self.x_prev: np.ndarray | None = None      # Verlet's previous positions (None: not started)
        self.h_prev = 0.0                          # the step x_prev belongs to
        self.cg_tolerance = 1e-12                  # implicit Euler: CG stops at |r| <= tol |b|
        self.cg_max_iterations: int | None = None  # None: the number of unknowns
        self.solve = SolveReport()                 # how the last implicit step's solve ended
        self.cg_failures = 0                       # implicit steps whose CG stopped short
        self.last_cg_failure: SolveReport | None = None   # the latest of those

    @property
    def cg_iterations(self) -> int:
        """CG iterations of the last implicit step."""
        return self.solve.iterations

    @property
    def cg_residual(self) -> float:
        """|b - A x| / |b| of CG's answer in the last implicit step."""
        return self.solve.residual

    def record_solve(self, report: SolveReport) -> None:
        """Keep the report of an implicit step's solve; count it if CG stopped short."""
        self.solve = report
        if not report.converged:
            self.cg_failures += 1
            self.last_cg_failure = report

    # ----- sizes ------------------------------------------------------------------------------
    @property
    def n(self) -> int:
        return self.x.shape[0]

    # ----- the solver interface ---------------------------------------------------------------
    def state(self) -> np.ndarray:
        """The phase-space point y = [x, v] as one flat vector (a copy)."""
        return np.concatenate((self.x.ravel(), self.v.ravel()))

    def set_state(self, y: np.ndarray) -> None:
        """Write a phase-space point back into x and v (new arrays, never views of y)."""
        half = self.x.size
        self.set_xv(np.array(y[:half]).reshape(self.x.shape), np.array(y[half:]).reshape(self.v.shape))

    def set_xv(self, x: np.ndarray, v: np.ndarray) -> None:
        """New positions and velocities from a one-step method: Verlet's x_prev no longer applies."""
        self.x, self.v = x, v
        self.x_prev = None

    def force(self, x: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Steps 1 and 2 of the derivative evaluation: clear, then accumulate every force."""
        self.evals += 1
        f = self.f
        f.fill(0.0)                                # 1. clear forces
        for force in self.forces:                  # 2. accumulate forces
            force.accumulate(self, x, v, f)
        return f

    def accel(self, x: np.ndarray, v: np.ndarray) -> np.ndarray:
        """f/m at (x, v): one derivative evaluation (pinned particles get 0)."""
        return self.force(x, v) * self.inv_mass[:, None]

    def derivative(self, y: np.ndarray) -> np.ndarray:
        """dy/dt = [v, f/m] at the phase-space point y: step 3, the gather."""
        half = self.x.size
        x = y[:half].reshape(self.x.shape)
        v = y[half:].reshape(self.v.shape)
        return np.concatenate((v.ravel(), self.accel(x, v).ravel()))

    # ----- force Jacobians, as products (for implicit Euler) --------------------------------------
    def force_jacobians(self, x: np.ndarray, v: np.ndarray) -> tuple[JacobianProduct, JacobianProduct]:
        """The two products w -> (df/dx) w and w -> (df/dv) w at (x, v), summed over the forces.

        Each force prepares its part once (spring directions, lengths) and the products never
        form a matrix: a conjugate-gradient solve only ever needs the matrix's action on a vector.
        """
        parts = [force.jacobian(self, x, v) for force in self.forces]
        wrt_x = [k for k, _ in parts if k is not None]
        wrt_v = [d for _, d in parts if d is not None]

        def dfdx_dot(w: np.ndarray) -> np.ndarray:
            self.jac_products += 1
            out = np.zeros_like(w)
            for add in wrt_x:
                add(w, out)
            return out

        def dfdv_dot(w: np.ndarray) -> np.ndarray:
            out = np.zeros_like(w)
            for add in wrt_v:
                add(w, out)
            return out

        return dfdx_dot, dfdv_dot

    # ----- bookkeeping --------------------------------------------------------------------------
    def is_finite(self) -> bool:
        return bool(np.isfinite(self.x).all() and np.isfinite(self.v).all())

    def copy_state(self) -> dict:
        """A cheap copy of everything that evolves (for snapshot/restore)."""
        return {"x": self.x.copy(), "v": self.v.copy(), "h_prev": self.h_prev,
                "x_prev": None if self.x_prev is None else self.x_prev.copy(),
                "evals": self.evals, "jac_products": self.jac_products}

    def restore_state(self, snap: dict) -> None:
        self.x, self.v = snap["x"].copy(), snap["v"].copy()
        self.x_prev = None if snap["x_prev"] is None else snap["x_prev"].copy()
        self.h_prev = snap["h_prev"]
        self.evals, self.jac_products = snap["evals"], snap["jac_products"]


def scatter_add(out: np.ndarray, index: np.ndarray, values: np.ndarray) -> None:
    """out[index[k]] += values[k] for every k, repeated indices summed: replaces the Python loop
    `for k in range(len(index)): out[index[k]] += values[k]`."""
    if len(index) < 64:
        np.add.at(out, index, values)              # few rows: one call, least overhead
        return
    n = out.shape[0]
    for d in range(out.shape[1]):                  # many rows: bincount is ~10x faster than add.at
        out[:, d] += np.bincount(index, weights=values[:, d], minlength=n)


__all__ = ["ParticleSystem", "Force", "scatter_add"]
