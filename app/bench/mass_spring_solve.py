"""`bench mass_spring`, its second half: the implicit cloth at classroom scale (issue 19).

1. Targets: denim, the scene's defaults otherwise (both top corners pinned, 60 Hz, 1 substep, CG
   to 1e-2), at 32x32 and 64x64: the median wall ms of a step (scene.advance(), as `--headless`
   times it, every step counted) over the first TARGET_SECONDS from rest, in REPEATS runs, beside
   its target (TARGETS). Where it is missed, the measured reason: the step split into the
   forces (with their Jacobian blocks) and the solve, CG's iterations and the solve's ms per
   iteration.
2. Routes: the same run solved each way the issue names, one at a time, from the same start:
   how A w is formed (NumPy slices per spring family, as before; a SciPy matrix of a fixed
   pattern refreshed in place, in row (CSR) or diagonal (DIA) storage), the preconditioner
   (Jacobi; 2x2 block Jacobi; SciPy's incomplete LU, refactored every step) and CG's first
   guess (0; the last step's dv; the last two extrapolated). Each row: ms per step, CG's mean
   iterations, and how far its cloth ended from the kept route's (max px): the same answers to
   the CG tolerance. Measured once by hand and not repeated here: pyamg's smoothed aggregation
   (25 iterations but 3 ms per application and 12-33 ms of set-up per step at 64x64: ~80 ms a
   solve), an exact LU of the previous step as preconditioner (4 iterations of 1.6-3 ms plus a
   58-100 ms factorization whenever it is renewed), SSOR by SciPy's triangular solves (49
   iterations of 4.7 ms), a two-level preconditioner with 4x4-particle aggregates (53 iterations
   instead of 85, each dearer): none paid (load 1.5-3.6).
3. Solvers (the scene's `solver`): CG against SciPy's sparse LU on the same cloth at several
   sizes: ms of the solve and of the whole step, CG's iterations, the LU factors' non-zeros
   against A's (the fill), and how each grows with the cloth: why Baraff & Witkin used CG,
   measured.
4. The window: the slowest settings the sliders accept (the stiffest and the lightest cloth, the
   largest size, the tightest tolerance and the most substeps the budget takes, each solver at
   hertz 1 / 60 / 1000, shear off and on): the step the budget estimated, the median and the
   longest step measured (CORNER_STEPS steps from rest), and a frame's worth of steps (hertz/60,
   at most 8) against the scene's FRAME_BUDGET_S.
"""

from __future__ import annotations

import math
import time
from typing import Any, Callable

import numpy as np

from app.bench import Timing
from scipy import sparse
from scipy.sparse.linalg import spilu

from app.bench import Report
from app.physics.cloth_matrix import ClothMatrix
from app.physics.linear_solve import preconditioned_cg
from app.physics.mass_spring_cost import FRAME_BUDGET_S, frame_cost, steps_per_frame
from app.physics.spring_forces import block_product
from app.scene import ParamError

TARGETS = {32: 4.0, 64: 16.0}            # ms a step (issue 19)
TARGET_SECONDS = 2.0                     # simulated seconds from rest, every step counted
REPEATS = 3
ROUTE_SECONDS = 2.0
ILU_STEPS = 20
SOLVER_SIZES = (16, 32, 48, 64)
SOLVER_STEPS = 30
CORNER_STEPS = 6
STIFF = {"tension": 1e5, "compression": 1e5, "shear_stiffness": 1e5, "bending_stiffness": 1e5}


def denim_scene(n: int, **settings):
    from scenes.mass_spring_cloth import MassSpringClothScene
    return MassSpringClothScene({"material": "denim", "rows": n, "cols": n, **settings})


# ----- 1. the targets ----------------------------------------------------------------------------
def target_run(n: int, seconds: float) -> dict[str, Any]:
    """One run of the denim scene at n x n from rest: every step's wall ms and CG iterations,
    and the cloth's own split of the time (forces with their blocks / solve)."""
    scene = denim_scene(n)
    spent0 = dict(scene.cloth.spent)
    ms, its = [], []
    for _ in range(round(seconds * scene.p["hertz"])):
        t0 = time.perf_counter()
        scene.advance()
        ms.append((time.perf_counter() - t0) * 1e3)
        its.append(scene.cloth.ps.cg_iterations)
    spent = {k: (v - spent0.get(k, 0.0)) * 1e3 / len(ms) for k, v in scene.cloth.spent.items()}
    solve = spent.pop("solve")
    return {"ms": ms, "its": its, "forces_ms": sum(spent.values()), "solve_ms": solve,
            "failures": scene.cloth.ps.cg_failures}


