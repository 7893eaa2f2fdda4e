"""The mass-spring cloth at its largest: part of `python -m app bench mass_spring`.

Denim (all springs, damping and air on, top row pinned), implicit Euler with conjugate
gradients at 60 Hz (the scene's defaults but the size), 64x64 and 128x128, hung for a few steps
from rest; then steps timed with OpenBLAS's own threads and with BLAS held to one thread
(app/physics/blas_threads.py), interleaved in the same process. What limits a step is read from
the cloth's own stopwatch: the forces and the matrix (set-up) against the CG solve, and the CG
iterations it took. Goal (issue 28): 128x128 at most 33 ms a step.
"""

from __future__ import annotations

import statistics
import time
from app.bench import Report, Timing
from app.physics import blas_threads

GOAL_MS = 33.0
H = 1 / 60


def _cloth(n: int):
    """An n x n denim cloth as bench mass_spring builds it (all springs, damping, air), hung
    for 3 steps."""
    from app.physics.blender_cloth import material_settings
    from app.physics.mass_spring import MassSpringCloth
    c = MassSpringCloth(n, n, 16.0, (100.0, 100.0), "top")
    c.material = material_settings("denim")
    c.on = {"gravity", "air", "damping", "shear", "bending"}
    c.configure()
    for _ in range(3):
        c.step(H, "implicit_euler")
    return c


def _step(c, pinned: bool) -> tuple[float, float, int]:
    """(seconds, seconds in the solve, CG iterations) of one step, BLAS as told (at every size:
    the cloth itself pins only above blas_threads.PIN_ABOVE)."""
    saved = blas_threads.PIN_ABOVE
    blas_threads.PIN_ABOVE = 0 if pinned else 1 << 62
    try:
        before = c.spent.get("solve", 0.0)
        t0 = time.perf_counter()
        c.step(H, "implicit_euler")
        seconds = time.perf_counter() - t0
        return seconds, c.spent["solve"] - before, c.ps.cg_iterations
    finally:
        blas_threads.PIN_ABOVE = saved


def run(report: Report) -> dict:
    sizes = [32, 64] if report.quick else [64, 128]
    steps = 2 if report.quick else 5
    out, rows = [], []
    for n in sizes:
        report.progress(f"mass-spring denim {n}x{n}, CG, BLAS threads")
        c = _cloth(n)
        runs: dict[str, list] = {"one BLAS thread": [], "BLAS's own threads": []}
        for k in range(2 * steps):
            label = list(runs)[k % 2]
            runs[label].append(_step(c, label == "one BLAS thread"))
        entry = {"n": n}
        for label, got in runs.items():
            ms = [g[0] * 1e3 for g in got]
            solve = statistics.median(g[1] for g in got) * 1e3
            its = int(statistics.median(g[2] for g in got))
            med = Timing.of(ms)
            entry[label] = {"ms": med, "spread_ms": max(ms) - min(ms), "solve_ms": solve,
                            "cg_iterations": its}
            rows.append([f"{n}x{n}", label, med, max(ms) - min(ms), solve, med - solve, its,
                         solve / max(its, 1)])
        out.append(entry)
    report.table("Mass-spring denim, implicit Euler + CG, 60 Hz: BLAS threads (ms per step, "
                 "median (interquartile range, steps), its spread (max - min), interleaved)",
                 ["cloth", "BLAS", "step", "spread", "CG solve", "forces + matrix",
                  "CG iterations", "ms per iteration"], rows)
    big = out[-1]
    pinned = big["one BLAS thread"]
    n = big["n"]
    limit = ("the CG solve" if pinned["solve_ms"] > pinned["ms"] - pinned["solve_ms"]
             else "the forces and the matrix")
    own = big["BLAS's own threads"]["ms"]
    report.say(f"{n}x{n} denim with CG: {pinned['ms']:.1f} ms a step with one BLAS thread "
               f"({own:.1f} ms with BLAS's own); goal "
               f"at most {GOAL_MS:g} ms: {'met' if pinned['ms'] <= GOAL_MS else 'NOT met'}; "
               f"{limit} dominates ({pinned['cg_iterations']} CG iterations of "
               f"{pinned['solve_ms'] / max(pinned['cg_iterations'], 1):.2f} ms, "
               f"{2 * n * n} unknowns)")
    return {"goal_ms": GOAL_MS, "sizes": out, "limited_by": limit}
