"""`python -m app bench cloth`: what accuracy costs in time, and what vectorising buys.

Every cloth here is the cloth scene the app runs, built through the registry (scenes.get_scene,
so the bench imports no scene module: the scene stays the one source of its settings) (structural + shear rods, top row pinned, gravity
and drag, no wind), in a well-defined state: it hangs for 150 steps under gravity from rest (20
with --quick), and its stretch (|length/rest - 1| of the structural rods) is averaged over the
last 30 of them (5). Drag is 0.05 (velocity lost per 1/60 s, whatever the substeps) so the cloth
has settled by then (the stretch is a state, not a phase of an oscillation). Bigger grids fill the same world area: same cloth, finer resolution.

1. sizes x iterations: ms per step and the resulting stretch;
2. equal work, 10 sweeps per step split as substeps x iterations (1x10, 2x5, 5x2, 10x1);
3. the same cloth written the slide's way (app/physics/cloth_naive.py: an object per particle,
   nested loops), timed in the same run: the ratio is what vectorising buys;
4. drawing: ms to draw a 64 x 64 cloth (strain heat map) on a 960 x 720 surface;
5. contact (app/bench/cloth_contact.py): collisions with three obstacles and self-collision
   (grid against all pairs) on a 64 x 64 cloth, each beside the step without it.
And first, the step against the same step in C, scalar and SIMD, compiled here when a compiler
is present (app/bench/cloth_c.py), with the optional numba kernel beside NumPy.
"""

from __future__ import annotations

import statistics

import pygame

from app.bench import Report, cloth_c, median_time
from app.draw.plot import LineChart, save_grid
from app.draw.view import View
from app.physics.cloth_naive import NaiveCloth
from app.scene import Scene

BASE = {"shear": True, "bending": False, "wind": False, "tearing": False, "pins": "top",
        "drag_coef": 0.05}          # strong drag: the cloth settles within the hang


def hung(n: int, iterations: int, substeps: int = 1, *, hang: int, avg: int,
         **extra) -> tuple[Scene, float, float]:
    """An n x n cloth after `hang` steps; returns it with its mean and max stretch averaged over
    the last `avg` steps."""
    from scenes import get_scene            # the registry: the scene the app runs
    scene = get_scene("cloth")({**BASE, "rows": n, "cols": n, "iterations": iterations,
                        "substeps": substeps, **extra})
    means, maxes = [], []
    for k in range(hang):
        scene.advance()
        if k >= hang - avg:
            m = scene.metrics()
            means.append(m["mean_stretch"])
            maxes.append(m["max_stretch"])
    return scene, statistics.fmean(means), statistics.fmean(maxes)


def step_ms(scene: Scene, repeats: int, number: int) -> float:
    return median_time(scene.advance, repeats=repeats, warmup=1, number=number) * 1000.0


