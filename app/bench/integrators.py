"""`python -m app bench integrators`: what accuracy costs, integrator by integrator.

For each test problem (mass on a spring, pendulum, two-body orbit, and a ball bouncing on a floor;
app/physics/problems.py) and each integrator it sweeps the step h (halving omega*h), runs to the
problem's time T and records
the relative phase-space error at T, the derivative evaluations used (implicit Euler: plus its
Jacobian-vector products, each about as costly as one evaluation) and the wall time (steps x the
median microseconds per step, timed over a batch of steps). It then reports

  * work-precision charts, one slide each with the four problems side by side: error against
    wall time (integrators_work_precision.png), against derivative evaluations
    (integrators_error_vs_evals.png) and against omega*h (integrators_order.png, where the slope
    is the order), and the same numbers as tables;
  * the measured order of convergence (slope of log error against log h over the smallest steps;
    on bounce over its whole sweep, the error averaged over where the contact falls in a step)
    beside the theoretical one: on bounce every order falls to about 1;
  * the measured stability limit in omega*h on the undamped oscillator (bisection with a growth
    criterion) beside the theoretical one;
  * which integrator reaches a relative error of 1e-3 and 1e-6 in the least time.

Timings are medians, but another process may load the machine: compare them within one run
(the report prints the load average when it starts).
"""

from __future__ import annotations

import math
import time
from typing import Any


from app.bench import Report, median_time
from app.draw.palette import INTEGRATOR_COLORS as COLORS
from app.draw.plot import LineChart, save_grid
from app.physics.integrators import INTEGRATORS
from app.physics.problems import (PROBLEMS, error_at, fitted_order, make_problem, stability_limit,
                                  sweep_steps)

TARGETS = (1e-3, 1e-6)
# Sweep of omega*h per order: (largest, halvings). Low orders need small steps to show their slope.
SWEEP = {1: (0.4, 8), 2: (0.4, 7), 4: (0.8, 6)}
QUICK_SWEEP = {1: (0.4, 3), 2: (0.4, 3), 4: (0.8, 3)}


def _time_per_step(problem, name: str, h: float, quick: bool) -> float:
    """Median seconds per step, timed over a batch of steps on a fresh system."""
    ps, step = problem.make_system(), INTEGRATORS[name].step
    batch = 10 if quick else 40

    def steps() -> None:
        for _ in range(batch):
            step(ps, h)
    return median_time(steps, repeats=3 if quick else 5, warmup=1) / batch


def sweep(problem, name: str, quick: bool) -> list[dict[str, float]]:
    """One point per step size: omega*h, steps, evaluations, us/step, wall ms, error at T."""
    T = problem.horizon
    top, halvings = (QUICK_SWEEP if quick else SWEEP)[INTEGRATORS[name].order]
    if problem.sweep is not None:                 # bounce: one sweep for every integrator
        top, halvings = problem.sweep[0], problem.sweep[1] - (3 if quick else 0)
    points = []
    for steps in sweep_steps(problem, top, halvings):
        h = T / steps
        error, evals = error_at(problem, name, T, steps)
        us = _time_per_step(problem, name, h, quick) * 1e6
        points.append({"omega_dt": problem.omega * h, "steps": steps, "evals": evals,
                       "us_per_step": us, "error": error})
    # A step costs the same at every h for these small systems: one median over all the batch
    # medians is the least noisy figure on a busy machine.
    from app.bench import Timing
    us = Timing.of([p["us_per_step"] for p in points])     # its spread: over the batches
    for p in points:
        p["us_per_step"], p["wall_ms"] = us, p["steps"] * us / 1000.0
    return points


def measured_order(points: list[dict[str, float]], whole: bool = False) -> float | None:
    """The order over the sweep's asymptotic range (problems.fitted_order), or over the whole
    sweep (whole: bounce, whose error is not a smooth power of h at any step)."""
    return fitted_order([p["omega_dt"] for p in points], [p["error"] for p in points],
                        asymptotic=not whole)


def time_to_reach(points: list[dict[str, float]], target: float, order: float
                  ) -> tuple[float, bool]:
    """Wall ms needed for error <= target: interpolated in log-log between the sweep points that
    bracket it, or extrapolated (flag True) from the smallest step with error ~ h^order."""
    errors = [p["error"] for p in points]
    j = len(points)
    while j > 0 and errors[j - 1] <= target:      # first index from which all errors stay <= target
        j -= 1
    if j == 0:
        return points[0]["wall_ms"], False         # already reached at the largest step
    if j < len(points):
        a, b = points[j - 1], points[j]
        if math.isfinite(a["error"]) and a["error"] > 0 and b["error"] > 0:
            s = math.log(target / a["error"]) / math.log(b["error"] / a["error"])
            return math.exp(math.log(a["wall_ms"]) + s * math.log(b["wall_ms"] / a["wall_ms"])), False
        return b["wall_ms"], False
    last = points[-1]
    if not (math.isfinite(last["error"]) and last["error"] > 0):
        return math.inf, True
    return last["wall_ms"] * (last["error"] / target) ** (1.0 / order), True


