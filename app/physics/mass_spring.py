"""Cloth as a mass-spring system (the lectures' "Cloth Animation" pages), on the particle system.

A rows x cols grid of particles, each with its share of the cloth's area times the density as its
mass (the slide: "the mass of the entire cloth is the total area ... times the mass density"):
an interior particle owns one cell, an edge particle half a cell, a corner a quarter. Springs join
them in three sets, each one force object (and one effect of the scene):

    structural   grid neighbours (r, c)-(r, c+1) and (r, c)-(r+1, c)     resist stretching
    shear        the diagonals (r, c)-(r+1, c+1) and (r, c)-(r+1, c-1)   resist shearing
    bending      skip one: (r, c)-(r, c+2) and (r, c)-(r+2, c)           resist folding (in 2D a
                                                                          fold shortens them)

A spring pulls its ends a and b together along l = x_a - x_b, with damping along the spring:

    f_a = -[ k_s (|l| - r) + k_d ((v_a - v_b) . l/|l|) ] l/|l|,     f_b = -f_a

split into two force objects, the Hooke part (`SpringSet`) and the damping part (`SpringDamping`),
so each costs only when its effect is on. As in Blender, a structural spring has two stiffnesses:
k_s is the *tension* value when the spring is longer than its rest length r, the *compression*
value when it is shorter. Other forces: gravity f = m g, air resistance f = -k v (forces.Drag) and
wind (`Wind`, a pressure: a force per area, the same on every material, so a light cloth is
blown further than a heavy one).

**Blender's materials.** MATERIALS holds Blender's own cloth presets, from the files
scripts/presets/cloth/{Cotton,Denim,Leather,Rubber,Silk}.py of the blender/blender repository
(vertex mass, tension, compression, shear and bending stiffness, spring damping, air damping).
How Blender turns them into forces is in source/blender/simulation/intern/SIM_mass_spring.cc
(cloth_calc_spring_force, cloth_calc_force): a spring's stiffness is k = stiffness /
avg_spring_len (a force per unit *strain*, the same for any mesh resolution), a linear bending
spring's is stiffness / (20 avg_spring_len) with damping 0.5 x its stiffness (bending_damping's
default), the damping value is the spring's damping coefficient, air drag is f = -0.01
air_damping v, and gravity is 0.001 x 9.81 (Blender's solver does not count time in seconds).
Mapping to this lab's units (px, s, kg; g = 900 px/s^2):
  * length: Blender's springs are taken as 1/16 m (a 2 m plane of 32 x 32 cells), so one
    Blender metre = PX_PER_M = 256 px and a Blender spring = REF_CELL = 16 px;
  * time: one Blender time unit = TAU = sqrt(256 px x 0.00981 / 900 px/s^2) = 0.0528 s, the
    choice that turns Blender's gravity into the lab's g;
  * so stiffness k = K_UNIT x stiffness / spacing with K_UNIT = 256 / TAU^2 = 9.17e4 (a
    particle's weight strains a spring exactly as much as in Blender: m g / (k r) =
    0.00981 m / stiffness), damping k_d = damping / TAU, air k = 0.01 air_damping / TAU;
  * mass: Blender's vertex mass is the mass of one REF_CELL x REF_CELL cell, so the density is
    mass / 256 px^2 and a particle's mass is its area times that.
In these units a particle's weight strains a spring by 0.00981 x mass / tension: 0.03 % for silk,
0.02 % for cotton and denim, 0.005 % for leather, 0.2 % for rubber (heavy and soft).

**Fast NumPy.** Positions live in an (n, 2) array, row-major, so x.reshape(rows, cols, 2) is the
grid without a copy. A *family* of springs joins every (r, c) to (r + dr, c + dc): its first ends
are one strided slice X[a] of the grid and its second ends another, X[b], so a whole family is
handled by a few array operations and its forces are added with F[a] += f_a, F[b] -= f_a:
inside one family no particle appears twice in a slice, so no scatter-add is needed.

**Implicit Euler** (`implicit_euler`, Baraff & Witkin, "Large Steps in Cloth Simulation"):

    (M - h df/dv - h^2 df/dx) dv = h (f0 + h (df/dx) v0),    v' = v0 + dv,   x' = x0 + h v'

The Jacobians of a spring family are one 2x2 block per spring (df_a/dx_a = -B, df_a/dx_b = +B),
so the system matrix is M plus, per family, h (damping blocks) + h^2 (stiffness blocks): its
product with a vector is a handful of slice operations per family (`block_product`). It is solved
by conjugate gradients with a Jacobi (diagonal) preconditioner; pinned and grabbed particles are
filtered out of the solve (their rows stay 0: Baraff-Witkin's filter for a fixed particle).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, fields
from typing import Callable, Iterable

import numpy as np

from app.physics.cloth import Family, rod_sets, wind_field
from app.physics.forces import Drag, Gravity
from app.physics.integrators import INTEGRATORS, preconditioned_cg
from app.physics.particles import AddProduct, ParticleSystem

# ----- Blender's units -> the lab's (see the module docstring) ------------------------------------
G_LAB = 900.0                        # px/s^2, the lab's gravity (README: ~9.8 m/s^2 at ~92 px/m)
BLENDER_G = 9.81 * 0.001             # Blender's cloth solver scales gravity by 0.001
PX_PER_M = 256.0                     # one Blender metre
REF_CELL = 16.0                      # px: a Blender spring (1/16 m); a cell of it weighs `mass`
TAU = math.sqrt(PX_PER_M * BLENDER_G / G_LAB)      # seconds per Blender time unit (0.0528)
K_UNIT = PX_PER_M / TAU ** 2         # Blender stiffness -> kg px/s^2 per unit strain (9.17e4)
BENDING_DAMPING = 0.5    # Blender's default bending_damping (DNA_cloth_defaults.h): c = .5 TAU k
EPS = 1e-9                           # shortest length we divide by


@dataclass(frozen=True)
class Material:
    """A Blender cloth preset in Blender's own numbers."""

    mass: float            # vertex mass, kg
    tension: float         # stiffness when stretched
    compression: float     # stiffness when compressed
    shear_stiffness: float
    bending_stiffness: float
    spring_damping: float  # tension = compression = shear damping in every preset
    air_damping: float