def run(report: Report) -> dict:
    quick = report.quick
    sizes = [12, 20] if quick else [32, 64, 128]
    iters = [1, 5] if quick else [1, 5, 10, 20]
    hang, avg = (20, 5) if quick else (150, 30)
    repeats, number = (3, 1) if quick else (7, 3)
    out: dict = {"sizes": sizes, "iterations": iters, "hang_steps": hang}
    # 0. the step against compiled C (scalar and SIMD) and the numba kernel (app/bench/cloth_c.py)
    out["vs_c"] = cloth_c.run(report)

    # 1. sizes x iterations
    rows, grid = [], {}
    for n in sizes:
        for it in iters:
            report.progress(f"{n}x{n}, {it} iterations")
            scene, mean, mx = hung(n, it, hang=hang, avg=avg)
            ms = step_ms(scene, repeats, number)
            grid[(n, it)] = (ms, mean, mx)
            rows.append([f"{n}x{n}", it, scene.metrics()["constraints"], ms, mean * 100, mx * 100])
    report.table("Cost and accuracy: n x n cloth, structural + shear, 1 substep, hanging "
                 f"{hang} steps",
                 ["cloth", "iterations", "rods", "ms/step", "mean stretch %", "max stretch %"],
                 rows)
    out["grid"] = [{"n": n, "iterations": it, "ms": v[0], "mean_stretch": v[1], "max_stretch": v[2]}
                   for (n, it), v in grid.items()]
    big = sizes[-1]
    target_it = 10 if 10 in iters else iters[-1]
    out["big_ms"] = grid[(big, target_it)][0]
    report.say(f"\n{big}x{big}, structural + shear, {target_it} iterations, 1 substep: "
               f"{out['big_ms']:.2f} ms/step (target: at most 8 ms at 128x128, float32)")
    scene64, _, _ = hung(big, target_it, hang=2, avg=1, precision="float64")
    out["big_ms_float64"] = step_ms(scene64, repeats, number)
    report.say(f"the same in float64: {out['big_ms_float64']:.2f} ms/step")

    # 2. equal work: substeps x iterations = 10 sweeps per step
    n_eq = 20 if quick else 64
    splits = [(1, 10), (2, 5), (5, 2), (10, 1)]
    eq_rows, eq = [], []
    for sub, it in splits:
        report.progress(f"{n_eq}x{n_eq}, {sub} substeps x {it} iterations")
        scene, mean, mx = hung(n_eq, it, sub, hang=hang, avg=avg)
        ms = step_ms(scene, repeats, number)
        eq.append({"substeps": sub, "iterations": it, "ms": ms, "mean_stretch": mean,
                   "max_stretch": mx})
        eq_rows.append([f"{sub} x {it}", ms, mean * 100, mx * 100])
    report.table(f"Equal work, 10 sweeps per step, {n_eq}x{n_eq} cloth: substeps x iterations",
                 ["substeps x iterations", "ms/step", "mean stretch %", "max stretch %"], eq_rows)
    out["equal_work"] = eq

    # 3. the slide's per-object Python version of the same algorithm
    n_nv = 12 if quick else 64
    it_nv = 10
    report.progress(f"per-object Python cloth {n_nv}x{n_nv}")
    scene, _, _ = hung(n_nv, it_nv, hang=2, avg=1)
    c = scene.cloth
    naive = NaiveCloth(n_nv, n_nv, c.spacing, (float(c.rest_x[0, 0, 0]), float(c.rest_x[1, 0, 0])),
                       "top", ("structural", "shear"))
    naive.iterations = it_nv
    h = scene.dt
    naive_ms = median_time(lambda: naive.step(h), repeats=1 if quick else 3, warmup=1) * 1000.0
    numpy_ms = step_ms(scene, repeats, number)
    out["naive"] = {"n": n_nv, "iterations": it_nv, "naive_ms": naive_ms, "numpy_ms": numpy_ms,
                    "speedup": naive_ms / numpy_ms}
    report.table(f"What vectorising buys: {n_nv}x{n_nv}, structural + shear, {it_nv} iterations",
                 ["version", "ms/step", "ratio"],
                 [["objects + nested loops (slide)", naive_ms, 1.0],
                  ["NumPy batches", numpy_ms, naive_ms / numpy_ms]])

    # 4. drawing
    n_dr = 20 if quick else 64
    scene, _, _ = hung(n_dr, 10, hang=hang, avg=1)
    surface = pygame.Surface(scene.world_size)
    view = View()

    def frame() -> None:
        surface.fill(scene.background)
        scene.draw(surface, view)

    draw_ms = median_time(frame, repeats=repeats, number=number) * 1000.0
    stepped = step_ms(scene, repeats, number)
    out["draw"] = {"n": n_dr, "draw_ms": draw_ms, "step_ms": stepped,
                   "frame_ms": draw_ms + stepped, "fps_limit": 1000.0 / (draw_ms + stepped)}
    report.table(f"Drawing a {n_dr}x{n_dr} cloth (strain heat map) on 960x720",
                 ["draw ms", "step ms", "draw + step ms", "fps it allows"],
                 [[draw_ms, stepped, draw_ms + stepped, 1000.0 / (draw_ms + stepped)]])

    # charts
    c_ms = LineChart("Cost: time per step vs iterations", "constraint iterations per step",
                     "time per step (ms)", logy=True)
    c_st = LineChart("Accuracy: mean stretch after hanging vs iterations",
                     "constraint iterations per step", "mean stretch |l/rest - 1| (%)", logy=True)
    for n in sizes:
        c_ms.add(f"{n}x{n}", iters, [grid[(n, it)][0] for it in iters])
        c_st.add(f"{n}x{n}", iters, [grid[(n, it)][1] * 100 for it in iters])
    c_eq = LineChart(f"Same work (10 sweeps per step), {n_eq}x{n_eq}: stretch vs substeps",
                     "substeps (x iterations = 10)", "stretch |l/rest - 1| (%)", logx=True,
                     logy=True)
    c_eq.add("mean stretch", [e["substeps"] for e in eq], [e["mean_stretch"] * 100 for e in eq])
    c_eq.add("max stretch", [e["substeps"] for e in eq], [e["max_stretch"] * 100 for e in eq])
    c_eqms = LineChart(f"Same work (10 sweeps per step), {n_eq}x{n_eq}: time vs substeps",
                       "substeps (x iterations = 10)", "time per step (ms)", logx=True)
    c_eqms.add("time per step", [e["substeps"] for e in eq], [e["ms"] for e in eq])
    # 5. contact: collisions and self-collision at 64 x 64 (app/bench/cloth_contact.py)
    from app.bench import cloth_contact
    out["contact"] = cloth_contact.run(report)

    out["chart"] = save_grid([c_ms, c_st, c_eq, c_eqms], report.chart_path("cloth.png"),
                             title="Verlet cloth: what accuracy costs (structural + shear rods, "
                                   "hanging from its top row)")
    return out


if __name__ == "__main__":      # python -m app.bench.cloth
    run(Report())