def targets(report: Report, quick: bool) -> list[dict[str, Any]]:
    rows = []
    for n, target in TARGETS.items():
        if quick and n > 32:
            continue
        report.progress(f"target: denim {n}x{n}")
        runs = [target_run(n, 0.5 if quick else TARGET_SECONDS) for _ in range(1 if quick else
                                                                                 REPEATS)]
        ms = np.concatenate([r["ms"] for r in runs])
        its = np.concatenate([r["its"] for r in runs])
        median = Timing.of(ms)                       # every step's ms: median, IQR, count
        forces = Timing.of([r["forces_ms"] for r in runs])
        solve = Timing.of([r["solve_ms"] for r in runs])
        per_iteration = solve / max(float(its.mean()), 1.0)
        met = median <= target
        reason = "" if met else (
            f"forces and their blocks {forces:.3g} ms + solve {solve:.3g} ms = "
            f"{its.mean():.0f} CG iterations x {per_iteration:.3g} ms (A's product, the "
            f"preconditioner and CG's vector arithmetic)")
        rows.append({"size": n, "target_ms": target, "median_ms": median,
                     "p90_ms": float(np.percentile(ms, 90)), "max_ms": float(ms.max()),
                     "cg_iterations_mean": float(its.mean()), "cg_iterations_max": int(its.max()),
                     "forces_ms": forces, "solve_ms": solve, "ms_per_iteration": per_iteration,
                     "cg_failures": sum(r["failures"] for r in runs), "met": met,
                     "reason": reason, "steps": int(ms.size)})
    report.table(f"targets: denim, the scene's defaults otherwise, ms a step over the first "
                 f"{TARGET_SECONDS:g} s from rest ({REPEATS} runs; without --full: 0.5 s, 1 run)",
                 ["size", "target", "median", "p90", "max", "CG its (mean/max)", "forces",
                  "solve", "verdict"],
                 [[f"{r['size']}x{r['size']}", f"<= {r['target_ms']:g}", f"{r['median_ms']:.3g}",
                   f"{r['p90_ms']:.3g}", f"{r['max_ms']:.3g}",
                   f"{r['cg_iterations_mean']:.0f}/{r['cg_iterations_max']}",
                   f"{r['forces_ms']:.3g}", f"{r['solve_ms']:.3g}",
                   "met" if r["met"] else "MISSED"] for r in rows])
    for r in rows:
        if not r["met"]:
            report.say(f"  {r['size']}x{r['size']} missed its {r['target_ms']:g} ms: "
                       f"{r['reason']}")
    return rows


# ----- 2. the routes -----------------------------------------------------------------------------
def combined_blocks(ps, x: np.ndarray, h: float):
    """h D + h^2 K per family, as MassSpringSystem.linear_system forms them."""
    stiff, damp = ps.blocks(x)
    out: dict[int, tuple] = {}
    for scale, blocks in ((h * h, stiff), (h, damp)):
        for fam, B in blocks:
            out[id(fam)] = (fam, out[id(fam)][1] + scale * B if id(fam) in out else scale * B)
    return stiff, list(out.values())


