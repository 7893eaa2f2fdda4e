"""The mass-spring cloth's forces as NumPy on a grid: Hooke springs and their damping by family,
wind as a pressure, and a stopwatch around each force (app/physics/mass_spring.py uses them).

Positions live in an (n, 2) array, row-major, so x.reshape(rows, cols, 2) is the
grid without a copy. A *family* of springs joins every (r, c) to (r + dr, c + dc): its first ends
are one strided slice X[a] of the grid and its second ends another, X[b], so a whole family is
handled by a few array operations and its forces are added with F[a] += f_a, F[b] -= f_a:
inside one family no particle appears twice in a slice, so no scatter-add is needed.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from app.physics.grid_shared import wind_field
from app.physics.particles import AddProduct, ParticleSystem
from app.physics.rods import EPS, Family
from app.physics.timing import Stopwatch


# ----- spring families on the grid ---------------------------------------------------------------
def spring_geometry(X: np.ndarray, fam: Family) -> tuple[np.ndarray, np.ndarray]:
    """|l| (m_r, m_c, 1) and l/|l| (m_r, m_c, 2) of every spring of a family, l = x_a - x_b."""
    l = X[fam.a] - X[fam.b]
    lx, ly = l[..., 0], l[..., 1]
    length = np.sqrt(lx * lx + ly * ly)[..., None]       # 2x np.sum(l * l, axis=-1)'s speed
    return length, l / np.maximum(length, EPS)


def _outer(u: np.ndarray) -> np.ndarray:
    """u u^T for every spring, component-major: (2, 2, m_r, m_c)."""
    u2 = np.ascontiguousarray(np.moveaxis(u, -1, 0))     # contiguous first: 8x faster (64x64)
    return u2[:, None] * u2[None, :]


# (family, B): df_a/dx_a = -B for every spring of the family, B of shape (2, 2, m_r, m_c)
Blocks = list[tuple[Family, np.ndarray]]


def block_product(blocks: Blocks, w: np.ndarray, rows: int, cols: int) -> np.ndarray:
    """sum over families of the blocks' action on w, component-major (2, n): out_a += B (w_a -
    w_b), out_b -= the same. With B the springs' Jacobian blocks this is -(df/dx) w. The loop it
    replaces: for every spring, a 2x2 matrix-vector product added into both ends. (Component-
    major, w[0] all x's and w[1] all y's, because contiguous slices make it ~2x faster.)"""
    W = w.reshape(2, rows, cols)
    out = np.zeros_like(W)
    for fam, B in blocks:
        a, b = (slice(None),) + fam.a, (slice(None),) + fam.b
        dw = W[a] - W[b]
        g = B[:, 0] * dw[0] + B[:, 1] * dw[1]              # B (w_a - w_b)
        out[a] += g
        out[b] -= g
    return out.reshape(w.shape)


def _as_product(blocks_of: Callable[[], Blocks], rows: int, cols: int) -> AddProduct:
    """An AddProduct out += J w on (n, 2) arrays for the Jacobian J whose blocks are -B."""
    blocks = blocks_of()

    def add(w: np.ndarray, out: np.ndarray) -> None:
        out -= block_product(blocks, np.ascontiguousarray(w.T), rows, cols).T
    return add


class SpringSet:
    """Hooke springs of one set (structural, shear or bending): f_a = -k (|l| - r) l/|l|.

    families: the set's families; k_tension / k_compression: the stiffness when the spring is
    longer / shorter than its rest length (equal for shear and bending)."""

    def __init__(self, name: str, families: list[Family], rows: int, cols: int,
                 k_tension: float, k_compression: float):
        self.name, self.families, self.rows, self.cols = name, families, rows, cols
        self.k_tension, self.k_compression = k_tension, k_compression

    def _k(self, length: np.ndarray, rest: float) -> np.ndarray | float:
        if self.k_tension == self.k_compression:
            return self.k_tension
        return np.where(length > rest, self.k_tension, self.k_compression)

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        X, F = x.reshape(self.rows, self.cols, 2), f.reshape(self.rows, self.cols, 2)
        for fam in self.families:
            length, u = spring_geometry(X, fam)
            fa = -self._k(length, fam.rest) * (length - fam.rest) * u    # f_a = -ks (|l| - r) l/|l|
            F[fam.a] += fa
            F[fam.b] -= fa                                              # f_b = -f_a

    def stiffness_blocks(self, x: np.ndarray, definite: bool = True) -> Blocks:
        """-df_a/dx_a of every spring: k [u u^T + (1 - r/|l|) (I - u u^T)], u = l/|l|.

        definite=True (the implicit solve, the frequency estimate): a compressed spring's
        transverse term k (1 - r/|l|) is negative (a compressed spring pushes sideways, it
        buckles), which would make the system matrix indefinite and conjugate gradients fail; as
        Choi & Ko do we clamp it at 0, so every block is positive semi-definite. definite=False:
        the exact derivative (for the finite-difference tests)."""
        X = x.reshape(self.rows, self.cols, 2)
        blocks = []
        for fam in self.families:
            length, u = spring_geometry(X, fam)
            k = self._k(length, fam.rest)
            across = 1.0 - fam.rest / np.maximum(length, EPS)
            if definite:
                across = np.maximum(across, 0.0)
            along = (k * np.ones_like(length))[..., 0]
            transverse = along * across[..., 0]
            B = (along - transverse) * _outer(u)       # k_along u u^T + k_across (I - u u^T)
            B[0, 0] += transverse
            B[1, 1] += transverse
            blocks.append((fam, B))
        return blocks

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray):
        """The exact df/dx as a product (no df/dv: Hooke's force does not depend on v)."""
        return _as_product(lambda: self.stiffness_blocks(x, definite=False),
                           self.rows, self.cols), None

    def energy(self, x: np.ndarray) -> float:
        """Elastic energy sum 1/2 k (|l| - r)^2."""
        X = x.reshape(self.rows, self.cols, 2)
        total = 0.0
        for fam in self.families:
            length, _ = spring_geometry(X, fam)
            total += 0.5 * float(np.sum(self._k(length, fam.rest) * (length - fam.rest) ** 2))
        return total


class SpringDamping:
    """The damping part of the springs: f_a = -k_d ((v_a - v_b) . l/|l|) l/|l|, f_b = -f_a.

    families: (family, k_d) pairs, for every spring set that is on."""

    def __init__(self, families: list[tuple[Family, float]], rows: int, cols: int):
        self.families, self.rows, self.cols = families, rows, cols

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        X, V = x.reshape(self.rows, self.cols, 2), v.reshape(self.rows, self.cols, 2)
        F = f.reshape(self.rows, self.cols, 2)
        for fam, kd in self.families:
            _, u = spring_geometry(X, fam)
            dv = V[fam.a] - V[fam.b]
            closing = (dv[..., 0] * u[..., 0] + dv[..., 1] * u[..., 1])[..., None]   # dv . u
            fa = -kd * closing * u                      # -kd ((v_a - v_b) . l/|l|) l/|l|
            F[fam.a] += fa
            F[fam.b] -= fa

    def damping_blocks(self, x: np.ndarray) -> Blocks:
        """-df_a/dv_a = k_d u u^T for every spring."""
        X = x.reshape(self.rows, self.cols, 2)
        return [(fam, kd * _outer(spring_geometry(X, fam)[1])) for fam, kd in self.families]

    def position_blocks(self, x: np.ndarray, v: np.ndarray) -> Blocks:
        """-df_a/dx_a of the damping force: k_d/|l| [ (dv.u) P + u (P dv)^T ], P = I - u u^T,
        dv = v_a - v_b. Not symmetric: Baraff & Witkin leave it out of the solve (so do we);
        it is here for the finite-difference tests and for completeness."""
        X, V = x.reshape(self.rows, self.cols, 2), v.reshape(self.rows, self.cols, 2)
        blocks = []
        for fam, kd in self.families:
            length, u = spring_geometry(X, fam)
            dv = V[fam.a] - V[fam.b]
            closing = np.sum(dv * u, axis=-1, keepdims=True)
            P = np.eye(2)[:, :, None, None] - _outer(u)
            Pdv = np.moveaxis(dv - closing * u, -1, 0)
            u2 = np.moveaxis(u, -1, 0)
            B = kd / np.maximum(length[..., 0], EPS) * (
                closing[..., 0] * P + u2[:, None] * Pdv[None, :])
            blocks.append((fam, B))
        return blocks

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray):
        return (_as_product(lambda: self.position_blocks(x, v), self.rows, self.cols),
                _as_product(lambda: self.damping_blocks(x), self.rows, self.cols))


