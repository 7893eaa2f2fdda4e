"""`python -m app bench frames`: every scene, alone and in 4-pane comparisons, run at
real time and drawn whole at 1920x1080, against the frame budget.

Every registered scene at its defaults, alone and in a comparison of 4 panes (and of 2 with
--full; copies at the defaults, as `--compare` would show them), is run as the window runs it
at real time: per frame of 1/60 s the steps that frame is due (hertz / 60 of them, through the
same SceneRunner, with its non-finite check), then the whole picture drawn into a 1920 x 1080 surface (the scene or the
panes, with their HUD text, as app/frames.py draws a screenshot). No display is needed (SDL's
dummy video driver). For each: physics, drawing and the whole frame in ms, median and spread
(max - min over the frames timed), against the frame budget: 16.7 ms for one scene (60 fps),
33 ms for a comparison (30 fps), on this machine. Times are CPU time of this process
(time.process_time): on a machine shared with other work, the wall clock also counts the time
the others ran; on a quiet one the two agree (drawing and stepping run in this one thread).
"""

from __future__ import annotations

import os
import statistics
import time

from app.bench import Report, load_average

SIZE = (1920, 1080)
BUDGET_MS = {1: 1000 / 60, 2: 1000 / 30, 4: 1000 / 30}


def frames_of(cls, panes: int, warm: int, frames: int):
    """(physics, drawing, frame) CPU seconds per frame, `frames` frames after `warm` frames."""
    import pygame

    from app.draw import hud
    from app.draw.layout import Pane
    from app.draw.panes import PaneGrid
    from app.frames import compare_header, compare_pane_lines
    from app.runner import SceneRunner

    runners = [SceneRunner(cls()) for _ in range(panes)]
    scenes = [r.scene for r in runners]
    surface = pygame.Surface(SIZE)
    area = surface.get_rect()
    grid = PaneGrid(scenes) if panes > 1 else None
    pane = Pane(scenes[0]) if panes == 1 else None
    due = 0.0
    physics, drawing, whole = [], [], []
    for k in range(warm + frames):
        t0 = time.process_time()
        due += scenes[0].p["hertz"] / 60.0          # steps due this frame (real time)
        n = int(due)
        due -= n
        for r in runners:
            r.run(n)
        t1 = time.process_time()
        surface.fill((21, 24, 29))
        if grid is not None:
            t = max(s.time for s in scenes)
            grid.draw(surface, area, compare_header(scenes, t), compare_pane_lines(runners),
                      brief=compare_pane_lines(runners, brief=True))
        else:
            scene = scenes[0]
            lines = hud.scene_lines(scene, [f"t = {scene.time:.2f} s  |  {hud.dt_text(scene)}"],
                                    [])
            pane.draw(surface, area, lines)
        t2 = time.process_time()
        if k >= warm:
            physics.append(t1 - t0)
            drawing.append(t2 - t1)
            whole.append(t2 - t0)
    return physics, drawing, whole


def _ms(values: list[float]) -> tuple[float, float]:
    return statistics.median(values) * 1e3, (max(values) - min(values)) * 1e3


def run(report: Report) -> dict:
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    import pygame
    pygame.init()
    from scenes import SCENES

    # by default alone and in 4 panes (about 30 s idle); 2 panes too with --full
    warm, frames = (2, 3) if report.quick else (30, 30) if report.full else (20, 25)
    pane_counts = (1, 2) if report.quick else (1, 2, 4) if report.full else (1, 4)
    chosen = SCENES[:3] if report.quick else SCENES
    out = []
    row = report.live_table(
        f"Whole frames at {SIZE[0]}x{SIZE[1]}, every scene at its defaults, real time "
        f"(median and spread (max - min) of {frames} frames, CPU ms)",
        ["scene", "panes", "physics", "spread", "drawing", "spread", "frame", "spread",
         "budget", "in time?"], [22, 5, 7, 7, 7, 7, 7, 7, 6, 8])
    for cls in chosen:
        for panes in pane_counts:
            report.progress(f"frames: {cls.name}, {panes} pane{'s' if panes > 1 else ''}")
            phys, draw, whole = frames_of(cls, panes, warm, frames)
            (pm, ps), (dm, ds), (fm, fs) = _ms(phys), _ms(draw), _ms(whole)
            budget = BUDGET_MS[panes]
            ok = fm <= budget
            out.append({"scene": cls.name, "panes": panes, "physics_ms": pm,
                        "physics_spread_ms": ps, "draw_ms": dm, "draw_spread_ms": ds,
                        "frame_ms": fm, "frame_spread_ms": fs, "budget_ms": budget,
                        "in_time": ok})
            row([cls.name, panes, pm, ps, dm, ds, fm, fs, budget, "yes" if ok else "NO"])
    late = [f"{o['scene']} x{o['panes']}" for o in out if not o["in_time"]]
    report.say(("every frame in time" if not late else
                f"over budget: {', '.join(late)}") + f" ({len(out)} cases)")
    return {"size": list(SIZE), "frames": frames, "cases": out,
            "late": late, "cores": os.cpu_count() or 1,
            "load": load_average()}