class Route:
    """One way of solving implicit Euler's system: product 'slices' | 'csr' | 'dia',
    preconditioner 'jacobi' | 'block' | 'ilu', first guess 'zero' | 'last' | 'extrapolated'."""

    def __init__(self, product: str, preconditioner: str, guess: str):
        self.product, self.preconditioner, self.guess = product, preconditioner, guess
        self.matrix: ClothMatrix | None = None
        self.last: list[np.ndarray] = []

    @property
    def label(self) -> str:
        guess = {"zero": "dv = 0", "last": "last dv", "extrapolated": "2 dv1 - dv2"}[self.guess]
        return f"{self.product} + {self.preconditioner} + {guess}"

    def step(self, ps, h: float) -> int:
        """One implicit Euler step of ps by this route; returns CG's iterations."""
        x0, v0 = ps.x, ps.v
        f0 = ps.force(x0, v0).T
        stiff, system = combined_blocks(ps, x0, h)
        mass = ps.mass + h * ps.air_drag()
        if self.matrix is None:
            self.matrix = ClothMatrix([fam for fam, _ in system], ps.rows, ps.cols,
                                      "csr" if self.product == "csr" else "dia")
        m = self.matrix
        m.refresh(mass, system)            # also the diagonal blocks (the preconditioners)
        if self.product == "slices":
            A: Callable = lambda w: mass * w + block_product(system, w, ps.rows, ps.cols)  # noqa
        else:
            A = m.product
        free = ps.free.T
        b = h * (f0 - h * block_product(stiff, np.ascontiguousarray(v0.T), ps.rows, ps.cols))
        precondition = self.precondition(m, free)
        guess = None
        if self.guess != "zero" and self.last:
            guess = (2 * self.last[-1] - self.last[-2] if self.guess == "extrapolated"
                     and len(self.last) > 1 else self.last[-1])
        dv, report = preconditioned_cg(A, b, free, precondition, ps.cg_tolerance, None, guess)
        self.last = (self.last + [dv])[-2:]
        v = v0 + dv.T
        ps.set_xv(x0 + h * v, v)
        return report.iterations

    def precondition(self, m: ClothMatrix, free: np.ndarray):
        if self.preconditioner == "block":
            return m.block_jacobi()
        if self.preconditioner == "jacobi":
            inv = 1.0 / np.stack((m.diagonal_blocks[0, 0].ravel(), m.diagonal_blocks[1, 1].ravel()))
            return lambda r: inv * r
        keep = np.tile(free.ravel(), 2)                   # 'ilu': A filtered, as factorize does
        F = sparse.diags(keep)
        ilu = spilu((F @ m.matrix @ F + sparse.diags(1.0 - keep)).tocsc(), drop_tol=1e-3,
                    fill_factor=5, permc_spec="MMD_AT_PLUS_A")
        return lambda r: ilu.solve(r.reshape(-1)).reshape(r.shape) * free


ROUTES = [("slices", "jacobi", "zero"), ("csr", "jacobi", "zero"), ("dia", "jacobi", "zero"),
          ("dia", "block", "zero"), ("dia", "ilu", "zero"), ("dia", "block", "last"),
          ("dia", "block", "extrapolated")]          # the last: what implicit_euler does


def reference_positions(n: int, steps: list[int]) -> dict[int, np.ndarray]:
    """The exact linearised steps (the sparse LU every step) from the same start: positions
    after each of `steps` steps."""
    cloth = denim_scene(n).cloth
    cloth.ps.solver = "direct"                  # past the window's step budget: measured here
    out = {}
    for k in range(1, max(steps) + 1):
        cloth.step(1.0 / 60.0, "implicit_euler")
        if k in steps:
            out[k] = cloth.ps.x.copy()
    return out


def routes(report: Report, quick: bool) -> list[dict[str, Any]]:
    rows = []
    seconds = 0.25 if quick else ROUTE_SECONDS
    for n in ((16,) if quick else (32, 64)):
        h = 1.0 / 60.0
        full = round(seconds / h)
        exact = reference_positions(n, sorted({full, min(full, ILU_STEPS)}))
        for spec in ROUTES:
            route = Route(*spec)
            report.progress(f"route {n}x{n}: {route.label}")
            cloth = denim_scene(n).cloth
            steps = min(full, ILU_STEPS) if spec[1] == "ilu" else full   # ilu: 0.1 s a step
            ms, its = [], []
            for _ in range(steps):
                t0 = time.perf_counter()
                its.append(route.step(cloth.ps, h))
                ms.append((time.perf_counter() - t0) * 1e3)
            rows.append({"size": n, "route": route.label, "product": spec[0],
                         "preconditioner": spec[1], "guess": spec[2], "steps": steps,
                         "kept": spec == ROUTES[-1], "median_ms": Timing.of(ms),
                         "cg_iterations_mean": float(np.mean(its)),
                         "max_px_from_exact": float(np.abs(cloth.ps.x - exact[steps]).max())})
    base = {r["size"]: r["median_ms"] for r in reversed(rows)}      # each size's first row
    report.table(f"routes: denim n x n, the first {seconds:g} s from rest (incomplete LU: "
                 f"{ILU_STEPS} steps at most), each alone; the last row is what the scene does; "
                 "speed-up against the first (as before issue 19); px from the exact linearised "
                 "steps (the sparse LU every step) at the end: every route solves to the same "
                 "1e-2",
                 ["size", "A w + preconditioner + first guess", "ms/step", "speed-up",
                  "CG its", "steps", "max px from exact"],
                 [[f"{r['size']}x{r['size']}", r["route"], r["median_ms"],
                   f"{base[r['size']] / r['median_ms']:.2f}", f"{r['cg_iterations_mean']:.0f}",
                   r["steps"], f"{r['max_px_from_exact']:.2g}"] for r in rows])
    return rows