def _json_number(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def run(report: Report) -> dict[str, Any]:
    quick = report.quick
    report.say("Work-precision of the six integrators (compare timings within this run only).")
    results: dict[str, Any] = {"problems": {}, "order": {}, "stability": {}, "fastest": {}}
    charts: dict[str, list[LineChart]] = {"wall_ms": [], "evals": [], "omega_dt": []}
    total = len(PROBLEMS) * len(INTEGRATORS)
    done = 0
    for pname in PROBLEMS:
        problem = make_problem(pname)
        T = problem.horizon
        per: dict[str, Any] = {}
        error = f"relative error at T = {T:g} s"
        panel = problem.title[0].upper() + problem.title[1:]
        by_wall = LineChart(panel, "wall time (ms)", error, logx=True, logy=True)
        by_evals = LineChart(panel, "derivative evaluations", error, logx=True, logy=True)
        by_step = LineChart(panel, "omega*dt (no unit)", error,
                            logx=True, logy=True)
        rows = []
        for name, info in INTEGRATORS.items():
            done += 1
            report.progress(f"[{done}/{total}] {pname}: {name}")
            t0 = time.perf_counter()
            points = sweep(problem, name, quick)
            order = measured_order(points, whole=problem.sweep is not None)
            per[name] = {"points": [{k: _json_number(v) for k, v in p.items()} for p in points],
                         "order_measured": order, "order_theory": info.order,
                         "seconds": time.perf_counter() - t0}
            shown = [p for p in points if math.isfinite(p["error"]) and p["error"] > 0]
            for chart, key in ((by_wall, "wall_ms"), (by_evals, "evals"), (by_step, "omega_dt")):
                chart.add(info.title, [p[key] for p in shown], [p["error"] for p in shown],
                          color=COLORS[name])
            for p in points:
                rows.append([name, p["omega_dt"], p["steps"], p["evals"], p["us_per_step"],
                             p["wall_ms"], p["error"]])
        report.table(f"work-precision: {problem.title}, error at T = {T:g} s",
                     ["integrator", "omega*dt", "steps", "evals", "us/step", "wall ms", "error"], rows)
        for key, chart in (("wall_ms", by_wall), ("evals", by_evals), ("omega_dt", by_step)):
            charts[key].append(chart)
        results["problems"][pname] = per

        fastest = {}
        for target in TARGETS:
            times = {}
            for name, info in INTEGRATORS.items():
                order = per[name]["order_measured"] or info.order
                ms, extrapolated = time_to_reach(
                    [p for p in per[name]["points"] if p["error"] is not None] or
                    [{"wall_ms": math.inf, "error": math.inf}], target, max(order, 0.5))
                times[name] = (ms, extrapolated)
            winner = min(times, key=lambda n: times[n][0])
            fastest[f"{target:g}"] = {"winner": winner,
                                      "ms": {n: _json_number(ms) for n, (ms, _) in times.items()},
                                      "extrapolated": [n for n, (_, x) in times.items() if x]}
        results["fastest"][pname] = fastest

    report.table("order of convergence: measured (slope over the smallest steps) vs theory",
                 ["integrator", "theory"] + list(PROBLEMS),
                 [[name, info.order] + [_fmt_order(results["problems"][p][name]["order_measured"])
                                        for p in PROBLEMS]
                  for name, info in INTEGRATORS.items()])
    report.say("  ('-': the error never fell below 0.1 in the sweep, so no asymptotic slope; the "
               "orbit's close passes need far smaller steps from the first-order methods)")
    report.say("  bounce: the floor's force jumps at touch-down; the step that straddles it makes an "
               "O(h) error whatever the method, so every order falls to about 1 (measured over "
               "the whole sweep, the error averaged over 8 start times within a step).")
    report.say("  Verlet: local position error O(h^4) per step, global error O(h^2) after a fixed "
               "time (T/h steps add up); the slides' \"4th order accurate\" counts the local "
               "error, and the measured order above (2) contradicts it as a global order.")
    results["order"] = {name: {p: results["problems"][p][name]["order_measured"] for p in PROBLEMS}
                        | {"theory": info.order} for name, info in INTEGRATORS.items()}

    stab_rows = []
    for name, info in INTEGRATORS.items():
        report.progress(f"stability limit: {name}")
        limit = stability_limit(name, steps=400 if quick else 1000, rel_tol=2e-2 if quick else 2e-3)
        results["stability"][name] = {"measured": _json_number(limit) if limit > 0 else 0.0,
                                      "theory": _json_number(info.stability_limit),
                                      "measured_text": _fmt_limit(limit),
                                      "theory_text": _fmt_limit(info.stability_limit)}
        stab_rows.append([name, _fmt_limit(info.stability_limit), _fmt_limit(limit), info.note])
    report.table("stability limit in omega*dt, undamped oscillator (growth over many steps)",
                 ["integrator", "theory", "measured", "note"], stab_rows)
    report.say("  (measured 'none': the energy already grows at omega*dt = 0.1, the smallest tested; "
               "'unconditional': still bounded at 20, the largest tested)")

    fast_rows = []
    for pname, by_target in results["fastest"].items():
        for target, entry in by_target.items():
            ms = entry["ms"]
            fast_rows.append([pname, target, entry["winner"]] + [
                ("~" if n in entry["extrapolated"] else "") + (f"{ms[n]:.3g}" if ms[n] else "inf")
                for n in INTEGRATORS])
    report.table("wall ms to reach a relative error (~ = extrapolated beyond the sweep)",
                 ["problem", "error", "fastest"] + list(INTEGRATORS), fast_rows)

    results["charts"] = [
        save_grid(charts[key], report.chart_path(name), cols=2, title=title)
        for key, name, title in (
            ("wall_ms", "integrators_work_precision.png",
             "Work-precision: the error each integrator reaches for the wall time it takes"),
            ("evals", "integrators_error_vs_evals.png",
             "The error each integrator reaches for the derivative evaluations it makes"),
            ("omega_dt", "integrators_order.png",
             "Error against step size: the slope is the order (1, 2 or 4; on bounce about 1 for all)"))]
    return results


def _fmt_order(order: float | None) -> str:
    return "-" if order is None else f"{order:.2f}"


def _fmt_limit(limit: float) -> str:
    if limit == 0:
        return "none"
    if math.isinf(limit):
        return "unconditional"
    return f"{limit:.3f}"