MATERIALS: dict[str, Material] = {     # scripts/presets/cloth/*.py (blender/blender)
    "cotton": Material(0.3, 15, 15, 15, 0.5, 5, 1),
    "denim": Material(1, 40, 40, 40, 10, 25, 1),
    "leather": Material(0.4, 80, 80, 80, 150, 25, 1),
    "rubber": Material(3, 15, 15, 15, 25, 25, 1),
    "silk": Material(0.15, 5, 5, 5, 0.05, 0, 1),
}
MATERIAL_KEYS = tuple(f.name for f in fields(Material))
# kg/px^2: the wind's pressure is wind_strength x this per px^2 of cloth, for every material
# (cotton's density: wind_strength is the acceleration it gives cotton)
WIND_DENSITY = MATERIALS["cotton"].mass / REF_CELL ** 2


def material_settings(name: str) -> dict[str, float]:
    """The preset `name` as a dict of slider values (mass, tension, ..., air_damping)."""
    m = MATERIALS[name]
    return {k: float(getattr(m, k)) for k in MATERIAL_KEYS}


def spring_constants(values: dict, spacing: float) -> dict[str, float]:
    """Lab-unit constants from Blender-unit settings (dict with MATERIAL_KEYS) at this spacing:
    stiffness in kg/s^2, damping in kg/s, density in kg/px^2."""
    k_bending = K_UNIT * values["bending_stiffness"] / (20.0 * spacing)
    return {
        "k_tension": K_UNIT * values["tension"] / spacing,
        "k_compression": K_UNIT * values["compression"] / spacing,
        "k_shear": K_UNIT * values["shear_stiffness"] / spacing,
        "k_bending": k_bending,
        "kd": values["spring_damping"] / TAU,
        "kd_bending": BENDING_DAMPING * TAU * k_bending,
        "air": 0.01 * values["air_damping"] / TAU,
        "density": values["mass"] / REF_CELL ** 2,
    }


# ----- spring families on the grid ---------------------------------------------------------------
def _geometry(X: np.ndarray, fam: Family) -> tuple[np.ndarray, np.ndarray]:
    """|l| (m_r, m_c, 1) and l/|l| (m_r, m_c, 2) of every spring of a family, l = x_a - x_b."""
    l = X[fam.a] - X[fam.b]
    length = np.sqrt(np.sum(l * l, axis=-1, keepdims=True))
    return length, l / np.maximum(length, EPS)