# ----- 3. CG against the direct solve ------------------------------------------------------------
def solvers(report: Report, quick: bool) -> dict[str, Any]:
    rows, steps = [], 10 if quick else SOLVER_STEPS
    for n in ((16, 24) if quick else SOLVER_SIZES):
        for solver in ("cg", "direct"):
            report.progress(f"solver {solver} at {n}x{n}")
            scene = denim_scene(n)
            scene.cloth.ps.solver = solver           # past the step budget too: measured here
            spent = scene.cloth.spent
            step_ms, solve_ms, its = [], [], []
            for _ in range(steps):
                s0, t0 = spent["solve"], time.perf_counter()
                scene.advance()
                step_ms.append((time.perf_counter() - t0) * 1e3)
                solve_ms.append((spent["solve"] - s0) * 1e3)
                its.append(scene.cloth.ps.cg_iterations)
            ps = scene.cloth.ps
            rows.append({"size": n, "solver": solver, "step_ms": Timing.of(step_ms),
                         "solve_ms": Timing.of(solve_ms),
                         "cg_iterations_mean": float(np.mean(its)),
                         "nonzeros": ps.matrix.nonzeros, "fill": ps.solve.fill,
                         "residual": ps.solve.residual})
    table = []
    for n in sorted({r["size"] for r in rows}):
        cg = next(r for r in rows if r["size"] == n and r["solver"] == "cg")
        lu = next(r for r in rows if r["size"] == n and r["solver"] == "direct")
        table.append([f"{n}x{n}", cg["solve_ms"], f"{cg['cg_iterations_mean']:.0f}",
                      lu["solve_ms"], f"{lu['solve_ms'] / cg['solve_ms']:.1f}",
                      cg["step_ms"], lu["step_ms"], f"{cg['nonzeros']:,}",
                      f"{lu['fill']:,}", f"{lu['fill'] / cg['nonzeros']:.1f}"])
    report.table(f"solver: CG (block Jacobi, warm start, to 1e-2) vs SciPy's sparse LU, denim n x "
                 f"n, median of the first {steps} steps (ms)",
                 ["size", "CG solve", "CG its", "LU solve", "LU/CG", "CG step", "LU step",
                  "A non-zeros", "LU non-zeros", "fill"], table)
    growth = {}
    sizes = sorted({r["size"] for r in rows})
    lo, hi = sizes[0], sizes[-1]
    for solver in ("cg", "direct"):
        a = next(r for r in rows if r["size"] == lo and r["solver"] == solver)["solve_ms"]
        b = next(r for r in rows if r["size"] == hi and r["solver"] == solver)["solve_ms"]
        growth[solver] = math.log(b / a) / math.log((hi / lo) ** 2)     # ms ~ particles^p
    top = [r for r in rows if r["size"] == hi]
    ratio = top[1]["solve_ms"] / top[0]["solve_ms"]
    line = (f"why Baraff & Witkin used CG, measured: at {hi}x{hi} the sparse LU's solve costs "
            f"{ratio:.1f}x CG's; from {lo}x{lo} to {hi}x{hi} CG's solve grows as particles^"
            f"{growth['cg']:.2f} and the LU's as particles^{growth['direct']:.2f} (its factors "
            f"hold {top[1]['fill'] / top[0]['nonzeros']:.1f}x A's non-zeros, refactored every "
            "step; CG only multiplies by A, stops at 1e-2 and starts from the last step's answer)")
    report.say("  " + line)
    return {"rows": rows, "growth_exponent": growth, "direct_over_cg": ratio, "line": line}


