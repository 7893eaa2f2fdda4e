"""`python -m app bench particles`: what finding the pairs costs, all pairs against a grid.

The particle dance (app/physics/particle_dance.py) at its scene's default rule (3 species, random
rule matrix from seed 0, cut-off 40 px, k_att 300, k_rep 1000 px/s^2, drag 1/s, walls) in the
scene's 960 x 720 box, for n = 100 .. 5000 particles. For each n one state is made (n particles
spread at random, then 120 steps (2 s) with the grid, 5 with --quick, so clusters have formed)
and both neighbour methods step copies of that same state:

1. ms per step (the median over repeated steps, the two methods taking turns; search + forces +
   drag + walls) and the pair tests per step of each method: all pairs makes n (n - 1) / 2
   tests, the grid about n x (the particles in 4.5 cells). The box is fixed, so the density
   grows with n and both counts grow like n^2 (the grid's from ~1/50 of all pairs); on the
   chart's log axes that is slope 2. The grid's time starts flatter (slope ~0.5 up to a few
   hundred particles: a fixed cost per step, some 0.07 ms of NumPy calls whatever n is,
   dominates) and bends towards slope 2 (1.9-2.0 from n = 1000 on);
2. the n where the grid starts to win: interpolated (log-log) between the two sweep sizes where
   the ratio all_pairs / grid crosses 1;
3. a frame of the scene at 2000 particles (300 with --quick) with the grid: one step plus
   drawing every particle (app/draw/dance_draw.py) on a 960 x 720 surface, against 16.7 ms (60
   frames per second).
"""

from __future__ import annotations

import copy
import math
import statistics
import time
from typing import Callable

import numpy as np
import pygame

from app.bench import Report, median_time
from app.draw.dance_draw import draw_particles
from app.draw.plot import LineChart, save_grid
from app.draw.view import View
from app.physics.neighbours import NEIGHBOUR_METHODS
from app.physics.particle_dance import EFFECTS, PairRule, ParticleDance, rule_matrix

BOX = (960.0, 720.0)          # the scene's world
SPECIES = 3
H = 1.0 / 60.0
SIZES = [100, 200, 500, 1000, 2000, 3000, 5000]
QUICK_SIZES = [100, 300, 1000]
FRAME_N = 2000
DOT_RADIUS = 3.5


def make_dance(n: int, method: str, settle: int) -> ParticleDance:
    """n particles with the scene's default rule, after `settle` steps (grid) from seed 0."""
    rule = PairRule(rule_matrix("random", SPECIES, np.random.default_rng([0, 1])), 40.0, 300.0,
                    1000.0)
    dance = ParticleDance(n, SPECIES, BOX, rule, np.random.default_rng(0), set(EFFECTS), 1.0,
                          "grid")
    for _ in range(settle):
        dance.step(H)
    dance.pair_force.method = method
    return dance


def alternating(fns: dict[str, Callable[[], None]], repeats: int, number: int) -> dict[str, float]:
    """Median ms of `number` calls of each fn, the fns taking turns repeat by repeat. Each timed
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
    return {name: statistics.median(t) for name, t in times.items()}


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


def run(report: Report) -> dict:
    quick = report.quick
    sizes = QUICK_SIZES if quick else SIZES
    settle = 5 if quick else 120
    out: dict = {"box": list(BOX), "cutoff": 40.0, "species": SPECIES, "settle_steps": settle}

    # 1. ms per step and pair tests, n x method, on the same state; the two methods' repeats
    # alternate, so a burst of load from another process hits both alike
    scaling, rows = [], []
    for n in sizes:
        report.progress(f"n = {n}, both methods")
        base = make_dance(n, "grid", settle)
        dances = {}
        for method in NEIGHBOUR_METHODS:
            dances[method] = copy.deepcopy(base)
            dances[method].pair_force.method = method
        # small n: a batch of steps per timing (at least ~2000 particle-steps), big n: one step
        number = 1 if quick else max(1, 2000 // n)
        repeats = 3 if quick else (5 if n >= 3000 else 9)
        ms = alternating({m: (lambda d=d: d.step(H)) for m, d in dances.items()},
                         repeats, number)
        for method, dance in dances.items():
            tests = dance.pair_force.tests
            scaling.append({"n": n, "method": method, "step_ms": ms[method],
                            "pair_tests": tests, "pairs": dance.pair_force.pairs})
            rows.append([n, method, ms[method], tests, dance.pair_force.pairs])
    report.table("ms per step and pair tests per step (960 x 720 box, cut-off 40 px, 1 substep)",
                 ["n", "method", "ms/step", "pair tests", "pairs < R"], rows)
    out["scaling"] = scaling

    # 2. where the grid starts to win
    by = {(s["n"], s["method"]): s for s in scaling}
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

    # 3. one frame at 2000 particles with the grid: step + draw
    n_frame = 300 if quick else FRAME_N
    dance = make_dance(n_frame, "grid", settle)
    surface = pygame.Surface((int(BOX[0]), int(BOX[1])))
    view = View()

    def draw() -> None:
        surface.fill((22, 24, 30))
        draw_particles(surface, view, dance.ps.x, dance.species, SPECIES, DOT_RADIUS)

    repeats = 3 if quick else 21
    step_ms = median_time(lambda: dance.step(H), repeats=repeats) * 1000.0
    draw_ms = median_time(draw, repeats=repeats) * 1000.0
    out["frame"] = {"n": n_frame, "method": "grid", "step_ms": step_ms, "draw_ms": draw_ms,
                    "frame_ms": step_ms + draw_ms, "fps_limit": 1000.0 / (step_ms + draw_ms)}
    report.table(f"One frame at {n_frame} particles, grid: step + draw on 960 x 720 "
                 "(60 fps = 16.7 ms)",
                 ["step ms", "draw ms", "step + draw ms", "fps it allows"],
                 [[step_ms, draw_ms, step_ms + draw_ms, 1000.0 / (step_ms + draw_ms)]])

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
