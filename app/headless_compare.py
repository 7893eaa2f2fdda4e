"""`--headless --compare`: the variants of one scene run in lockstep (app/compare.py), one JSON
object per variant.

    python -m app --headless --scene cloth --compare iterations=2 iterations=20 --json

Each object is the single run's summary (README, "Command line") plus `variant` (its settings as
given), `pane` (A, B, ...), `label` (what differs from the other variants) and `reference_error`
(the scene's error against its reference: what, metric, value; null for a scene without one).
`wall_seconds` is the whole comparison's (the variants ran interleaved); `step_ms` is the
variant's own median. `--steps N` counts ticks of the comparison's clock (the smallest dt among
the variants: with one hertz, N steps of each). `--screenshot` saves every pane in one PNG,
`--csv` one file with a `variant` column. A variant that goes non-finite stops alone (its
object says `"finite": false`, stderr says why, exit code 1) while the others run to the end.
"""

from __future__ import annotations

import json
import sys
import time
from typing import Any

from app.compare import TAGS, CompareRunner, Variant, labels, resolve_variants
from app.headless import (EXIT_NONFINITE, EXIT_OK, EXIT_USAGE, Extras, card_json, describe,
                          finish_csv, note_clip, note_replaced, record_clip, report_stop,
                          save_screenshot, steps_for, summary)
from app.scene import InputEvent, Scene, Try
from app.series import clean as json_clean


def compare_steps(cls: type[Scene], overrides: list[dict[str, Any]], steps: int | None,
                  seconds: float | None) -> int:
    """The ticks a run takes: --steps, or --seconds at the smallest dt among the variants."""
    if steps is not None:
        return steps
    tick = min(1.0 / cls.resolve(o)[0]["hertz"] for o in overrides)
    return steps_for(seconds, tick)


def run_compare(cls: type[Scene], shared: dict[str, Any], variants: list[Variant],
                steps: int | None, seconds: float | None, events: list[InputEvent] | None,
                screenshot: str | None, as_json: bool, card: Try | None = None,
                extras: Extras | None = None, video: str | None = None, fps: int | None = None,
                width: int | None = None, clean: bool = False) -> int:
    """Run the comparison; print one JSON object (or readable summary) per variant. With
    `video`, a clip of every pane (app/clips.py) at `fps`, `width` px wide."""
    extras = extras or Extras()
    overrides = resolve_variants(cls, shared, variants)
    runner = CompareRunner([cls(o) for o in overrides], events, keep_all_times=True)
    n = compare_steps(cls, overrides, steps, seconds)
    inst = extras.instruments(extras.csv, True, n * runner.tick)
    if inst is not None:
        inst.attach(runner.runners, [v.text for v in variants], per_step=True)
    start = time.perf_counter()
    clip = None
    if video:
        clip = record_clip(runner.scenes[0], n, None, video, fps, width, clean, runner=runner,
                           inst=inst, compare=True)[1]
    else:
        runner.run(n)
    wall = time.perf_counter() - start
    late = runner.events_left
    if late:
        print(f"{cls.name}: {len(late)} --input event(s) not delivered: the last tick starts at "
              f"t = {max(runner.clock - runner.tick, 0.0):g} s and the first of them is due at "
              f"t = {late[0].t:g} s; give more --steps or --seconds", file=sys.stderr)
    names = labels(runner.scenes)
    results = []
    for k, (r, v) in enumerate(zip(runner.runners, variants)):
        result = {"variant": v.text, "pane": TAGS[k], "label": names[k], **summary(r, wall)}
        result["events"] = runner.next_event
        err = r.scene.reference_error()
        result["reference_error"] = None if err is None else \
            {"what": err[0], "metric": err[1], "value": json_clean(err[2])}
        if card is not None:
            result["try"] = card_json(card)
        results.append(result)
    unsaved = False
    shared_out: dict = {}
    if video:
        unsaved = not note_clip(shared_out, clip, cls.name)
    if screenshot:
        unsaved = not save_screenshot(screenshot, cls.name, shared_out, runner.runners, inst,
                                      True, width, clean) or unsaved
    for result in results:
        result.update({k: list(v) if k == "_replaced" else v for k, v in shared_out.items()})
    if inst is not None and inst.csv is not None:
        unsaved = not finish_csv(inst, results, extras.csv, cls.name) or unsaved
    for result in results:
        note_replaced(result)
    nonfinite = False
    for r, v, result in zip(runner.runners, variants, results):
        print(json.dumps(result, allow_nan=False) if as_json else
              f"[{result['pane']}] {v.text}\n" + describe(result), flush=True)
        nonfinite = report_stop(r, f"{cls.name} [{v.text}]") or nonfinite
    return EXIT_NONFINITE if nonfinite else EXIT_USAGE if unsaved else EXIT_OK


__all__ = ["run_compare", "compare_steps"]