def _outer(u: np.ndarray) -> np.ndarray:
    """u u^T for every spring, component-major: (2, 2, m_r, m_c)."""
    u2 = np.moveaxis(u, -1, 0)
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
            length, u = _geometry(X, fam)
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
            length, u = _geometry(X, fam)
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
            length, _ = _geometry(X, fam)
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
            _, u = _geometry(X, fam)
            closing = np.sum((V[fam.a] - V[fam.b]) * u, axis=-1, keepdims=True)
            fa = -kd * closing * u                      # -kd ((v_a - v_b) . l/|l|) l/|l|
            F[fam.a] += fa
            F[fam.b] -= fa

    def damping_blocks(self, x: np.ndarray) -> Blocks:
        """-df_a/dv_a = k_d u u^T for every spring."""
        X = x.reshape(self.rows, self.cols, 2)
        return [(fam, kd * _outer(_geometry(X, fam)[1])) for fam, kd in self.families]

    def position_blocks(self, x: np.ndarray, v: np.ndarray) -> Blocks:
        """-df_a/dx_a of the damping force: k_d/|l| [ (dv.u) P + u (P dv)^T ], P = I - u u^T,
        dv = v_a - v_b. Not symmetric: Baraff & Witkin leave it out of the solve (so do we);
        it is here for the finite-difference tests and for completeness."""
        X, V = x.reshape(self.rows, self.cols, 2), v.reshape(self.rows, self.cols, 2)
        blocks = []
        for fam, kd in self.families:
            length, u = _geometry(X, fam)
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
    """A force as it is, plus a stopwatch around it: the seconds spent in it (and its Jacobian
    blocks) go to spent[name], the calls to calls[name]. Keeps the timing out of the formulas."""

    def __init__(self, name: str, force, spent: dict[str, float], calls: dict[str, int]):
        self.name, self.force, self.spent, self.calls = name, force, spent, calls

    def _timed(self, fn: Callable, *args):
        t0 = time.perf_counter()
        try:
            return fn(*args)
        finally:
            self.spent[self.name] += time.perf_counter() - t0
            self.calls[self.name] += 1

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


