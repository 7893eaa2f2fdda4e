"""`python -m app bench mass_spring`: Baraff & Witkin's large steps, measured.

Every cloth here is app/physics/mass_spring.MassSpringCloth: an n x n grid (n = 16; 8 with
--quick) of 16 px cells, its top row pinned, gravity, air resistance, spring damping and all
three spring sets on, a material's Blender preset with every stiffness (tension, compression,
shear, bending) multiplied by 1, 10 or 100, the particles nudged by 0.01 px (a seed for the
highest mode, which a perfectly symmetric start would not excite).

1. The large-steps table: for each material and stiffness scale, the largest stable h of each
   explicit integrator, found by bisection. Stable: during HORIZON steps (1000; 150 with
   --quick, symplectic Euler and Verlet only) every particle stays finite, slower than MAX_SPEED and within MAX_DRIFT of its
   start, and the energy's peak in the second half of the run is no higher than in the first
   (by ENERGY_RISE of its size): a hanging cloth loses energy or, undamped (silk's springs), keeps
   it; a peak that grows is a growing mode, even one too slow to reach MAX_SPEED. The horizon was measured: with 150 steps and no energy
   test, leather's "max stable h" blew up at step 430 and denim x100 reached 128,000 px/s; the
   table gives, per row, the step at which the first trial above the limit failed ("seen at"),
   and the horizon must stay well beyond those. Beside it the limit predicted from omega_max and
   the top mode's damping (mass_spring_stability.predicted_limit: the linearised cloth's own for
   symplectic Euler; one mode's (omega_max, c) for the others, an estimate off by up to ~35 %
   where damping mixes the modes) and the margin measured / predicted: above 1 the measurement
   or the prediction is wrong, and the row says so. Forward Euler and midpoint gain energy on
   every undamped mode; where their measured h is 0 no step tried was stable.
2. Cost, counted from the first step: explicit integrators cost the same per step at any h, so
   their wall time per simulated second is the median ms of a step (timed from the first step,
   no warm-up dropped) x the steps per second at the measured h; implicit Euler's is the wall
   time of its first simulated second from rest at h = 1/60 s and 1/30 s (the first steps, while
   the cloth moves, take the most CG iterations: a warm-up batch that left them out reported
   490 ms per simulated second for leather x10, which costs 865), the median of `repeats` runs.
   The ratio table: implicit Euler at 1/60 s against the cheapest explicit integrator at its
   measured limit, per material and stiffness, whichever wins.
3. step_ms: one step of each integrator on the denim cloth (explicit ones at half their limit,
   implicit Euler at 1/60 s).
4. The CG tolerance: iterations, ms and the largest position error a tolerance leaves after one
   implicit step at 1/60 s against a 1e-10 solve, near rest (20 steps into the hang) and moving
   (5 steps in).
5.-8. The implicit cloth at classroom scale (issue 19: the targets, the routes to them, CG
   against the direct solve, the window's slowest accepted settings): app/bench/mass_spring_solve.py.
Timings are medians within one run; another process may load the machine (see the load line).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from app.bench import Report, mass_spring_big, median_time
from app.draw.plot import LineChart, save_grid
from app.physics.integrators import INTEGRATORS
from app.physics.blender_cloth import MATERIALS, material_settings
from app.physics.mass_spring import CG_TOLERANCE, MassSpringCloth
from app.physics.mass_spring_stability import predicted_limit, top_mode

SCALES = (1, 10, 100)
STIFFNESS_KEYS = ("tension", "compression", "shear_stiffness", "bending_stiffness")
EXPLICIT = [name for name, info in INTEGRATORS.items() if info.explicit]
IMPLICIT_STEPS = (1 / 60, 1 / 30)
MAX_DRIFT = 5000.0        # px from the start: a cloth hanging from its top row never goes this far
# px/s. A hanging cloth stays below ~550 px/s in these runs (measured, 16x16, every material at x1
# and x100, h up to 0.97x the limit); past the limit the top mode grows from the 0.01 px nudge
# but often saturates in a shiver of a pixel or two per step at 1500-15000 px/s instead of
# reaching inf: a 2e4 threshold counted that shiver as stable and put the measured limit of
# symplectic Euler 12-16 % above the linear prediction (which the exact spectral radius of the
# linearised step matches within 0.5 % at x1)
MAX_SPEED = 1000.0
HORIZON = 1000            # steps a stable h must survive (150 with --quick): see the docstring
ENERGY_RISE = 1e-2        # growth of the energy's peak from the first half of a run to the second
IMPLICIT_SECONDS = 1.0    # implicit Euler is timed over its first simulated second from rest


def make_cloth(material: str, scale: float, n: int) -> MassSpringCloth:
    """An n x n cloth of `material` with every stiffness x scale, nudged (see the docstring)."""
    c = MassSpringCloth(n, n, 16.0, (100.0, 100.0), "top")
    values = material_settings(material)
    for key in STIFFNESS_KEYS:
        values[key] *= scale
    c.material = values
    c.on = {"gravity", "air", "damping", "shear", "bending"}
    c.configure()
    c.ps.x = c.ps.x + np.random.default_rng(7).normal(0.0, 0.01, c.ps.x.shape) * c.ps.free
    return c


def trial(material: str, scale: float, name: str, h: float, n: int, steps: int) -> int | None:
    """Run `steps` steps of h with `name`; None if the cloth stays stable (see the docstring),
    else the step at which it failed (for an energy that grew: the horizon)."""
    c = make_cloth(material, scale, n)
    x0 = c.ps.x.copy()
    energy = [c.energy()]
    for k in range(steps):
        c.step(h, name)
        if k % 10 == 9 or k == steps - 1:
            if not (c.is_sane() and float(np.abs(c.ps.v).max()) < MAX_SPEED
                    and float(np.abs(c.ps.x - x0).max()) < MAX_DRIFT):
                return k + 1
            energy.append(c.energy())
    half = len(energy) // 2
    size = max(abs(e) for e in energy)
    if max(energy[half:]) > max(energy[:half]) + ENERGY_RISE * size:
        return steps                     # the energy grew: a mode that grows, however slowly
    return None


def survives(material: str, scale: float, name: str, h: float, n: int, steps: int) -> bool:
    """True if `steps` steps of h with `name` leave the cloth stable (see trial)."""
    return trial(material, scale, name, h, n, steps) is None


def largest_stable_h(material: str, scale: float, name: str, guess: float, n: int, steps: int,
                     bisections: int) -> tuple[float, int | None]:
    """Bisection on log h between a stable and an unstable step, starting around `guess` (the
    bracket is lopsided so that no midpoint falls on the guess itself: the test does not peek).
    Returns (the largest stable h found, the step at which the last unstable h failed)."""
    lo, hi = guess / 3.0, guess * 2.5
    failed_at = None
    for _ in range(12):
        failed = trial(material, scale, name, lo, n, steps)
        if failed is None:
            break
        hi, lo, failed_at = lo, lo / 4.0, failed
    else:
        return 0.0, failed_at
    while (failed := trial(material, scale, name, hi, n, steps)) is None:
        lo, hi = hi, hi * 2.0
    failed_at = failed
    for _ in range(bisections):
        mid = math.sqrt(lo * hi)
        failed = trial(material, scale, name, mid, n, steps)
        if failed is None:
            lo = mid
        else:
            hi, failed_at = mid, failed
    return lo, failed_at


def step_seconds(c: MassSpringCloth, name: str, h: float, number: int, repeats: int) -> float:
    """Median wall seconds of one step, timed over `number` steps from the first (no warm-up)."""
    def batch() -> None:
        for _ in range(number):
            c.step(h, name)
    return median_time(batch, repeats=repeats, warmup=0) / number


def implicit_seconds(material: str, scale: float, h: float, n: int, repeats: int
                     ) -> tuple[float, int]:
    """Median wall seconds of implicit Euler's first IMPLICIT_SECONDS from rest (every step
    counted), and the CG iterations of its first step."""
    times, first = [], 0
    for _ in range(repeats):
        c = make_cloth(material, scale, n)
        t0 = time.perf_counter()
        for k in range(round(IMPLICIT_SECONDS / h)):
            c.step(h, "implicit_euler")
            if k == 0:
                first = c.ps.cg_iterations
        times.append(time.perf_counter() - t0)
    from app.bench import Timing
    return Timing.of(times), first       # the median, its spread and repeats


def _num(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def run(report: Report) -> dict[str, Any]:
    quick, full = report.quick, report.full
    n = 8 if quick else 16
    # by default the stiffest and the softest preset at x1 and x10 (the whole sweep, every
    # material at x1, x10, x100, behind --full: 6.5 min idle, 20 min on a busy machine)
    materials = ["leather"] if quick else list(MATERIALS) if full else ["leather", "cotton"]
    scales = (1, 100) if quick else SCALES if full else (1, 10)
    steps, bisections = (150, 3) if quick else (HORIZON, 6 if full else 4)
    explicit = ["symplectic_euler", "verlet"] if quick else EXPLICIT
    number, repeats = (20, 1) if quick else (100, 5)
    report.say(f"Large steps: {n}x{n} cloth, top row pinned, all springs, damping and air on; "
               f"stable = {steps} steps without blowing up or gaining energy; ms per simulated "
               f"second counted from the first step.")
    rows, table = [], []
    explicit_ms: dict[tuple[str, str], float] = {}
    big = mass_spring_big.run(report)     # 128x128 denim with CG, BLAS threads (issue 28)
    for material in materials:
        for scale in scales:
            probe = make_cloth(material, scale, n)
            omega, damping, _ = top_mode(probe.ps, 200)
            se_pred = predicted_limit("symplectic_euler", omega, damping)
            for name in explicit:
                report.progress(f"{material} x{scale}: {name}")
                pred = predicted_limit(name, omega, damping)
                h, seen = largest_stable_h(material, scale, name, pred or se_pred, n, steps,
                                           bisections)
                if (material, name) not in explicit_ms:    # the same at every h and stiffness
                    explicit_ms[material, name] = step_seconds(
                        make_cloth(material, scale, n), name, 0.5 * (h or se_pred), number,
                        repeats) * 1e3
                ms = explicit_ms[material, name] / h if h > 0 else math.inf
                margin = h / pred if pred and h > 0 else None
                rows.append({"material": material, "stiffness_scale": scale, "integrator": name,
                             "h": _num(h), "max_stable_h": _num(h), "predicted_h": _num(pred),
                             "margin": _num(margin), "above_prediction": bool(margin and
                                                                            margin > 1.0),
                             "unstable_seen_at_step": seen, "horizon_steps": steps,
                             "ms_per_sim_second": _num(ms), "omega_max": omega,
                             "cg_iterations": 0})
            for h in IMPLICIT_STEPS:
                report.progress(f"{material} x{scale}: implicit_euler at 1/{round(1 / h)} s")
                sec, first = implicit_seconds(material, scale, h, n, repeats)
                rows.append({"material": material, "stiffness_scale": scale,
                             "integrator": "implicit_euler", "h": h, "max_stable_h": None,
                             "predicted_h": None, "margin": None, "above_prediction": False,
                             "unstable_seen_at_step": None, "horizon_steps": None,
                             "ms_per_sim_second": sec * 1e3 / IMPLICIT_SECONDS,
                             "omega_max": omega, "cg_iterations": first})
    for r in rows:
        margin = "-" if r["margin"] is None else (f"{r['margin']:.2f}"
                                                  + (" ABOVE" if r["above_prediction"] else ""))
        table.append([r["material"], f"x{r['stiffness_scale']}", r["integrator"],
                      "-" if r["max_stable_h"] is None else f"{r['max_stable_h'] * 1e3:.4g}",
                      "-" if r["predicted_h"] is None else f"{r['predicted_h'] * 1e3:.4g}",
                      margin, "-" if r["unstable_seen_at_step"] is None
                      else r["unstable_seen_at_step"],
                      f"{r['h'] * 1e3:.4g}" if r["h"] else "-",
                      "inf" if r["ms_per_sim_second"] is None else f"{r['ms_per_sim_second']:.4g}",
                      r["cg_iterations"]])
    report.table(f"large steps: largest stable h (ms) over {steps} steps, measured vs predicted; "
                 "the step at which the first h above it failed; wall ms per simulated second",
                 ["material", "stiffness", "integrator", "max h", "predicted", "margin",
                  "seen at", "h used", "ms per sim s", "CG its (1st)"], table)
    seen = [r["unstable_seen_at_step"] for r in rows if r["unstable_seen_at_step"]]
    if seen:
        report.say(f"  growth above the limit showed by step {max(seen)} at the latest "
                   f"(median {int(np.median(seen))}); horizon {steps} steps")

    ratios = implicit_ratios(rows, materials, scales)
    report.table("implicit Euler at 1/60 s vs the cheapest explicit integrator at its measured "
                 "limit (ms per simulated second; ratio > 1: implicit is cheaper)",
                 ["material", "stiffness", "cheapest explicit", "its ms/s", "implicit ms/s",
                  "ratio"],
                 [[q["material"], f"x{q['stiffness_scale']}", q["explicit"],
                   f"{q['explicit_ms']:.4g}", f"{q['implicit_ms']:.4g}", f"{q['ratio']:.3g}"]
                  for q in ratios])

    verdicts = _verdicts(rows, materials, scales)
    for line in verdicts["lines"]:
        report.say("  " + line)

    # step_ms on the denim cloth
    step_ms: dict[str, float] = {}
    base = make_cloth("denim", 1, n)
    omega, damping, _ = top_mode(base.ps, 200)
    for name in INTEGRATORS:
        pred = predicted_limit(name, omega, damping)
        h = 1 / 60 if name == "implicit_euler" else 0.5 * (pred or predicted_limit(
            "symplectic_euler", omega, damping))
        step_ms[name] = step_seconds(make_cloth("denim", 1, n), name, h, number, repeats) * 1e3
    report.table(f"one step, {n}x{n} denim (explicit at half its limit, implicit Euler at 1/60 s)",
                 ["integrator", "ms/step"], [[k, v] for k, v in step_ms.items()])

    tolerance = cg_tolerance_table(n, quick)
    report.table("CG tolerance: one implicit step at 1/60 s vs a 1e-10 solve "
                 f"(the scene uses {CG_TOLERANCE:g})",
                 ["material", "state", "tolerance", "iterations", "ms",
                  "max position error px"],
                 [[t["material"], t["state"], f"{t['tolerance']:g}", t["iterations"], t["ms"],
                   f"{t['max_error_px']:.2g}"] for t in tolerance])

    charts = []
    for material in materials:
        chart = LineChart(f"{material}: wall ms per simulated second", "stiffness scale",
                          "ms per simulated second", logx=True, logy=True)
        for name in EXPLICIT + ["implicit_euler"]:
            for h in (IMPLICIT_STEPS if name == "implicit_euler" else (None,)):
                pts = [r for r in rows if r["material"] == material and r["integrator"] == name
                       and (h is None or r["h"] == h) and r["ms_per_sim_second"] is not None]
                label = name if h is None else f"{name} h=1/{round(1 / h)}"
                chart.add(label, [r["stiffness_scale"] for r in pts],
                          [r["ms_per_sim_second"] for r in pts])
        charts.append(chart)
    path = save_grid(charts, report.chart_path("mass_spring_large_steps.png"), cols=2,
                     cell=(760, 470))
    from app.bench import mass_spring_solve
    classroom = mass_spring_solve.run(report)        # issue 19: targets, routes, solvers, window
    return {"largest": big, "large_steps": rows, "implicit_vs_explicit": ratios, "step_ms": step_ms,
            "cg_tolerance": tolerance, "verdicts": verdicts, "charts": [path], "grid": n,
            "steps_per_trial": steps, **classroom}


def implicit_ratios(rows: list[dict], materials: list[str], scales) -> list[dict[str, Any]]:
    """Per material and stiffness: implicit Euler at 1/60 s against the cheapest explicit
    integrator at its measured limit, as measured (a ratio below 1: explicit wins)."""
    out = []
    for material in materials:
        for scale in scales:
            at = [r for r in rows if r["material"] == material and r["stiffness_scale"] == scale]
            explicit = [r for r in at if r["integrator"] != "implicit_euler"
                        and r["ms_per_sim_second"] is not None]
            implicit = next(r for r in at if r["integrator"] == "implicit_euler"
                            and r["h"] == 1 / 60)
            if not explicit:
                continue
            best = min(explicit, key=lambda r: r["ms_per_sim_second"])
            out.append({"material": material, "stiffness_scale": scale,
                        "explicit": best["integrator"], "explicit_h": best["h"],
                        "explicit_ms": best["ms_per_sim_second"],
                        "implicit_ms": implicit["ms_per_sim_second"],
                        "ratio": best["ms_per_sim_second"] / implicit["ms_per_sim_second"]})
    return out


def _verdicts(rows: list[dict], materials: list[str], scales) -> dict[str, Any]:
    """The issue's two questions, answered from the table (honestly, whatever the numbers)."""
    stiffest = max(materials, key=lambda m: MATERIALS[m].tension)
    top = max(scales)
    at = [r for r in rows if r["material"] == stiffest and r["stiffness_scale"] == top]
    explicit = [r for r in at if r["integrator"] != "implicit_euler"
                and r["ms_per_sim_second"] is not None]
    cheapest = min(explicit, key=lambda r: r["ms_per_sim_second"])
    implicit = next(r for r in at if r["integrator"] == "implicit_euler" and r["h"] == 1 / 60)
    ratio = cheapest["ms_per_sim_second"] / implicit["ms_per_sim_second"]
    se = [r for r in rows if r["integrator"] == "symplectic_euler" and r["predicted_h"]
          and r["max_stable_h"]]
    errors = [abs(r["max_stable_h"] / r["predicted_h"] - 1.0) for r in se]
    worst = max(errors) if errors else None
    above = [f"{r['material']} x{r['stiffness_scale']} {r['integrator']} ({r['margin']:.2f}x)"
             for r in rows if r.get("above_prediction")]
    lines = [
        "measured limit above the linear prediction: "
        + (", ".join(above) + " (one-mode estimates; symplectic Euler's must never be)"
           if above else "nowhere"),
        f"{stiffest} x{top}: implicit Euler at 1/60 s takes {implicit['ms_per_sim_second']:.4g} "
        f"ms per simulated second, the cheapest explicit ({cheapest['integrator']} at h = "
        f"{cheapest['h'] * 1e3:.3g} ms) {cheapest['ms_per_sim_second']:.4g} ms: implicit is "
        f"{ratio:.3g}x cheaper ({'meets' if ratio >= 10 else 'misses'} the 10x target)",
        "symplectic Euler: measured limit vs predicted, worst deviation "
        + ("-" if worst is None else
           f"{worst * 100:.1f}% ({'within' if worst <= 0.1 else 'outside'} the 10% target)"),
    ]
    return {"stiffest": stiffest, "implicit_vs_cheapest_explicit": ratio, "above_prediction": above,
            "cheapest_explicit": cheapest["integrator"], "symplectic_worst_deviation": worst,
            "lines": lines}


def cg_tolerance_table(n: int, quick: bool) -> list[dict[str, Any]]:
    """What each CG tolerance leaves: one implicit step at 1/60 s from a state 5 steps (moving)
    and 20 steps (near rest) into a hang, against the same step solved to 1e-10."""
    out = []
    for material in (["denim"] if quick else ["denim", "leather", "silk"]):
        for into in (5, 20):
            c = make_cloth(material, 1, n)
            for _ in range(into):
                c.step(1 / 60, "implicit_euler")
            start = c.copy_state()
            results = {}
            for tol in (1e-10, 1e-1, 1e-2, 1e-3, 1e-4):
                c.restore_state(start)
                c.ps.cg_tolerance = tol
                t0 = time.perf_counter()
                c.step(1 / 60, "implicit_euler")
                results[tol] = (c.ps.x.copy(), c.ps.cg_iterations,
                                (time.perf_counter() - t0) * 1e3)
            ref = results[1e-10][0]
            for tol, (x, its, ms) in results.items():
                if tol != 1e-10:
                    out.append({"material": material, "state": f"{into} steps in",
                                "tolerance": tol, "iterations": its, "ms": ms,
                                "max_error_px": float(np.abs(x - ref).max())})
    return out