# ----- 4. the window: the slowest settings the sliders accept --------------------------------------
def corner_settings() -> list[dict[str, Any]]:
    """64x64, the stiffest and lightest cloth, each solver at hertz 1, 60 and 1000, shear off
    and on, with the tightest tolerance and the most substeps the step budget accepts."""
    from scenes.mass_spring_cloth import MassSpringClothScene

    def first_accepted(base, key, values):
        for v in values:
            try:
                MassSpringClothScene.resolve({**base, key: v})
                return v
            except ParamError:
                pass
        return None
    out = []
    for solver in ("cg", "direct"):
        for hertz in (1, 60, 1000):
            for shear in (False, True):
                base = {"rows": 64, "cols": 64, "material": "custom", "mass": 0.001, **STIFF,
                        "hertz": hertz, "solver": solver, "shear": shear}
                side = next(k for k in range(64, 1, -1)
                            if first_accepted({**base, "rows": k, "cols": k}, "cg_tolerance",
                                              (0.5,)) is not None)
                base.update(rows=side, cols=side)
                if solver == "cg":
                    base["cg_tolerance"] = first_accepted(
                        base, "cg_tolerance", (1e-10, 1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 1e-1, 0.5))
                base["substeps"] = first_accepted(base, "substeps", range(50, 0, -1))
                out.append(base)
    return out


def window(report: Report, quick: bool) -> dict[str, Any]:
    from scenes.mass_spring_cloth import MassSpringClothScene
    rows = []
    for settings in corner_settings():
        report.progress(f"window: {settings}")
        scene = MassSpringClothScene(settings)
        frame_estimate, step_estimate, _ = frame_cost(scene.p, scene.world_size)
        ms = []
        for _ in range(CORNER_STEPS):
            t0 = time.perf_counter()
            scene.advance()
            ms.append((time.perf_counter() - t0) * 1e3)
        ps, k = scene.cloth.ps, steps_per_frame(settings["hertz"])
        rows.append({"settings": settings, "steps_per_frame": k,
                     "step_estimate_ms": step_estimate * 1e3,
                     "frame_estimate_ms": frame_estimate * 1e3,
                     "median_ms": Timing.of(ms), "max_ms": float(max(ms)),
                     "frame_ms": k * float(np.median(ms)), "first_ms": ms[0],
                     "cg_iterations": ps.cg_iterations, "stopped_short": ps.cg_failures,
                     "stop": ps.solve.stop})
    report.table(f"the window: the slowest settings the sliders accept (stiffness 1e5, mass 0.001, "
                 f"the tightest cg_tolerance, the largest cloth and the most substeps accepted), "
                 f"{CORNER_STEPS} steps from rest; a frame runs hertz/60 steps (at most 8): "
                 f"against the {FRAME_BUDGET_S * 1e3:.0f} ms a frame the window waits",
                 ["size", "solver", "hertz", "shear", "tol", "substeps", "steps/frame",
                  "est. step", "median step", "longest", "frame (median)", "CG its",
                  "stopped short"],
                 [[f"{r['settings']['rows']}x{r['settings']['cols']}", r["settings"]["solver"],
                   r["settings"]["hertz"], "on" if r["settings"]["shear"] else "off",
                   f"{r['settings'].get('cg_tolerance', 0.01):g}", r["settings"]["substeps"],
                   r["steps_per_frame"], f"{r['step_estimate_ms']:.3g}",
                   r["median_ms"], f"{r['max_ms']:.3g}", f"{r['frame_ms']:.3g}",
                   r["cg_iterations"], r["stopped_short"]] for r in rows])
    worst = max(rows, key=lambda r: r["frame_ms"])
    line = (f"the slowest accepted setting measured: {worst['frame_ms']:.0f} ms a frame "
            f"({worst['steps_per_frame']} x {worst['median_ms']:.0f} ms), longest step "
            f"{max(r['max_ms'] for r in rows):.0f} ms (budget {FRAME_BUDGET_S * 1e3:.0f} ms a "
            "frame; the first step of a run builds the matrix's pattern)")
    report.say("  " + line)
    return {"rows": rows, "line": line}


def run(report: Report) -> dict[str, Any]:
    quick = not report.full          # the classroom sizes (32 and 64, the window) with --full
    report.say("\nThe implicit cloth at classroom scale (issue 19)"
               + ("" if report.full else ": small sizes (the classroom's 32x32 and 64x64, and "
                                         "the window's slowest settings, with --full)"))
    out = {"targets": targets(report, quick), "routes": routes(report, quick),
           "solvers": solvers(report, quick)}
    if not quick:
        out["window"] = window(report, quick)
    return out
