"""`python -m app bench particles`: what finding the pairs costs (all pairs against a grid), what
drawing the dots costs, and the particle dance's targets at 5,000 particles.

The particle dance (app/physics/particle_dance.py) at its scene's default rule (3 species, random
rule matrix from seed 0, cut-off 40 px, k_att 300, k_rep 1000 px/s^2, drag 1/s, walls) in the
scene's 960 x 720 box. For each n one state is made (n particles spread at random, then 120
steps (2 s) with the grid, 5 with --quick, so clusters have formed) and both neighbour methods
step copies of that same state, taking turns (a burst of load from another process hits both):

1. ms per step (median; search + forces + drag + walls) and pair tests per step, n = 100 ..
   5000: all pairs makes n (n - 1) / 2 tests, the grid about n x (the particles in 4.5 cells).
   The box is fixed, so the density grows with n and both counts grow like n^2 (the grid's from
   ~1/50 of all pairs): slope 2 on the chart's log axes;
2. the n where the grid starts to win (interpolated, log-log);
3. crowds: the particles gathered into disks of shrinking radius down to every particle at one
   point (and all 5,000 at one point with --full), and the grid's worst case (four tight clusters in four neighbouring cells: it tests
   every pair, a quarter of them interact), the grid against all pairs: the grid tests fewer
   pairs or, at worst, every pair, and its time stays below all pairs' (which is why the grid
   has no fallback to all pairs);
4. drawing 5,000 dots on 1280 x 800 with pygame's options side by side: a circle call per
   particle, a sprite per species with per-pixel alpha, a colour-keyed sprite per species (the
   one app/draw/dance_draw.py uses), stamping disks into the pixels with NumPy (surfarray);
5. the step budget: the costliest settings the scene accepts (most substeps at 5,000 particles,
   each method; the widest cut-off) stepped for real against the window's 100 ms, beside the
   scene's own estimate; and (with --full: about a minute) the densest crowd the sliders allow:
   the strongest, widest mouse held for 3 s on 5,000 particles;
6. one frame at 5,000 particles (grid): a step plus drawing every particle at 1280 x 800.

Last, the targets of issue 19 with the figures beside them: the grid at 5,000 particles <= 8 ms a
step and >= 10x cheaper than all pairs, drawing 5,000 dots <= 4 ms, the grid no slower than all
pairs with every particle at one point, the costliest accepted settings <= 100 ms a step; where
a target is missed, the measured reason.
"""

from __future__ import annotations

import copy
import math
import os
import time
from typing import Callable

import numpy as np
import pygame

from app.bench import Report, Timing, median_time
from app.draw.dance_draw import DRAWERS, USED as DRAWER_USED
from app.draw.plot import LineChart, save_grid
from app.draw.view import View
from app.physics.neighbours import NEIGHBOUR_METHODS, all_pair_tests
from app.physics.particle_dance import EFFECTS, PairForce, PairRule, ParticleDance, rule_matrix

BOX = (960.0, 720.0)          # the scene's world
SPECIES = 3
H = 1.0 / 60.0
SIZES = [100, 200, 500, 1000, 2000, 3000, 5000]
QUICK_SIZES = [100, 300, 1000]
TARGET_N = 5000
DOT_RADIUS = 3.5
SCREEN = (1280, 800)
CROWD_RADII = [400.0, 200.0, 120.0, 80.0, 40.0, 20.0, 2.0]
GOALS = {"grid_ms": 8.0, "ratio": 10.0, "draw_ms": 4.0, "crowd_ratio": 1.0, "budget_ms": 100.0}


def default_rule() -> PairRule:
    """The scene's default rule: 3 species, random matrix from seed 0, R 40, k_att 300, k_rep 1000."""
    return PairRule(rule_matrix("random", SPECIES, np.random.default_rng([0, 1])), 40.0, 300.0,
                    1000.0)


def make_dance(n: int, method: str, settle: int) -> ParticleDance:
    """n particles with the scene's default rule, after `settle` steps (grid) from seed 0."""
    dance = ParticleDance(n, SPECIES, BOX, default_rule(), np.random.default_rng(0), set(EFFECTS),
                          1.0, "grid")
    for _ in range(settle):
        dance.step(H)
    dance.pair_force.method = method
    return dance