class Wind:
    """Wind: f = load a(x, t) with a from app.physics.cloth.wind_field ("gust" or the slide's
    "lecture" field F = (sin(x y t), cos(z t)), read in the plane z = 1 of this 2-D lab, so
    cos(z t) = cos(t)). load is each particle's area times a fixed density (WIND_DENSITY): the
    wind pushes on the cloth's area, not on its mass, so strength is the acceleration it gives
    a cotton cloth, silk (half cotton's mass) gets twice that and denim 0.3x: silk flows, denim
    and rubber hardly move. `clock()` gives t; t is held during a step (an RK4 step sees one
    wind).
    Treated explicitly in the implicit solve (no Jacobian), as Baraff & Witkin treat external
    forces."""

    def __init__(self, field: str, strength: float, world: tuple[float, float],
                 clock: Callable[[], float], load: np.ndarray):
        self.field, self.strength, self.world, self.clock = field, strength, world, clock
        self.load = load

    def accumulate(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray, f: np.ndarray) -> None:
        ax, ay = wind_field(self.field, x[:, 0], x[:, 1], self.clock(), self.world)
        f[:, 0] += self.strength * self.load * ax
        f[:, 1] += self.strength * self.load * ay

    def jacobian(self, ps: ParticleSystem, x: np.ndarray, v: np.ndarray):
        return None, None


class Timed:
    """A force as it is, timed from outside by a Stopwatch (app/physics/timing.py): the seconds
    spent in it (and its Jacobian blocks) go to watch.spent[name], the calls to calls[name]."""

    def __init__(self, name: str, force, watch: Stopwatch, calls: dict[str, int]):
        self.name, self.force, self.watch, self.calls = name, force, watch, calls

    def _timed(self, fn: Callable, *args):
        with self.watch(self.name):
            out = fn(*args)
        self.calls[self.name] += 1
        return out

    def accumulate(self, ps, x, v, f) -> None:
        self._timed(self.force.accumulate, ps, x, v, f)

    def jacobian(self, ps, x, v):
        return self._timed(self.force.jacobian, ps, x, v)

    def stiffness_blocks(self, x) -> Blocks:
        return self._timed(self.force.stiffness_blocks, x) \
            if hasattr(self.force, "stiffness_blocks") else []

    def damping_blocks(self, x) -> Blocks:
        return self._timed(self.force.damping_blocks, x) \
            if hasattr(self.force, "damping_blocks") else []
