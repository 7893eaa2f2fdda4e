"""Force objects of the particle system, in the lecture's three kinds:

* unary forces act on each particle on its own:   Gravity  f = m g,   Drag  f = -k_d v,
  and PendulumGravity (gravity's tangential part for a pendulum in its arc-length coordinate);
* n-ary forces act on a fixed set of particles:   Springs (damped Hooke springs between pairs a, b)
      f_a = -[ k_s (|l| - r) + k_d (v_a - v_b) . l/|l| ] l/|l|,   f_b = -f_a,   l = x_a - x_b;
* spatial forces act between any pairs:            Attraction (inverse-square; negative = repulsion).

Every force *adds* into the particle system's force accumulator (`accumulate`), so the system
never needs to know which forces exist. For implicit Euler each force also gives its Jacobians as
products, w -> (df/dx) w and w -> (df/dv) w (`jacobian`): the linear system of a backward-Euler
step (Baraff & Witkin, "Large Steps in Cloth Simulation") is then solved by conjugate gradients
without ever forming a matrix.
"""

from __future__ import annotations

import numpy as np

from app.physics.particles import AddProduct, ParticleSystem, scatter_add

Jacobians = tuple["AddProduct | None", "AddProduct | None"]


def _row_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise dot products, shape (m, 1): sum(a * b, axis=1) kept as a column."""
    return np.sum(a * b, axis=1, keepdims=True)


class Gravity:
    """Unary: f = m g for every particle (g a vector, y down in the lab: (0, +g))."""

    def __init__(self, g: tuple[float, ...]):
        self.g = np.asarray(g, dtype=float)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        f += ps.mass[:, None] * self.g

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray) -> Jacobians:
        return None, None                          # constant force: both derivatives are zero


class Drag:
    """Unary viscous drag: f = -k_d v."""

    def __init__(self, kd: float):
        self.kd = float(kd)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        f -= self.kd * v

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray) -> Jacobians:
        def dfdv(w: np.ndarray, out: np.ndarray) -> None:
            out -= self.kd * w                     # df/dv = -k_d I
        return None, dfdv


class PendulumGravity:
    """Unary, for a pendulum written as a 1-D particle at arc length s = L theta along its circle:
    the tangential part of gravity, f = -m g sin(s / L). (A rod-free pendulum: no constraint,
    so every integrator sees the same smooth ODE theta'' = -(g/L) sin theta.)"""

    def __init__(self, g: float, length: float):
        self.g, self.length = float(g), float(length)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        f -= ps.mass[:, None] * self.g * np.sin(x / self.length)

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray) -> Jacobians:
        k = -ps.mass[:, None] * self.g * np.cos(x / self.length) / self.length

        def dfdx(w: np.ndarray, out: np.ndarray) -> None:
            out += k * w                           # df/ds = -m g cos(s/L) / L
        return dfdx, None


class FloorPush:
    """Unary, a contact: a floor at y = level (y down) that pushes every particle below its surface
    up with a constant force `push` (N, i.e. px kg / s^2), and nothing above it:
    f_y = -push if y > level else 0. The force *jumps* from 0 to push at the surface, as a contact
    switches on: that jump is what the integrator lab's `bounce` problem shows to cost every
    integrator its order. Conservative (potential push * max(0, y - level)), so a ball bounces
    back to the height it fell from. Its Jacobian is zero everywhere but at the surface (a delta
    there, which no Jacobian-vector product can carry): implicit Euler does not see the floor
    coming either."""

    def __init__(self, level: float, push: float):
        self.level, self.push = float(level), float(push)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        f[:, 1] -= self.push * (x[:, 1] > self.level)    # push up (-y) on every particle in it

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray) -> Jacobians:
        return None, None                          # piecewise constant: zero off the surface


class Springs:
    """n-ary: damped Hooke springs between particle pairs (a[k], b[k]).

    ks, kd: stiffness and damping (scalars or one per spring); rest: rest lengths (default: the
    lengths at construction time, so a mesh built in its rest shape starts in equilibrium).
    """

    def __init__(self, a, b, ks, kd=0.0, rest=None, x0: np.ndarray | None = None):
        self.a = np.asarray(a, dtype=np.intp)
        self.b = np.asarray(b, dtype=np.intp)
        m = len(self.a)
        self.ks = np.broadcast_to(np.asarray(ks, dtype=float), (m,))[:, None]
        self.kd = np.broadcast_to(np.asarray(kd, dtype=float), (m,))[:, None]
        if rest is None:
            if x0 is None:
                raise ValueError("Springs need rest lengths or the positions x0 to take them from")
            rest = np.linalg.norm(x0[self.a] - x0[self.b], axis=1)
        self.rest = np.broadcast_to(np.asarray(rest, dtype=float), (m,))[:, None]
        self.has_damping = bool((self.kd != 0).any())

    def _geometry(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Spring lengths |l| (m, 1) and unit directions l/|l| (m, dim), l = x_a - x_b."""
        l = x[self.a] - x[self.b]
        length = np.linalg.norm(l, axis=1, keepdims=True)
        return length, l / np.maximum(length, 1e-12)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        length, u = self._geometry(x)
        magnitude = self.ks * (length - self.rest)
        if self.has_damping:
            magnitude = magnitude + self.kd * _row_dot(v[self.a] - v[self.b], u)
        fa = -magnitude * u
        scatter_add(f, self.a, fa)                 # f_a += fa for every spring
        scatter_add(f, self.b, -fa)                # f_b -= fa

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray) -> Jacobians:
        """df_a/dx_a = -k_s [ u u^T + (1 - r/|l|) (I - u u^T) ] (the damping term's x-derivative
        is dropped, as Baraff & Witkin do). A compressed spring (|l| < r) would make the transverse
        part push outwards and the matrix indefinite; like Choi & Ko we clamp (1 - r/|l|) at 0 so
        conjugate gradients always sees a positive definite system."""
        length, u = self._geometry(x)
        transverse = np.maximum(1.0 - self.rest / np.maximum(length, 1e-12), 0.0)

        def dfdx(w: np.ndarray, out: np.ndarray) -> None:
            dw = w[self.a] - w[self.b]
            along = _row_dot(u, dw) * u
            ka = -self.ks * (along + transverse * (dw - along))
            scatter_add(out, self.a, ka)
            scatter_add(out, self.b, -ka)

        def dfdv(w: np.ndarray, out: np.ndarray) -> None:
            da = -self.kd * _row_dot(u, w[self.a] - w[self.b]) * u     # df_a/dv_a = -k_d u u^T
            scatter_add(out, self.a, da)
            scatter_add(out, self.b, -da)

        return dfdx, (dfdv if self.has_damping else None)


