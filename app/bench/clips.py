"""`python -m app bench clips`: how fast a headless clip of each scene is made, against real time.

For four scenes of the registry (the two cloths, the double pendulum and the integrator lab:
the slowest to film; every scene with --full), at their default settings, and for
each format (GIF always, MP4 when imageio-ffmpeg is installed), it records a 2 s clip three times
(10 s three times with --full, 1 s once with --quick) exactly as
`python -m app --headless --scene NAME --seconds 10 --video OUT` does (1280 px wide, 30 fps,
HUD in) and reports

  * wall seconds to make it (run + frames + encoding), the median over repeats, and the speed
    against real time: clip seconds / wall seconds (above 1: faster than real time);
  * CPU seconds (this process's threads and ffmpeg's), which another process's load changes far
    less than wall time: below the clip's length means faster than real time on one core;
  * the physics alone (the same steps without a clip, timed in the same run), the frames, the
    file size.

Each row is printed as soon as it is measured. By default about 45 s on an idle 2-core machine
(24 clips of 1-2 CPU seconds each; 3 min at load ~10).

The clips are kept in <out>/clips/ so they can be looked at.
"""

from __future__ import annotations

import os
import time
from typing import Any

from app.bench import Report
from app.bench import Timing
from app.clips import DEFAULT_FPS, DEFAULT_WIDTH, mp4_problem


def _cpu() -> float:
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def make_clip(cls, seconds: float, path: str) -> dict[str, Any]:
    """One headless clip of `cls` at its defaults; wall and CPU seconds, frames, bytes."""
    from app.headless import record_clip, steps_for
    scene = cls({})
    steps = steps_for(seconds, scene.dt)
    wall0, cpu0 = time.perf_counter(), _cpu()
    runner, clip = record_clip(scene, steps, None, path, DEFAULT_FPS, DEFAULT_WIDTH, False)
    wall, cpu = time.perf_counter() - wall0, _cpu() - cpu0
    if isinstance(clip, str) or not runner.finite:
        raise RuntimeError(f"{cls.name}: {clip if isinstance(clip, str) else 'went non-finite'}")
    return {"wall": wall, "cpu": cpu, "frames": clip.frames, "bytes": clip.bytes,
            "size": list(clip.size)}


def physics_seconds(cls, seconds: float) -> float:
    """Wall seconds of the same run without a clip."""
    from app.headless import steps_for
    from app.runner import run_scene
    scene = cls({})
    t0 = time.perf_counter()
    run_scene(scene, steps_for(seconds, scene.dt))
    return time.perf_counter() - t0


DEFAULT_SCENES = ("cloth", "mass_spring_cloth", "double_pendulum", "integrators")
# the slowest to film (3 s clips at load ~8: 0.25-0.5x real time); every scene with --full


def run(report: Report) -> dict[str, Any]:
    from scenes import SCENES
    quick, full = report.quick, report.full
    # 10 s clips three times each of every scene is 66 clips (minutes): behind --full
    seconds = 1.0 if quick else 10.0 if full else 2.0
    repeats = 1 if quick else 3
    chosen = SCENES if full else [c for c in SCENES if c.name in DEFAULT_SCENES]
    formats = [".gif"] + ([".mp4"] if mp4_problem() is None else [])
    if ".mp4" not in formats:
        report.say(f"MP4 left out: {mp4_problem()}")
    folder = os.path.join(report.out_dir, "clips")
    os.makedirs(folder, exist_ok=True)
    report.say(f"A {seconds:g} s headless clip of {'each scene' if full else 'four scenes'} at "
               f"its defaults ({DEFAULT_WIDTH} px wide, {DEFAULT_FPS} fps, HUD in); medians "
               f"over {repeats} run(s)" + ("" if full else "; every scene: --full") + ".")
    rows, out = [], {"seconds": seconds, "repeats": repeats, "clips": []}
    row = report.live_table(
        f"{seconds:g} s clips: wall and CPU seconds to make them (speed = clip seconds / wall "
        "seconds; above 1 is faster than real time)",
        ["scene", "format", "frames", "size", "MB", "physics s", "wall s", "CPU s", "speed"],
        [17, 6, 6, 9, 6, 24, 24, 24, 6])
    for cls in chosen:
        report.progress(f"{cls.name}: physics alone")
        physics = Timing.of([physics_seconds(cls, seconds) for _ in range(repeats)])
        for fmt in formats:
            path = os.path.join(folder, f"{cls.name}{fmt}")
            runs = []
            for k in range(repeats):
                report.progress(f"{cls.name}{fmt} ({k + 1}/{repeats})")
                runs.append(make_clip(cls, seconds, path))
            wall = Timing.of([r["wall"] for r in runs])
            cpu = Timing.of([r["cpu"] for r in runs])
            last = runs[-1]
            entry = {"scene": cls.name, "format": fmt[1:], "frames": last["frames"],
                     "size": last["size"], "mb": last["bytes"] / 1e6, "wall_s": wall,
                     "speed_x_real_time": seconds / wall, "cpu_s": cpu, "physics_s": physics,
                     "path": path}
            out["clips"].append(entry)
            rows.append([cls.name, fmt[1:], entry["frames"], f"{last['size'][0]}x{last['size'][1]}",
                         entry["mb"], physics, wall, cpu, entry["speed_x_real_time"]])
            row(rows[-1])
    slowest = min(out["clips"], key=lambda e: e["speed_x_real_time"])
    out["slowest"] = slowest["scene"] + "." + slowest["format"]
    out["all_faster_than_real_time"] = slowest["speed_x_real_time"] > 1.0
    report.say(f"\nslowest: {out['slowest']} at {slowest['speed_x_real_time']:.2f}x real time "
               f"({'faster' if out['all_faster_than_real_time'] else 'SLOWER'} than real time); "
               f"clips in {folder}")
    if not full:
        report.say("  (short clips, where starting up (fonts, threads, ffmpeg, the GIF's "
                   "palette) weighs most; --full measures 10 s clips)")
    return out


if __name__ == "__main__":      # python -m app.bench.clips
    run(Report())