def alternating(fns: dict[str, Callable[[], None]], repeats: int, number: int) -> dict[str, float]:
    """Median ms (a Timing: with its spread and repeats) of `number` calls of each fn, the fns taking turns repeat by repeat. Each timed
    batch follows one untimed call of the same fn: right after the other method's step (all
    pairs churns through megabytes) the first grid step ran up to 3x slower than the next."""
    times: dict[str, list[float]] = {name: [] for name in fns}
    for _ in range(repeats):
        for name, fn in fns.items():
            fn()
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            times[name].append((time.perf_counter() - t0) / number * 1000.0)
    return {name: Timing.of(t) for name, t in times.items()}


def crossover(ns: list[int], all_ms: list[float], grid_ms: list[float]) -> float | None:
    """The n from which the grid is faster for every larger size in the sweep: where
    log(all / grid) crosses 0, interpolated linearly in log n; None if the grid never wins
    (n[0] if it always does)."""
    ratio = [math.log(a / g) for a, g in zip(all_ms, grid_ms)]
    if ratio[-1] <= 0:
        return None
    k = len(ratio) - 1
    while k > 0 and ratio[k - 1] > 0:
        k -= 1
    if k == 0:
        return float(ns[0])
    r0, r1 = ratio[k - 1], ratio[k]
    t = r0 / (r0 - r1)
    return math.exp(math.log(ns[k - 1]) + t * (math.log(ns[k]) - math.log(ns[k - 1])))


def load_note() -> str:
    """'load 2.4 on 2 cores' (the load average over the last minute), for the reasons."""
    try:
        return f"load {os.getloadavg()[0]:.1f} on {os.cpu_count() or 1} cores"
    except (AttributeError, OSError):
        return "load unknown"


def grid_breakdown(dance: ParticleDance, steps: int) -> dict:
    """ms per step of the grid's search, its forces and the rest (drag, walls, the integrator),
    over `steps` steps of `dance` (means: the parts add up to the whole)."""
    pf = dance.pair_force
    search0, inter0 = pf.search_seconds, dance.spent["interaction"]
    t0 = time.perf_counter()
    for _ in range(steps):
        dance.step(H)
    total = (time.perf_counter() - t0) / steps * 1000.0
    search = (pf.search_seconds - search0) / steps * 1000.0
    forces = (dance.spent["interaction"] - inter0) / steps * 1000.0 - search
    return {"step_ms": total, "search_ms": search, "forces_ms": forces,
            "rest_ms": total - search - forces, "tests": pf.tests, "pairs": pf.pairs}