class Attraction:
    """Spatial: every pair (i, j) attracts with f_i = G m_i m_j d / (|d|^2 + eps^2)^(3/2),
    d = x_j - x_i (inverse-square gravity; eps softens close encounters; G < 0 repels)."""

    def __init__(self, G: float, n: int, softening: float = 0.0):
        self.G = float(G)
        self.eps2 = float(softening) ** 2
        self.i, self.j = np.triu_indices(n, 1)     # all pairs i < j, instead of a double loop

    def _pairs(self, ps: ParticleSystem, x: np.ndarray):
        d = x[self.j] - x[self.i]
        s = np.sum(d * d, axis=1, keepdims=True) + self.eps2
        gmm = self.G * (ps.mass[self.i] * ps.mass[self.j])[:, None]
        return d, s, gmm

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        d, s, gmm = self._pairs(ps, x)
        fi = gmm * d / s ** 1.5
        scatter_add(f, self.i, fi)
        scatter_add(f, self.j, -fi)

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray) -> Jacobians:
        """df_i/dx_j = G m_i m_j [ I / s^(3/2) - 3 d d^T / s^(5/2) ] = -df_i/dx_i. Not definite:
        pulling harder when closer is a negative stiffness along d."""
        d, s, gmm = self._pairs(ps, x)
        c1, c3 = gmm / s ** 1.5, 3.0 * gmm / s ** 2.5

        def dfdx(w: np.ndarray, out: np.ndarray) -> None:
            dw = w[self.j] - w[self.i]
            fi = c1 * dw - c3 * _row_dot(d, dw) * d
            scatter_add(out, self.i, fi)
            scatter_add(out, self.j, -fi)

        return dfdx, None


__all__ = ["Gravity", "Drag", "PendulumGravity", "Springs", "Attraction"]
