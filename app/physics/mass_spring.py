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
so each costs only when its effect is on. A structural spring has two stiffnesses, Blender's
*tension* and *compression* values: k_s is the tension value when the spring is longer than its
rest length r, the compression value when it is shorter. Plain Hooke springs either way are our
simplification, not Blender's model: Blender resists compression only along Choi & Ko's buckling
curve (or linearly with `resist_compress`), its shear springs resist no compression at all, and
its default bending is angular (app/physics/blender_cloth.py). Other forces: gravity f = m g, air resistance f = -k v (forces.Drag) and
wind (`Wind`, a pressure: a force per area, the same on every material, so a light cloth is
blown further than a heavy one).

**Blender's materials** and their units: app/physics/blender_cloth.py.

**Fast NumPy**, the forces by spring family: app/physics/spring_forces.py. **The explicit
limit** (omega_max, each integrator's largest step): app/physics/mass_spring_stability.py.

**Implicit Euler** (`implicit_euler`, Baraff & Witkin, "Large Steps in Cloth Simulation"):

    (M - h df/dv - h^2 df/dx) dv = h (f0 + h (df/dx) v0),    v' = v0 + dv,   x' = x0 + h v'

The Jacobians of a spring family are one 2x2 block per spring (df_a/dx_a = -B, df_a/dx_b = +B),
so the system matrix is M plus, per family, h (damping blocks) + h^2 (stiffness blocks): a sparse
matrix whose pattern never changes, so it is built once and its numbers refreshed in place each
step (app/physics/cloth_matrix.py). Pinned and grabbed particles are filtered out of the solve
(their rows stay 0: Baraff-Witkin's filter for a fixed particle). Two solvers (`solver`):

    cg       conjugate gradients (the lecture's, app/physics/linear_solve.py), handed the matrix's
             product, a 2x2 block Jacobi preconditioner and a first guess extrapolated from the
             last two steps' dv; it stops at CG_TOLERANCE of the residual;
    direct   SciPy's sparse LU (SuperLU): exact up to rounding, but it factors the matrix anew
             every step, and its factors fill in (`python -m app bench mass_spring` measures both).
"""

from __future__ import annotations

import time
from typing import Callable, Iterable, NamedTuple

import numpy as np

from app.physics.blas_threads import one_blas_thread
from app.physics.blender_cloth import G_LAB, WIND_DENSITY, material_settings, spring_constants
from app.physics.forces import Drag, Gravity
from app.physics.integrators import INTEGRATORS
from app.physics.cloth_matrix import ClothMatrix
from app.physics.linear_solve import solve, solve_directly
from app.physics.particles import ParticleSystem
from app.physics.rods import Family, rod_sets
from app.physics.spring_forces import (Blocks, SpringDamping, SpringSet, Timed, Wind, block_product,
                                       spring_geometry)
from app.physics.timing import Stopwatch


# ----- the linear system of one implicit step ----------------------------------------------------
class MassSpringSystem(ParticleSystem):
    """A ParticleSystem on a rows x cols grid whose spring forces give their Jacobians as 2x2
    blocks per family, which implicit Euler writes into a sparse matrix of a fixed pattern."""

    def __init__(self, x, v, mass, rows: int, cols: int, forces=(), pinned=()):
        super().__init__(x, v, mass, forces, pinned)
        self.rows, self.cols = rows, cols
        self.cg_tolerance = CG_TOLERANCE
        self.solver = "cg"                         # or "direct" (SOLVERS)
        self.budget_iterations: int | None = None  # CG's most that fit the step's time budget
        self.matrix: ClothMatrix | None = None     # A's pattern, built on the first solve
        self.last_dv: np.ndarray | None = None     # the last two steps' dv (2, n), for CG's
        self.dv_before: np.ndarray | None = None   # first guess (next_dv_guess)

    def next_dv_guess(self) -> np.ndarray | None:
        """CG's first guess for this step's dv: the last two extrapolated, 2 dv_1 - dv_2 (a
        cloth that moves smoothly changes its velocity smoothly), or the last one alone. CG
        keeps it only if it beats dv = 0 (preconditioned_cg). Measured on the 64x64 denim cloth
        over its first 2.5 s: 133 iterations a step from 0, 101 from the last dv, 83 from the
        extrapolation."""
        if self.last_dv is None or self.last_dv.shape != (2, self.n):
            return None
        if self.dv_before is None:
            return self.last_dv
        return 2.0 * self.last_dv - self.dv_before

    def copy_state(self) -> dict:
        copy = lambda a: None if a is None else a.copy()      # noqa: E731
        return {**super().copy_state(), "last_dv": copy(self.last_dv),
                "dv_before": copy(self.dv_before)}

    def restore_state(self, snap: dict) -> None:
        super().restore_state(snap)
        copy = lambda a: None if a is None else a.copy()      # noqa: E731
        self.last_dv, self.dv_before = copy(snap.get("last_dv")), copy(snap.get("dv_before"))

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

    def linear_system(self, x: np.ndarray, h: float) -> "ImplicitSystem":
        """At x: implicit Euler's A = M - h df/dv - h^2 df/dx as a sparse matrix with a fixed
        pattern, refreshed in place (app/physics/cloth_matrix.py), its product and its block
        Jacobi preconditioner on component-major vectors (2, n); K = df/dx as a product; and a
        direct solve of A (solver=direct, or the fallback where CG stops short)."""
        stiff, damp = self.blocks(x)
        combined: dict[int, tuple[Family, np.ndarray]] = {}     # one block per family: h D + h^2 K
        for scale, blocks in ((h * h, stiff), (h, damp)):
            for fam, B in blocks:
                key = id(fam)
                B = combined[key][1] + scale * B if key in combined else scale * B
                combined[key] = (fam, B)
        system = list(combined.values())
        families = [fam for fam, _ in system]
        if self.matrix is None or not self.matrix.key_matches(families):
            self.matrix = ClothMatrix(families, self.rows, self.cols)   # a new pattern
        matrix = self.matrix
        matrix.refresh(self.mass + h * self.air_drag(), system)   # f = -k v: -h df/dv = h k I
        rows, cols = self.rows, self.cols

        def A(w: np.ndarray) -> np.ndarray:
            self.jac_products += 1
            return matrix.product(w)

        def K(w: np.ndarray) -> np.ndarray:
            return -block_product(stiff, w, rows, cols)

        def direct(b: np.ndarray) -> tuple[np.ndarray | None, int | None]:
            """A x = b on the free rows by SuperLU's sparse LU, x = 0 on the fixed ones."""
            free = self.free[:, 0] > 0
            solve_lu, fill = matrix.factorize(free)
            if solve_lu is None:
                return None, None
            return solve_lu(b * free[None, :]), fill
        return ImplicitSystem(A, K, matrix.block_jacobi(), direct)


class ImplicitSystem(NamedTuple):
    """One implicit step's linear system (MassSpringSystem.linear_system)."""
    A: Callable[[np.ndarray], np.ndarray]         # w -> A w
    K: Callable[[np.ndarray], np.ndarray]         # w -> (df/dx) w
    precondition: Callable[[np.ndarray], np.ndarray]    # r -> z, the block Jacobi
    direct: Callable[[np.ndarray], tuple[np.ndarray | None, int | None]]   # b -> (A^-1 b, fill)


# CG stops at |r| <= CG_TOLERANCE |b|: relative to |b|, which grows with the motion, so what it
# leaves in the positions grows too. Measured after one step at h = 1/60 s against a 1e-10 solve
# (the scene's cloth, corner pins; issue 19's solver: block Jacobi, warm start; the solver before
# it, Jacobi from dv = 0, left as much): a 32x32 cloth 5 and 20 steps into its fall, 0.003-0.014 px
# (leather, cotton, denim, silk; before: 0.003-0.012); the scene's default cloth over its first
# second, at most 0.04 px (0.03); in a fling, the grabbed particle moved 32 px a step (1920 px/s,
# the cloth up to ~2700 px/s), 0.5-5.7 px (0.7-8.3): a few per cent of a step of 32 px. Below a
# pixel except in a fling, and smaller than the O(h^2) error of linearising once per step, in
# 11-53 iterations at 32x32 (to 1e-10: 145-341).
CG_TOLERANCE = 1e-2


SOLVERS = ("cg", "direct")     # how implicit_euler solves its system (MassSpringSystem.solver)


def implicit_euler(ps: MassSpringSystem, h: float) -> None:
    """Baraff-Witkin's linearised backward Euler step:
    (M - h df/dv - h^2 df/dx) dv = h (f0 + h (df/dx) v0);  v' = v0 + dv;  x' = x0 + h v'.
    solver "cg": conjugate gradients with the block Jacobi preconditioner, started from the last
    steps' dv (the sparse LU where it stops short); "direct": the sparse LU (CG where it fails).
    CG stops after ps.cg_max_iterations (default: the unknowns) or ps.budget_iterations (what
    fits the scene's time budget, app/physics/mass_spring_cost.py), whichever is fewer; stopped
    by the budget it takes no direct solve (that would not fit either) and reports "budget"."""
    x0, v0 = ps.x, ps.v
    f0 = ps.force(x0, v0).T                       # component-major (2, n): see block_product
    system = ps.linear_system(x0, h)
    b = h * (f0 + h * system.K(np.ascontiguousarray(v0.T)))
    free = ps.free.T

    unknowns = 2 * int(ps.free.sum())
    cap = min(ps.cg_max_iterations or unknowns, ps.budget_iterations or unknowns)
    budget = cap < (ps.cg_max_iterations or unknowns)   # the time budget caps CG, not the size

    def cg(fallback=None):
        dv, report = solve(system.A, b, free, system.precondition, ps.cg_tolerance, cap,
                           None if budget else fallback, x0=ps.next_dv_guess())
        if budget and report.stop == "iteration cap":
            report.stop = "budget"                # no direct solve either: it would not fit
        return dv, report
    if ps.solver == "direct":
        dv, report = solve_directly(system.A, b, free, "sparse LU", lambda: system.direct(b),
                                    ps.cg_tolerance, cg)
    else:
        dv, report = cg(("sparse LU", lambda: system.direct(b)[0]))
    ps.record_solve(report)
    ps.last_dv, ps.dv_before = dv, ps.last_dv
    v = v0 + dv.T
    ps.set_xv(x0 + h * v, v)


STEPPERS: dict[str, Callable[[ParticleSystem, float], None]] = {
    name: (implicit_euler if name == "implicit_euler" else info.step)
    for name, info in INTEGRATORS.items()}


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
        self._verlet_back: np.ndarray | None = None
        self.watch = Stopwatch()                 # seconds per force, timed around the forces
        self.spent = self.watch.spent
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
        self.ps.forces = [Timed(name, force, self.watch, self.calls) for name, force in forces]
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
        # Verlet's positions a step back (x_n-1, the same h), for its centred velocity (energy())
        ps = self.ps
        self._verlet_back = (ps.x_prev if integrator == "verlet" and ps.x_prev is not None
                             and ps.h_prev == h else None)
        clock = self.watch.clock                  # (the forces' clock: a bench may set CPU time)
        t0 = clock()
        with one_blas_thread(self.ps.x.size):     # (BLAS's threads hurt on long vectors)
            STEPPERS[integrator](self.ps, h)
        elapsed = clock() - t0
        # what the integrator itself spent (its vector arithmetic and, implicit, the CG solve)
        self.spent["solve"] += elapsed - (self._force_seconds() - forces_before)
        self.t += h

    def _force_seconds(self) -> float:
        return sum(v for k, v in self.spent.items() if k != "solve")

    # ----- what the scene reports -----------------------------------------------------------------
    def stretch(self, family: Family) -> np.ndarray:
        """|length / rest - 1| of every spring of a family, in the family's grid shape."""
        length, _ = spring_geometry(self.ps.x.reshape(self.rows, self.cols, 2), family)
        return np.abs(length[..., 0] / family.rest - 1.0)

    def spring_count(self) -> int:
        return sum(int(f.alive.size) for s in self.active_sets for f in self.sets[s].families)

    def energy(self) -> float:
        """Kinetic + elastic (active springs) + gravitational energy, 0 at rest in the start
        pose (y down: a particle that fell by d lost m g d).

        After a Verlet step it is the energy one step back, at x_n, with the centred velocity
        (x_n+1 - x_n-1) / 2h: Verlet's own velocity estimate v' = (x' - x)/h + a h/2 (taken at
        the new point with the old acceleration) is off by O(h^2) in a way that does not average
        out, so on an undamped cloth the energy it gives climbs (cotton without damping or air
        at h = 0.5 ms: +2.1 J over 6 s) while the centred one stays within 0.24 J of 0."""
        return sum(self.energy_parts())

    def energy_parts(self) -> tuple[float, float, float]:
        """(kinetic, elastic, gravitational) energy, each as energy() takes it: 0 at rest in the
        start pose, the Verlet step's at x_n with the centred velocity."""
        ps = self.ps
        x, v = ps.x, ps.v
        if self._verlet_back is not None and ps.x_prev is not None:
            x, v = ps.x_prev, (ps.x - self._verlet_back) / (2.0 * ps.h_prev)
        free = ps.free[:, 0]
        kinetic = 0.5 * float(np.sum(free * ps.mass * np.sum(v * v, axis=1)))
        elastic = 0.0
        for force in ps.forces:
            if isinstance(force.force, SpringSet):
                elastic += force.force.energy(x)
        gravity = 0.0
        if "gravity" in self.on:
            gravity = -self.g * float(np.sum(free * ps.mass * (x[:, 1] - self.rest_x[:, 1])))
        return kinetic, elastic, gravity

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
        self._verlet_back = None
        self._update_pins()


__all__ = ["MassSpringSystem", "implicit_euler", "STEPPERS", "MassSpringCloth", "CG_TOLERANCE", "SOLVERS",
           "PINS", "FORCE_EFFECTS", "SET_NAMES"]
