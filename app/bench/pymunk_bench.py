"""Benchmark of the pymunk scenes: `python -m app bench pymunk`.

What it shows: first, the lab's step in every pymunk scene against a bare pymunk loop over the
same bodies (app/bench/pymunk_cost.py: the ratio lab / bare, goal at most 1.5); then, for
falling_balls with balls packed into its container, radius 6 px:
  1. step + draw of 1000 awake balls (2000 with --full) against the 16.7 ms of a 60 fps frame;
  2. the project's drawing (one batch read, sprites, one fblits) against pymunk's
     `space.debug_draw` (pymunk.pygame_util.DrawOptions) of the very same space, side by side;
  3. a settled pile that sleeps against the same pile awake (sleeping switched off): the solver
     skips sleeping bodies (and the lab reads none), so a resting pile costs almost nothing;
  4. ms per step against the number of balls, awake and asleep (chart pymunk_step.png), and the
     drawing cost against the number of balls (chart pymunk_draw.png).
Every figure is a median (app.bench.median_time); ratios compare runs made in the same process.
"""

from __future__ import annotations

import pygame
import pymunk.pygame_util

from app.bench import Report, median_time, pymunk_cost, pymunk_ir
from app.draw.plot import LineChart
from app.draw.view import View
from app.scene import Scene


def falling_balls() -> type[Scene]:
    """The falling-balls scene class, from the registry (the bench imports no scene module)."""
    from scenes import get_scene
    return get_scene("falling_balls")


RADIUS = 6.0


def pile(n: int, sleeping: bool) -> Scene:
    """A falling_balls scene with n balls packed into its container (no new balls coming)."""
    scene = falling_balls()({"container": True, "spawn_rate": 0, "radius": RADIUS,
                               "max_balls": max(n, 1), "sleeping": sleeping})
    added = scene.add_balls(n)
    assert added == n, f"only {added} of {n} balls fit"
    return scene


def settle(scene: Scene, max_steps: int) -> int:
    """Step until every ball sleeps (or max_steps); return the steps taken."""
    for i in range(max_steps):
        scene.advance()
        if i % 30 == 29 and scene.asleep_count() == len(scene.balls):
            return i + 1
    return max_steps


def run(report: Report) -> dict:
    quick = report.quick
    repeats = 3 if quick else 15 if report.full else 7
    # 2000 balls (~50 s at load ~3: their pile never settles in 900 steps) behind --full
    counts = [100, 200] if quick else [250, 500, 1000, 2000] if report.full else [250, 500, 1000]
    big = counts[-1]
    surface = pygame.Surface(falling_balls().world_size)
    view = View()
    options = pymunk.pygame_util.DrawOptions(surface)
    results: dict = {"radius": RADIUS, "by_count": []}
    # 0: the lab's step against a bare pymunk loop over the same bodies (app/bench/pymunk_cost.py)
    results["engine_cost"] = pymunk_cost.run(report)
    if report.full:          # the same cases in instructions (valgrind, when installed)
        labels = [label for label, _ in pymunk_cost.cases(False)]
        results["engine_cost"]["instructions"] = pymunk_ir.instructions(report, labels)

    # 1 + 2: many awake balls, stepping and drawing, ours vs debug_draw
    draw_own, draw_debug, step_awake, step_asleep = [], [], [], []
    for n in counts:
        report.progress(f"{n} balls")
        scene = pile(n, sleeping=False)
        for _ in range(30 if quick else 120):         # 2 s: the packed grid settles, awake
            scene.advance()
        step = median_time(scene.advance, repeats=repeats, number=5 if quick else 10)
        own = median_time(lambda: scene.draw(surface, view), repeats=repeats, number=3)
        debug = median_time(lambda: scene.space.debug_draw(options), repeats=repeats, number=3)

        # 3: the same number of balls as a settled pile, asleep and then woken
        sleepy = pile(n, sleeping=True)
        settle_steps = settle(sleepy, 120 if quick else 900)
        asleep = sleepy.asleep_count()
        t_asleep = median_time(sleepy.advance, repeats=repeats, number=5 if quick else 20)
        sleepy.set("sleeping", False)                  # wakes every ball, same positions
        t_awake = median_time(sleepy.advance, repeats=repeats, number=5 if quick else 10)

        row = {"balls": n, "step_ms": step * 1e3, "draw_ms": own * 1e3,
               "debug_draw_ms": debug * 1e3, "frame_ms": (step + own) * 1e3,
               "draw_speedup": debug / own, "settle_steps": settle_steps, "asleep": asleep,
               "pile_asleep_step_ms": t_asleep * 1e3, "pile_awake_step_ms": t_awake * 1e3,
               "sleep_speedup": t_awake / t_asleep}
        results["by_count"].append(row)
        draw_own.append(own * 1e3)
        draw_debug.append(debug * 1e3)
        step_awake.append(t_awake * 1e3)
        step_asleep.append(t_asleep * 1e3)

    rows = results["by_count"]
    report.table("falling_balls: step and draw (awake balls, 960x720, ms)",
                 ["balls", "step", "draw (ours)", "step+draw", "60 fps?", "debug_draw",
                  "debug/ours"],
                 [[r["balls"], r["step_ms"], r["draw_ms"], r["frame_ms"],
                   "yes" if r["frame_ms"] <= 1000 / 60 else "NO", r["debug_draw_ms"],
                   r["draw_speedup"]] for r in rows])
    report.table("a settled pile: asleep vs the same pile awake (ms per step)",
                 ["balls", "steps to settle", "asleep", "step asleep", "step awake",
                  "awake/asleep"],
                 [[r["balls"], r["settle_steps"], r["asleep"], r["pile_asleep_step_ms"],
                   r["pile_awake_step_ms"], r["sleep_speedup"]] for r in rows])

    top = rows[-1]
    by_n = {r["balls"]: r for r in rows}
    pile_n = 1000 if 1000 in by_n else big
    results["summary"] = {
        "balls": big,
        "frame_ms": top["frame_ms"],
        "fits_60fps": top["frame_ms"] <= 1000 / 60,
        "draw_speedup_vs_debug_draw": top["draw_speedup"],
        "sleep_pile_balls": pile_n,
        "sleep_speedup": by_n[pile_n]["sleep_speedup"],
    }
    s = results["summary"]
    report.say(f"\n{big} balls: step+draw {s['frame_ms']:.2f} ms "
               f"({'within' if s['fits_60fps'] else 'OVER'} 16.7 ms); our drawing "
               f"{s['draw_speedup_vs_debug_draw']:.1f}x faster than space.debug_draw; a sleeping "
               f"pile of {pile_n} steps {s['sleep_speedup']:.1f}x faster than awake")

    chart = LineChart("falling_balls: a settled pile, asleep or awake", "balls",
                      "time per step (ms)", logy=True)
    chart.add("awake (sleeping off)", counts, step_awake)
    chart.add("asleep (sleeping on)", counts, step_asleep)
    chart.save(report.chart_path("pymunk_step.png"))
    chart = LineChart("falling_balls: drawing a frame", "balls", "time per frame drawn (ms)",
                      logy=True)
    chart.add("space.debug_draw", counts, draw_debug)
    chart.add("pymunk_draw (batch + sprites)", counts, draw_own)
    chart.save(report.chart_path("pymunk_draw.png"))
    return results