# ----- the linear system of one implicit step ----------------------------------------------------
class MassSpringSystem(ParticleSystem):
    """A ParticleSystem on a rows x cols grid whose spring forces give their Jacobians as 2x2
    blocks per family, so implicit Euler's matrix-vector product is a few slice operations."""

    def __init__(self, x, v, mass, rows: int, cols: int, forces=(), pinned=()):
        super().__init__(x, v, mass, forces, pinned)
        self.rows, self.cols = rows, cols
        self.cg_tolerance = CG_TOLERANCE
        self.cg_residual = 0.0                    # |r| / |b| after the last implicit step

    def blocks(self, x: np.ndarray) -> tuple[Blocks, Blocks]:
        """The stiffness blocks (-df/dx) and damping blocks (-df/dv) of forces that have them."""
        stiff = [b for force in self.forces for b in force.stiffness_blocks(x)]
        damp = [b for force in self.forces for b in force.damping_blocks(x)]
        return stiff, damp

    def stiffness_product(self, x: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
        """w -> -(df/dx) w, component-major (2, n), with the definite blocks."""
        stiff, _ = self.blocks(x)
        return lambda w: block_product(stiff, w, self.rows, self.cols)

    def air_drag(self) -> float:
        """The air-resistance coefficient k of f = -k v (0 if off)."""
        return sum(getattr(f, "force", f).kd for f in self.forces
                   if isinstance(getattr(f, "force", f), Drag))

    def linear_system(self, x: np.ndarray, h: float):
        """At x: implicit Euler's A = M - h df/dv - h^2 df/dx and K = df/dx as products on
        component-major vectors (2, n), and 1/diag(A) (the Jacobi preconditioner), (2, n)."""
        stiff, damp = self.blocks(x)
        combined: dict[int, tuple[Family, np.ndarray]] = {}     # one block per family: h D + h^2 K
        for scale, blocks in ((h * h, stiff), (h, damp)):
            for fam, B in blocks:
                key = id(fam)
                B = combined[key][1] + scale * B if key in combined else scale * B
                combined[key] = (fam, B)
        system = list(combined.values())
        M = (self.mass + h * self.air_drag())[None, :]            # f = -k v: -h df/dv = h k I
        rows, cols = self.rows, self.cols

        def A(w: np.ndarray) -> np.ndarray:
            self.jac_products += 1
            return M * w + block_product(system, w, rows, cols)

        def K(w: np.ndarray) -> np.ndarray:
            return -block_product(stiff, w, rows, cols)

        diagonal = np.repeat(M, 2, axis=0).reshape(2, rows, cols)
        for fam, B in system:
            d = np.stack((B[0, 0], B[1, 1]))
            diagonal[(slice(None),) + fam.a] += d
            diagonal[(slice(None),) + fam.b] += d
        return A, K, 1.0 / diagonal.reshape(2, -1)


# CG stops at |r| <= CG_TOLERANCE |b|. Chosen from the error it leaves (the tolerance table of
# `python -m app bench mass_spring`): on a 32x32 cloth at h = 1/60 s, 1e-2 leaves the positions
# of one step within 1e-4 px of a 1e-10 solve (denim 3e-5, silk 7e-5, leather 3e-9 px), far
# below a pixel and below the O(h^2) error of linearising once per step, in ~35-95 iterations;
# every tenfold tightening costs another 15-25 iterations for an error nobody can see.
CG_TOLERANCE = 1e-2


def implicit_euler(ps: MassSpringSystem, h: float) -> None:
    """Baraff-Witkin's linearised backward Euler step:
    (M - h df/dv - h^2 df/dx) dv = h (f0 + h (df/dx) v0);  v' = v0 + dv;  x' = x0 + h v'."""
    x0, v0 = ps.x, ps.v
    f0 = ps.force(x0, v0).T                       # component-major (2, n): see block_product
    A, K, inv_diagonal = ps.linear_system(x0, h)
    b = h * (f0 + h * K(np.ascontiguousarray(v0.T)))
    dv, ps.cg_iterations, ps.cg_residual = preconditioned_cg(
        A, b, ps.free.T, inv_diagonal, ps.cg_tolerance, ps.cg_max_iterations)
    v = v0 + dv.T
    ps.set_xv(x0 + h * v, v)


STEPPERS: dict[str, Callable[[ParticleSystem, float], None]] = {
    name: (implicit_euler if name == "implicit_euler" else info.step)
    for name, info in INTEGRATORS.items()}


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


# ----- the cloth ---------------------------------------------------------------------------------
SET_NAMES = ("structural", "shear", "bending")
FORCE_EFFECTS = ("gravity", "air", "wind", "damping", "shear", "bending")
PINS = ("corner", "corners", "top", "none")     # top-left corner, both top corners, ...
MAX_COORD = 1e6        # px: beyond this a particle has blown up (is_finite says so before inf)
MAX_SPEED = 1e8        # px/s


class MassSpringCloth:
    """The grid, its particle system and its force objects; see the module docstring.

    Settings (change them, then call `configure()`): the Blender-unit material values
    (MATERIAL_KEYS), g, wind_field, wind_strength, and `on` (the effects that are on)."""

    def __init__(self, rows: int, cols: int, spacing: float, origin: tuple[float, float] = (0, 0),
                 pins: str = "top", world: tuple[float, float] = (960.0, 720.0)):
        if rows < 2 or cols < 2:
            raise ValueError("a cloth needs at least 2 x 2 particles")
        self.rows, self.cols, self.spacing = rows, cols, float(spacing)
        self.world = world
        rr, cc = np.mgrid[0:rows, 0:cols]
        x0 = np.stack([origin[0] + cc * spacing, origin[1] + rr * spacing], axis=-1).reshape(-1, 2)
        self.rest_x = x0.astype(float)
        # each particle's share of the cloth's area: 1 cell inside, 1/2 on an edge, 1/4 a corner
        share = np.ones((rows, cols))
        share[[0, -1], :] *= 0.5
        share[:, [0, -1]] *= 0.5
        self.area = share.ravel() * spacing * spacing
        self.ps = MassSpringSystem(x0, np.zeros_like(x0), self.area, rows, cols)
        self.sets = rod_sets(rows, cols, spacing, np.float64)   # the families (and a drawable
        self.locked = np.zeros((rows, cols), bool)              # structural set: app/draw)
        self.anchor = self.rest_x.reshape(rows, cols, 2).copy()
        self.grabbed: tuple[int, int] | None = None
        self.grab_target = (0.0, 0.0)
        self.default_pins = {"top": [(0, c) for c in range(cols)], "corner": [(0, 0)],
                             "corners": [(0, 0), (0, cols - 1)], "none": []}[pins]
        self.t = 0.0
        self.spent: dict[str, float] = {}
        self.calls: dict[str, int] = {}
        self.material = material_settings("cotton")
        self.g, self.wind_field, self.wind_strength = G_LAB, "gust", 600.0
        self.on: set[str] = {"gravity", "air", "damping", "shear", "bending"}
        self.lock_cells(self.default_pins)
        self.configure()

    # ----- settings -------------------------------------------------------------------------------
    def configure(self) -> None:
        """Rebuild the force list from the settings: only the effects that are on are in it, so
        an effect that is off costs nothing. Masses follow the density."""
        k = spring_constants(self.material, self.spacing)
        self.constants = k
        self.ps.mass[:] = self.area * k["density"]
        self._update_pins()
        sets = ["structural"] + [s for s in SET_NAMES[1:] if s in self.on]
        stiffness = {"structural": (k["k_tension"], k["k_compression"]),
                     "shear": (k["k_shear"],) * 2, "bending": (k["k_bending"],) * 2}
        damping = {"structural": k["kd"], "shear": k["kd"], "bending": k["kd_bending"]}
        forces = []
        if "gravity" in self.on:
            forces.append(("gravity", Gravity((0.0, self.g))))
        if "air" in self.on:
            forces.append(("air", Drag(k["air"])))
        if "wind" in self.on:
            forces.append(("wind", Wind(self.wind_field, self.wind_strength, self.world,
                                        lambda: self.t, self.area * WIND_DENSITY)))
        for name in sets:
            forces.append((name, SpringSet(name, self.sets[name].families, self.rows, self.cols,
                                           *stiffness[name])))
        damped = [(fam, damping[name]) for name in sets if damping[name] > 0
                  for fam in self.sets[name].families]       # silk: only its bending springs
        if "damping" in self.on and damped:
            forces.append(("damping", SpringDamping(damped, self.rows, self.cols)))
        for name, _ in forces:
            self.spent.setdefault(name, 0.0)
            self.calls.setdefault(name, 0)
        self.spent.setdefault("solve", 0.0)
        self.ps.forces = [Timed(name, force, self.spent, self.calls) for name, force in forces]
        self.active_sets = sets

    # ----- pins and the mouse (a grabbed particle is a moving pin) -----------------------------
    def _update_pins(self) -> None:
        pinned = self.locked.copy()
        if self.grabbed is not None:
            pinned[self.grabbed] = True
        ps = self.ps
        ps.inv_mass = np.where(pinned.ravel(), 0.0, 1.0 / ps.mass)
        ps.free = (~pinned.ravel()).astype(float)[:, None]

    def _index(self, cell: tuple[int, int]) -> int:
        return cell[0] * self.cols + cell[1]

    def _place(self, cell: tuple[int, int], pos) -> None:
        """Put a particle at pos at rest (Verlet's memory too, so it does not fly off)."""
        k = self._index(cell)
        self.ps.x[k] = pos
        self.ps.v[k] = 0.0
        if self.ps.x_prev is not None:
            self.ps.x_prev[k] = pos

    def lock_cells(self, cells: Iterable[tuple[int, int]]) -> None:
        for cell in cells:
            self.locked[cell] = True
            self._place(cell, self.rest_x[self._index(cell)])
            self.anchor[cell] = self.rest_x[self._index(cell)]
        self._update_pins()

    @property
    def x(self) -> np.ndarray:
        """Positions as (2, rows, cols), the Verlet cloth's layout (for app/draw/cloth_draw)."""
        return np.moveaxis(self.ps.x.reshape(self.rows, self.cols, 2), -1, 0)

    def grab(self, cell: tuple[int, int], pos: tuple[float, float]) -> None:
        self.release()
        self.grabbed = cell
        self.grab_target = pos
        self.locked[cell] = False
        self._update_pins()

    def release(self, pos: tuple[float, float] | None = None) -> None:
        """Drop the grabbed particle: it stays locked where it was dropped."""
        if self.grabbed is None:
            return
        cell, self.grabbed = self.grabbed, None
        if pos is not None:
            self._place(cell, pos)
        self.locked[cell] = True
        self.anchor[cell] = self.ps.x[self._index(cell)]
        self._update_pins()

    def unlock(self, cell: tuple[int, int]) -> None:
        self.locked[cell] = False
        self._update_pins()

    def unlock_all(self) -> None:
        """Free every particle (and drop a grab), then restore the default pins."""
        self.grabbed = None
        self.locked[:] = False
        self.lock_cells(self.default_pins)

    # ----- the step -------------------------------------------------------------------------------
    def step(self, h: float, integrator: str) -> None:
        """One step of h seconds with the named integrator (the grabbed particle is moved to the
        mouse first: a moving pin)."""
        if self.grabbed is not None:
            self._place(self.grabbed, self.grab_target)
        forces_before = self._force_seconds()
        t0 = time.perf_counter()
        STEPPERS[integrator](self.ps, h)
        elapsed = time.perf_counter() - t0
        # what the integrator itself spent (its vector arithmetic and, implicit, the CG solve)
        self.spent["solve"] += elapsed - (self._force_seconds() - forces_before)
        self.t += h

    def _force_seconds(self) -> float:
        return sum(v for k, v in self.spent.items() if k != "solve")

    # ----- what the scene reports -----------------------------------------------------------------
    def stretch(self, family: Family) -> np.ndarray:
        """|length / rest - 1| of every spring of a family, in the family's grid shape."""
        length, _ = _geometry(self.ps.x.reshape(self.rows, self.cols, 2), family)
        return np.abs(length[..., 0] / family.rest - 1.0)

    def spring_count(self) -> int:
        return sum(int(f.alive.size) for s in self.active_sets for f in self.sets[s].families)

    def energy(self) -> float:
        """Kinetic + elastic (active springs) + gravitational energy, 0 at rest in the start
        pose (y down: a particle that fell by d lost m g d)."""
        ps = self.ps
        free = ps.free[:, 0]
        e = 0.5 * float(np.sum(free * ps.mass * np.sum(ps.v * ps.v, axis=1)))
        for force in ps.forces:
            if isinstance(force.force, SpringSet):
                e += force.force.energy(ps.x)
        if "gravity" in self.on:
            e -= self.g * float(np.sum(free * ps.mass * (ps.x[:, 1] - self.rest_x[:, 1])))
        return e

    def kinetic_energy(self) -> float:
        ps = self.ps
        return 0.5 * float(np.sum(ps.free[:, 0] * ps.mass * np.sum(ps.v * ps.v, axis=1)))

    def pinned_drift(self) -> float:
        """Largest distance a locked particle has moved from where it was locked."""
        if not self.locked.any():
            return 0.0
        d = self.ps.x.reshape(self.rows, self.cols, 2)[self.locked] - self.anchor[self.locked]
        return float(np.sqrt((d ** 2).sum(-1)).max())

    def is_sane(self) -> bool:
        """Finite, and no particle beyond MAX_COORD px or faster than MAX_SPEED px/s: a blown-up
        explicit step is caught here, a second or so before it reaches inf."""
        ps = self.ps
        return bool(np.isfinite(ps.x).all() and np.isfinite(ps.v).all()
                    and np.abs(ps.x).max() < MAX_COORD and np.abs(ps.v).max() < MAX_SPEED)

    def copy_state(self) -> dict:
        return {"ps": self.ps.copy_state(), "locked": self.locked.copy(),
                "anchor": self.anchor.copy(), "grabbed": self.grabbed,
                "grab_target": self.grab_target, "t": self.t}

    def restore_state(self, snap: dict) -> None:
        self.ps.restore_state(snap["ps"])
        self.locked[...] = snap["locked"]
        self.anchor[...] = snap["anchor"]
        self.grabbed, self.grab_target, self.t = snap["grabbed"], snap["grab_target"], snap["t"]
        self._update_pins()


__all__ = ["MATERIALS", "Material", "material_settings", "spring_constants", "SpringSet",
           "SpringDamping", "Wind", "Timed", "MassSpringSystem", "implicit_euler", "STEPPERS",
           "top_mode", "symplectic_limit", "predicted_limit", "MassSpringCloth", "block_product",
           "CG_TOLERANCE", "WIND_DENSITY", "K_UNIT", "TAU", "PX_PER_M", "PINS", "FORCE_EFFECTS"]
