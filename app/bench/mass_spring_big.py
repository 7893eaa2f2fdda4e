"""The mass-spring cloth at its largest: part of `python -m app bench mass_spring`.

Denim (all springs, damping and air on, top row pinned), implicit Euler with conjugate
gradients at 60 Hz (the scene's defaults but the size), 64x64 and 128x128, hung for a few steps
from rest; then STEPS steps timed with OpenBLAS's own threads and STEPS with BLAS held to one thread
(app/physics/blas_threads.py), interleaved in the same process. The goal's figure is the CPU time of the stepping
thread with BLAS held to one thread (time.thread_time: the median, its interquartile range and
its spread): the wall clock counts other programs' turns on a busy machine, and the process's
CPU time counts BLAS's idle threads, which spin for a while after the steps with threads used
them (so the steps are interleaved in blocks of STEPS / 3, alternating which goes first) (measured: 23-30 ms a 128x128 step pinned, alone, process CPU = thread CPU;
interleaved, the process's CPU time read about twice the thread's). Beside it: all threads'
CPU time and the wall clock, and with BLAS's own threads the same three. What limits a step is read from
the cloth's own stopwatch: the forces and the matrix (set-up) against the CG solve, and the CG
iterations it took. Goal (issue 28): 128x128 at most 33 ms a step.
"""

from __future__ import annotations

import statistics
import time
from app.bench import Report, Timing, load_average
from app.physics import blas_threads

GOAL_MS = 33.0
H = 1 / 60
STEPS = 15          # steps timed with each BLAS setting (5 gave 27-39 ms at 128x128, loaded)


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


def _step(c, pinned: bool) -> tuple[float, float, float, float, int]:
    """(CPU seconds of this thread, CPU seconds of the process, wall seconds, this thread's CPU
    seconds in the solve, CG iterations) of one step, BLAS as told (at every size: the cloth
    itself pins only above blas_threads.PIN_ABOVE)."""
    saved = blas_threads.PIN_ABOVE
    blas_threads.PIN_ABOVE = 0 if pinned else 1 << 62
    c.watch.clock = time.thread_time              # the cloth's own split, in CPU time too
    try:
        before = c.spent.get("solve", 0.0)
        t0, p0, w0 = time.thread_time(), time.process_time(), time.perf_counter()
        c.step(H, "implicit_euler")
        t1, p1, w1 = time.thread_time(), time.process_time(), time.perf_counter()
        return t1 - t0, p1 - p0, w1 - w0, c.spent["solve"] - before, c.ps.cg_iterations
    finally:
        blas_threads.PIN_ABOVE = saved


def run(report: Report) -> dict:
    sizes = [32, 64] if report.quick else [64, 128]
    steps = 2 if report.quick else STEPS
    out, rows = [], []
    for n in sizes:
        report.progress(f"mass-spring denim {n}x{n}, CG, BLAS threads ({2 * steps} steps)")
        c = _cloth(n)
        runs: dict[str, list] = {"one BLAS thread": [], "BLAS's own threads": []}
        block = max(1, steps // 3)            # blocks of steps, alternating which goes first
        for b in range(0, steps, block):
            order = list(runs) if (b // block) % 2 == 0 else list(runs)[::-1]
            for label in order:
                for _ in range(min(block, steps - b)):
                    runs[label].append(_step(c, label == "one BLAS thread"))
        entry = {"n": n, "load": load_average()}
        for label, got in runs.items():
            ms = [g[0] * 1e3 for g in got]
            solve = statistics.median(g[3] for g in got) * 1e3
            its = int(statistics.median(g[4] for g in got))
            med = Timing.of(ms)
            every, wall = Timing.of([g[1] * 1e3 for g in got]), Timing.of([g[2] * 1e3 for g in got])
            entry[label] = {"ms": med, "spread_ms": max(ms) - min(ms), "process_ms": every,
                            "wall_ms": wall, "solve_ms": solve, "cg_iterations": its,
                            "steps": len(ms)}
            rows.append([f"{n}x{n}", label, med, max(ms) - min(ms), every, wall, solve,
                         med - solve, its, solve / max(its, 1), f"{entry['load']:.2f}"])
        out.append(entry)
    report.table("Mass-spring denim, implicit Euler + CG, 60 Hz: BLAS threads (ms per step, "
                 "median (interquartile range, steps), in interleaved blocks of steps, from rest: CPU "
                 "time of the stepping thread and its spread (max - min), CPU time of every "
                 "thread, wall time; the split into CG and the rest: the stepping thread's CPU)",
                 ["cloth", "BLAS", "step (CPU)", "spread", "CPU, all threads", "wall",
                  "CG solve", "forces + matrix", "CG iterations", "ms per iteration", "load"],
                 rows)
    big = out[-1]
    pinned = big["one BLAS thread"]
    n = big["n"]
    limit = ("the CG solve" if pinned["solve_ms"] > pinned["ms"] - pinned["solve_ms"]
             else "the forces and the matrix")
    own = big["BLAS's own threads"]
    report.say(f"{n}x{n} denim with CG: {pinned['ms']:.1f} ms of CPU a step with one BLAS thread "
               f"(median of {pinned['steps']}, spread {pinned['spread_ms']:.1f} ms; wall "
               f"{pinned['wall_ms']:.1f} ms; with BLAS's own threads {own['wall_ms']:.1f} ms wall, "
               f"{own['process_ms']:.1f} ms of CPU in all threads; load {big['load']:.2f}); goal "
               f"at most {GOAL_MS:g} ms: {'met' if pinned['ms'] <= GOAL_MS else 'NOT met'}; "
               f"{limit} dominates ({pinned['cg_iterations']} CG iterations of "
               f"{pinned['solve_ms'] / max(pinned['cg_iterations'], 1):.2f} ms, "
               f"{2 * n * n} unknowns; forces and matrix "
               f"{pinned['ms'] - pinned['solve_ms']:.1f} ms). (The stepping thread's CPU time: "
               f"BLAS's threads, which spin a while after their last use, add their time to the "
               f"process's even in the steps pinned to one thread.)")
    return {"goal_ms": GOAL_MS, "sizes": out, "limited_by": limit}