def scaling(report: Report, sizes: list[int], settle: int) -> tuple[list[dict], dict]:
    """Section 1: ms per step and pair tests, n x method, on the same state."""
    rows, scaled = [], []
    grid_5000: dict = {}
    for n in sizes:
        report.progress(f"n = {n}, both methods")
        base = make_dance(n, "grid", settle)
        dances = {}
        for method in NEIGHBOUR_METHODS:
            dances[method] = copy.deepcopy(base)
            dances[method].pair_force.method = method
        number = 1 if report.quick else max(1, 2000 // n)     # at least ~2000 particle-steps
        repeats = 3 if report.quick else (7 if n >= 3000 else 9)
        ms = alternating({m: (lambda d=d: d.step(H)) for m, d in dances.items()}, repeats, number)
        for method, dance in dances.items():
            pf = dance.pair_force
            scaled.append({"n": n, "method": method, "step_ms": ms[method],
                           "pair_tests": pf.tests, "pairs": pf.pairs})
            rows.append([n, method, ms[method], pf.tests, pf.pairs])
        if n == sizes[-1]:
            grid_5000 = grid_breakdown(dances["grid"], 5 if report.quick else 30)
    report.table("ms per step and pair tests per step (960 x 720 box, cut-off 40 px, 1 substep)",
                 ["n", "method", "ms/step", "pair tests", "pairs < R"], rows)
    return scaled, grid_5000


def crowd_positions(n: int, radius: float, seed: int = 7) -> np.ndarray:
    """n particles spread evenly over a disk of `radius` px at the box's centre (a cell corner)."""
    rng = np.random.default_rng(seed)
    r = radius * np.sqrt(rng.uniform(0.0, 1.0, n))
    a = rng.uniform(0.0, 2.0 * math.pi, n)
    return np.column_stack((BOX[0] / 2 + r * np.cos(a), BOX[1] / 2 + r * np.sin(a)))


def four_corners(n: int, seed: int = 7) -> np.ndarray:
    """The grid's worst case: four tight clusters at the far corners of the 2 x 2 cells round the
    box's centre. The four cells are all neighbours, so the grid tests every pair, but only the
    pairs within a cluster (a quarter) are closer than R."""
    rng = np.random.default_rng(seed)
    c = np.array([[BOX[0] / 2 - 38.0, BOX[1] / 2 - 38.0], [BOX[0] / 2 + 38.0, BOX[1] / 2 - 38.0],
                  [BOX[0] / 2 - 38.0, BOX[1] / 2 + 38.0], [BOX[0] / 2 + 38.0, BOX[1] / 2 + 38.0]])
    return c[rng.integers(0, 4, n)] + rng.uniform(-1.5, 1.5, (n, 2))


def crowds(report: Report, n: int, radii: list[float], corners: bool = True) -> list[dict]:
    """Section 3: the pair force alone (search + forces) in crowds, grid against all pairs."""
    species = np.random.default_rng(0).integers(0, SPECIES, n)
    shapes = [(f"disk, radius {r:g} px", r, crowd_positions(n, r)) for r in radii]
    if corners:
        shapes.insert(-1, ("4 clusters, 76 px apart", None, four_corners(n)))
    rows, out = [], []
    for label, radius, x in shapes:
        report.progress(f"crowd of {n}: {label}")
        forces = {m: PairForce(default_rule(), species, BOX, m) for m in NEIGHBOUR_METHODS}
        f = np.zeros_like(x)

        def evaluate(force: PairForce) -> None:
            f.fill(0.0)
            force.accumulate(None, x, None, f)

        ms = alternating({m: (lambda p=p: evaluate(p)) for m, p in forces.items()},
                         3 if report.quick or n > 2000 else 5, 1)
        grid = forces["grid"]
        share = grid.tests / all_pair_tests(n)
        row = {"n": n, "shape": label, "radius": radius, "grid_tests_share": share,
               "pairs_share": grid.pairs / all_pair_tests(n), "grid_ms": ms["grid"],
               "all_pairs_ms": ms["all_pairs"], "grid_over_all_pairs": ms["grid"] / ms["all_pairs"]}
        out.append(row)
        rows.append([label, share, row["pairs_share"], ms["grid"], ms["all_pairs"],
                     row["grid_over_all_pairs"]])
    report.table(f"Crowds: {n} particles gathered at the centre (radius 2 px: all at one point); "
                 "the pair force alone (search + forces)",
                 ["shape", "grid tests / all", "pairs / all", "grid ms", "all pairs ms",
                  "grid / all pairs"], rows)
    return out


def drawing(report: Report, n: int) -> dict:
    """Section 4: drawing n dots at 1280 x 800 by each of pygame's ways, same positions."""
    dance = make_dance(n, "grid", 5 if report.quick else 120)
    surface = pygame.Surface(SCREEN, 0, 32)          # the display's usual format, 32-bit XRGB
    view = View.fit((int(BOX[0]), int(BOX[1])), (0, 0, *SCREEN))
    times = {}
    for name, draw in DRAWERS.items():
        def frame(draw=draw) -> None:
            surface.fill((22, 24, 30))
            draw(surface, view, dance.ps.x, dance.species, SPECIES, DOT_RADIUS)
        times[name] = median_time(frame, repeats=3 if report.quick else 21) * 1000.0
    fill = median_time(lambda: surface.fill((22, 24, 30)), repeats=21) * 1000.0
    rows = [[name, max(ms - fill, 0.0), "used by the scene" if name == DRAWER_USED else ""]
            for name, ms in times.items()]
    report.table(f"Drawing {n} dots of radius {DOT_RADIUS:g} world px ({view.len(DOT_RADIUS):.1f} "
                 f"screen px) on {SCREEN[0]} x {SCREEN[1]} (the fill, {fill:.2f} ms, taken off)",
                 ["way", "ms", ""], rows)
    return {"n": n, "screen": list(SCREEN), "ms": {k: max(v - fill, 0.0) for k, v in times.items()},
            "used": DRAWER_USED}


def step_budget(report: Report) -> list[dict]:
    """Section 5: the costliest settings the scene accepts, stepped for real."""
    from app.scene import InputEvent, ParamError
    from scenes.particle_dance import ParticleDanceScene as Dance

    def most_substeps(settings: dict) -> int:
        accepted = 0
        for substeps in range(1, 51):
            try:
                Dance.resolve({**settings, "substeps": substeps})
            except ParamError:
                break
            accepted = substeps
        return accepted

    n = 300 if report.quick else TARGET_N
    cases = [{"particles": n, "neighbour_method": "grid"},
             {"particles": n, "neighbour_method": "all_pairs"},
             {"particles": n, "neighbour_method": "grid", "cutoff": 80.0}]
    out, rows = [], []
    for settings in cases:
        settings = {**settings, "substeps": most_substeps(settings)}
        report.progress(f"the scene at {settings}")
        scene = Dance(settings)
        for _ in range(3 if report.quick else 20):             # clusters start to form
            scene.advance()
        ms = median_time(scene.advance, repeats=3 if report.quick else 7, warmup=0) * 1000.0
        estimate = Dance.step_seconds(scene.p) * 1000.0
        out.append({"settings": settings, "estimate_ms": estimate, "step_ms": ms,
                    "pairs": scene.dance.pair_force.pairs})
        rows.append([", ".join(f"{k}={v}" for k, v in settings.items()), estimate, ms])
    if report.full:             # ~45 s at load ~20 (a third of the bench): behind --full
        settings = {"particles": TARGET_N, "mouse_strength": 20000.0, "mouse_radius": 400.0}
        report.progress("the densest crowd: the strongest, widest mouse held 3 s (about a minute)")
        scene = Dance(settings)
        scene.handle_event(InputEvent("mouse_down", (BOX[0] / 2, BOX[1] / 2), 1))
        while scene.time < 3.0:
            scene.advance()
        ms = median_time(scene.advance, repeats=5, warmup=0) * 1000.0
        pf = scene.dance.pair_force
        out.append({"settings": {**settings, "lmb_held_s": 3.0}, "estimate_ms": None,
                    "step_ms": ms, "pairs": pf.pairs, "tests": pf.tests})
        rows.append([f"particles={TARGET_N}, mouse 20000 px/s^2 x 400 px, LMB held 3 s: "
                     f"{pf.pairs / 1e6:.1f} M pairs < R", None, ms])
    report.table("The step budget: the costliest settings the scene accepts (most substeps), "
                 "against the window's 100 ms", ["settings", "estimate ms", "measured ms"], rows)
    return out


def frame(report: Report, n: int) -> dict:
    """Section 6: one step plus drawing every particle at 1280 x 800, grid."""
    dance = make_dance(n, "grid", 5 if report.quick else 120)
    surface = pygame.Surface(SCREEN, 0, 32)
    view = View.fit((int(BOX[0]), int(BOX[1])), (0, 0, *SCREEN))

    def draw() -> None:
        surface.fill((22, 24, 30))
        DRAWERS[DRAWER_USED](surface, view, dance.ps.x, dance.species, SPECIES, DOT_RADIUS)

    repeats = 3 if report.quick else 21
    step_ms = median_time(lambda: dance.step(H), repeats=repeats) * 1000.0
    draw_ms = median_time(draw, repeats=repeats) * 1000.0
    report.table(f"One frame at {n} particles, grid: step + draw on {SCREEN[0]} x {SCREEN[1]} "
                 "(60 fps = 16.7 ms)", ["step ms", "draw ms", "step + draw ms", "fps it allows"],
                 [[step_ms, draw_ms, step_ms + draw_ms, 1000.0 / (step_ms + draw_ms)]])
    return {"n": n, "method": "grid", "step_ms": step_ms, "draw_ms": draw_ms,
            "frame_ms": step_ms + draw_ms, "fps_limit": 1000.0 / (step_ms + draw_ms)}


def targets(report: Report, out: dict) -> list[dict]:
    """The targets of issue 19 with the measured figures and, where one is missed, why."""
    by = {(s["n"], s["method"]): s for s in out["scaling"]}
    n = max(s["n"] for s in out["scaling"])
    grid, every = by[(n, "grid")], by[(n, "all_pairs")]
    parts = out["grid_breakdown"]
    load = load_note()
    ns_test = parts["search_ms"] * 1e6 / max(parts["tests"], 1)
    ns_all = every["step_ms"] * 1e6 / max(every["pair_tests"], 1)
    why_grid = (f"of {parts['step_ms']:.1f} ms (mean of 30 steps): finding pairs "
                f"{parts['search_ms']:.1f} ({parts['tests']:,} candidate tests, {ns_test:.0f} ns "
                f"each), forces {parts['forces_ms']:.1f} ({parts['pairs']:,} pairs), drag, walls "
                f"and the integrator {parts['rest_ms']:.1f}; {load}")
    ratio = every["step_ms"] / grid["step_ms"]
    ceiling = every["step_ms"] / max(parts["forces_ms"] + parts["rest_ms"], 1e-9)
    why_ratio = (f"the grid tests {every['pair_tests'] / max(grid['pair_tests'], 1):.0f}x fewer "
                 f"pairs but each costs more ({ns_test:.0f} ns a candidate against "
                 f"{ns_all:.1f} ns an all-pairs test), and the forces on the "
                 f"{parts['pairs']:,} pairs within R, the same work in both methods, take "
                 f"{parts['forces_ms']:.1f} of the grid's {parts['step_ms']:.1f} ms: even a free "
                 f"search would stop the ratio at {ceiling:.0f}; {load}")
    draw = out["drawing"]["ms"][DRAWER_USED]
    one_point = out["crowds"][-1]
    slowest = max(out["crowds"], key=lambda c: c["grid_over_all_pairs"])
    worst = max(out["budget"][:3], key=lambda b: b["step_ms"])
    crowd = out["budget"][3] if len(out["budget"]) > 3 else None
    rows = [
        (f"grid at {n} particles, ms a step", f"<= {GOALS['grid_ms']:g}", grid["step_ms"],
         grid["step_ms"] <= GOALS["grid_ms"], why_grid),
        (f"all pairs / grid at {n} particles", f">= {GOALS['ratio']:g}", ratio,
         ratio >= GOALS["ratio"], why_ratio),
        (f"drawing 5000 dots at {SCREEN[0]} x {SCREEN[1]}, ms", f"<= {GOALS['draw_ms']:g}", draw,
         draw <= GOALS["draw_ms"], f"the quickest way measured: "
         f"{min(out['drawing']['ms'], key=out['drawing']['ms'].get)}; {load}"),
        (f"grid / all pairs, every particle at one point (n = {one_point['n']})",
         f"<= {GOALS['crowd_ratio']:g}", one_point["grid_over_all_pairs"],
         one_point["grid_over_all_pairs"] <= GOALS["crowd_ratio"],
         f"both test all {all_pair_tests(one_point['n']):,} pairs and every pair interacts; "
         f"{load}"),
        (f"grid / all pairs, the worst of {len(out['crowds'])} crowds", f"<= {GOALS['crowd_ratio']:g}",
         slowest["grid_over_all_pairs"], slowest["grid_over_all_pairs"] <= GOALS["crowd_ratio"],
         f"{slowest['shape']}, n = {slowest['n']}: the grid tests {slowest['grid_tests_share']:.0%}"
         f" of all pairs, {slowest['pairs_share']:.0%} interact; {load}"),
        ("costliest settings the scene accepts, ms a step", f"<= {GOALS['budget_ms']:g}",
         worst["step_ms"], worst["step_ms"] <= GOALS["budget_ms"],
         f"{worst['settings']}: the scene estimated {worst['estimate_ms']:.0f} ms; {load}"),
    ]
    if crowd is not None:
        rows.append(("the densest crowd the sliders allow (LMB held), ms a step",
                     f"<= {GOALS['budget_ms']:g}", crowd["step_ms"],
                     crowd["step_ms"] <= GOALS["budget_ms"],
                     f"{crowd['pairs']:,} pairs within R: every one needs its force, whatever "
                     f"finds them ({crowd['step_ms'] * 1e6 / crowd['pairs']:.0f} ns a pair); "
                     f"{load}"))
    table = []
    result = []
    for name, goal, measured, met, reason in rows:
        verdict = "met" if met else "MISSED: " + reason
        if report.quick:
            verdict = "(--quick: small sizes, not the targets' measurement) " + verdict
        table.append([name, goal, measured, verdict])
        result.append({"target": name, "goal": goal, "measured": measured, "met": bool(met),
                       "reason": None if met else reason})
    report.table("Targets (issue 19)", ["target", "goal", "measured", "verdict"], table)
    return result


def run(report: Report) -> dict:
    quick = report.quick
    sizes = QUICK_SIZES if quick else SIZES
    settle = 5 if quick else 120
    out: dict = {"box": list(BOX), "cutoff": 40.0, "species": SPECIES, "settle_steps": settle}

    # 1-2. scaling and where the grid starts to win
    out["scaling"], out["grid_breakdown"] = scaling(report, sizes, settle)
    by = {(s["n"], s["method"]): s for s in out["scaling"]}
    all_ms = [by[(n, "all_pairs")]["step_ms"] for n in sizes]
    grid_ms = [by[(n, "grid")]["step_ms"] for n in sizes]
    out["grid_wins_from_n"] = crossover(sizes, all_ms, grid_ms)
    ratios = [a / g for a, g in zip(all_ms, grid_ms)]
    out["ratio_all_pairs_over_grid"] = {str(n): r for n, r in zip(sizes, ratios)}
    report.table("all pairs / grid, ms per step (same run): > 1 means the grid is faster",
                 ["n", "all_pairs / grid"], [[n, r] for n, r in zip(sizes, ratios)])
    wins = out["grid_wins_from_n"]
    report.say(f"\nthe grid is faster from n = {wins:.0f} on" if wins is not None
               else "\nthe grid was not faster at any n of the sweep")

    # 3-6. crowds, drawing, the step budget, a frame
    crowd_n = 300 if quick else 2000
    radii = [400.0, 40.0, 2.0] if quick else CROWD_RADII
    out["crowds"] = crowds(report, crowd_n, radii)
    if report.full:                     # every particle of the target at one point (~25 s)
        out["crowds"] += crowds(report, TARGET_N, [2.0], corners=False)
    out["drawing"] = drawing(report, TARGET_N)
    out["budget"] = step_budget(report)
    out["frame"] = frame(report, 300 if quick else TARGET_N)
    out["targets"] = targets(report, out)

    # charts
    c_ms = LineChart("ms per step vs particles (log-log: slope 2 = n^2, slope 1 = n)",
                     "particles n", "ms/step", logx=True, logy=True)
    c_tests = LineChart("pair tests per step vs particles", "particles n", "pair tests",
                        logx=True, logy=True)
    for method in NEIGHBOUR_METHODS:
        c_ms.add(method, sizes, [by[(n, method)]["step_ms"] for n in sizes])
        c_tests.add(method, sizes, [by[(n, method)]["pair_tests"] for n in sizes])
    out["chart"] = save_grid([c_ms, c_tests], report.chart_path("particles.png"))
    return out


if __name__ == "__main__":      # python -m app.bench.particles
    run(Report())
