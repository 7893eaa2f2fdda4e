"""The headless runner behind `--headless`: the same scene code as the window, no window.

It builds a scene, replays timed input events, advances a fixed number of steps, times every step
(drawing excluded), watches that the state stays finite, and reports a summary (the JSON object of
DESIGN.md). It is also the engine of the determinism tests: two runs with the same arguments give
the same `state_hash`.
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from app.clips import Clip
from app.outputs import OutputError, input_problem, one_line, output_problem, shown
from app.runner import SceneRunner, advice, deliver, run_scene   # noqa: F401 (deliver: for importers)
from app.scene import InputEvent, Scene, SceneError, Try
from app.series import MAX_WINDOW, clean

if TYPE_CHECKING:
    from app.instruments import Instruments

EVENT_TYPES = ("mouse_down", "mouse_up", "mouse_move", "key_down", "key_up", "edit", "save",
               "open")
MAX_FORM_TEXT = 200             # characters of an "edit" value or a "save" name (a panel's text box)
DEFAULT_SECONDS = 5.0
EXIT_OK, EXIT_NONFINITE, EXIT_USAGE = 0, 1, 2       # the command line's exit codes (DESIGN.md)
MAX_STEPS = 1_000_000           # a headless run longer than this is a typo, not an experiment
MAX_INPUT_BYTES = 64 * 2**20    # an --input file (an hour of recorded mouse moves is ~10 MB);
                                # read at most this much: /dev/zero or an endless pipe never ends


class InputFileError(ValueError):
    """An --input file that cannot be read or does not follow the format (one-line message)."""


def _json_kind(value: Any) -> str:
    """What a decoded JSON value is, in JSON's words (messages never name Python types)."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    return "a list" if isinstance(value, list) else "an object"


def _shown(value: Any) -> str:
    """A short JSON rendering of a value for a message (cut to 40 characters)."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10 ** 20:
        return f"a {len(str(abs(value)))}-digit integer"
    try:
        text = json.dumps(value)
    except (TypeError, ValueError, RecursionError):
        text = _json_kind(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _finite_number(value: Any) -> float | None:
    """value as a float if it is a JSON number (not true/false) that a float can hold (a
    400-digit integer cannot: float() and math.isfinite would raise OverflowError)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    if isinstance(value, int) and value.bit_length() > 1023:
        return None
    number = float(value)
    return number if math.isfinite(number) else None


def parse_events(data: Any, source: str = "input") -> list[InputEvent]:
    """Validate a decoded --input document (a list of event objects); return the events sorted
    by time. Raises InputFileError naming the first problem (in JSON's words: a missing field is
    'missing', a wrong one is shown as written)."""
    if not isinstance(data, list):
        raise InputFileError(f"{source}: expected a JSON list of events, got {_json_kind(data)}")
    events = []
    for i, item in enumerate(data):
        where = f"{source}: event {i}"
        if not isinstance(item, dict):
            raise InputFileError(f"{where}: expected an object like "
                                 '{"t": 0.5, "type": "mouse_down", "button": 1, "pos": [x, y]}, '
                                 f"got {_json_kind(item)}")

        def bad(field: str, wanted: str) -> InputFileError:
            got = "it is missing" if field not in item else f"got {_shown(item[field])}"
            return InputFileError(f"{where}: '{field}' must be {wanted}; {got}")

        t = _finite_number(item.get("t"))
        if t is None or t < 0:
            raise bad("t", "a finite number of seconds >= 0")
        kind = item.get("type")
        if kind not in EVENT_TYPES:
            raise bad("type", f"one of {', '.join(EVENT_TYPES)}")
        if kind.startswith("mouse"):
            pos = item.get("pos")
            xy = [_finite_number(v) for v in pos] if isinstance(pos, list) and len(pos) == 2 else []
            if len(xy) != 2 or None in xy:
                raise bad("pos", "[x, y], two finite numbers")
            button = item.get("button", 0 if kind == "mouse_move" else None)
            allowed = (0, 1, 2, 3) if kind == "mouse_move" else (1, 2, 3)
            if isinstance(button, bool) or button not in allowed:
                raise bad("button", "1 (left), 2 or 3 (right)")
            events.append(InputEvent(kind, (xy[0], xy[1]), int(button or 0), t=t))
        elif kind == "edit":            # a field of the scene's panel form (app/form.py)
            field, value = item.get("field"), item.get("value")
            if not isinstance(field, str) or not field or len(field) > 40:
                raise bad("field", 'the name of a field of the panel, such as "mass"')
            if not isinstance(value, str) or len(value) > MAX_FORM_TEXT:
                raise bad("value", f"the text typed, in quotes (at most {MAX_FORM_TEXT} "
                          "characters)")
            events.append(InputEvent(kind, field=field, value=value, t=t))
        elif kind in ("save", "open"):  # the name typed at the panel's prompt ("" cancels)
            name = item.get("name")
            if not isinstance(name, str) or len(name) > MAX_FORM_TEXT:
                raise bad("name", f"the name typed, in quotes (at most {MAX_FORM_TEXT} "
                          "characters; \"\" cancels)")
            events.append(InputEvent(kind, value=name, t=t))
        else:
            key = item.get("key")
            if not isinstance(key, str) or not key:
                raise bad("key", 'a key name such as "r"')
            events.append(InputEvent(kind, key=key, t=t))
    events.sort(key=lambda e: e.t)   # stable: simultaneous events keep their order
    return events


def load_events(path: str, classes: list | None = None) -> list[InputEvent]:
    """Read and validate an --input file (for `classes`: panel events only for scenes with a
    panel form, app/form.py)."""
    if not path.strip():
        raise InputFileError("--input needs a file name (a JSON list of events)")
    problem = input_problem(path, "--input")     # a FIFO would block for ever: refused first
    if problem:
        raise InputFileError(problem)
    path_text = shown(path)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read(MAX_INPUT_BYTES + 1)
        data = json.loads(text) if len(text) <= MAX_INPUT_BYTES else None
    except OSError as e:
        raise InputFileError(f"cannot read --input file {path_text}: {e.strerror or shown(str(e))}") from None
    except RecursionError:
        raise InputFileError(f"--input file {path_text} nests lists or objects too deeply; accepted: "
                             "a flat list of event objects") from None
    except UnicodeDecodeError as e:
        raise InputFileError(f"--input file {path_text} is not UTF-8 text ({e.reason})") from None
    except json.JSONDecodeError as e:
        raise InputFileError(f"--input file {path_text} is not valid JSON: {e.msg} (line {e.lineno}, column {e.colno})") from None
    except ValueError:           # e.g. an integer of more than 4300 digits (Python's own limit)
        raise InputFileError(f"--input file {path_text} holds a number too long to read (over 4300 "
                             "digits); accepted: numbers of at most 300 digits") from None
    if len(text) > MAX_INPUT_BYTES:
        raise InputFileError(f"--input file {path_text} is larger than {MAX_INPUT_BYTES >> 20} MB; "
                             "accepted: a JSON list of events up to that size")
    events = parse_events(data, f"--input file {path_text}")
    form = next((e for e in events if e.kind in ("edit", "save", "open")), None)
    plain = [c.name for c in classes or () if c.panel_form is Scene.panel_form]
    if form is not None and plain:
        raise InputFileError(f"--input file {path_text}: the event \"{form.kind}\" (t = {form.t:g}) "
                             f"is typed into a scene's own panel fields, and {plain[0]} has none; "
                             "accepted: such events for the sandbox (or a scene with a form)")
    return events


def summary(runner: SceneRunner, wall_seconds: float) -> dict[str, Any]:
    """The JSON summary object of DESIGN.md for a finished run (plus "error" when the scene
    raised SceneError)."""
    s = runner.scene
    median = runner.step_times.median() if runner.step_times is not None else None
    out = {
        "scene": s.name,
        "steps": runner.steps,
        "sim_seconds": round(runner.steps * s.dt, 9),
        "wall_seconds": round(wall_seconds, 6),
        "step_ms": round(median * 1000, 6) if median is not None else None,   # None: no step
        "params": clean(s.p),
        "effects": sorted(s.on),
        "metrics": clean(s.metrics()),
        "state_hash": s.state_hash(),
        "finite": runner.finite,
        "events": runner.next_event,
        "error": runner.error,          # a SceneError's message (a student's exception), or None
    }
    return out


json_clean = clean    # run_headless's `clean` (a clip without HUD) hides this name there


def frame(runners: list, width: int | None = None, clean: bool = False, inst=None,
          compare: bool = False):
    """What a screenshot shows, as a pygame Surface: the scene's current frame (or every pane
    of a comparison), with its own drawing code and the window's HUD (less fps, which a headless
    run has none of) laid out as the window lays them out (the HUD off the scene's content), the
    plot strip and the arrows if `inst` has them on; `clean` leaves HUD and metrics out. Drawn
    `width` px wide (text scaled with it; default: the world's width), not scaled afterwards, so
    a large frame stays sharp. Screenshots (render) and clips (record_clip) both take their
    pictures here (app/frames.py: picture)."""
    from app.frames import picture
    return picture(runners, inst, compare, width, clean)


def render(runners: list, path: str, width: int | None = None, clean: bool = False, inst=None,
           compare: bool = False) -> None:
    """Save frame() as a PNG (whole or not at all: app/outputs.py). Raises OutputError (one
    line) if it cannot."""
    from app.draw import save_png
    save_png(frame(runners, width, clean, inst, compare), path, what="--screenshot")


def steps_for(seconds: float | None, dt: float) -> int:
    """Fixed steps in `seconds` of simulated time (DEFAULT_SECONDS if None), at least one."""
    return max(1, round((seconds or DEFAULT_SECONDS) / dt))


def check_output_path(path: str, what: str) -> str | None:
    """None if a file can be written at `path`, else a one-line reason (checked before a run, so
    a long run is not lost to a typo in the output path): app.outputs.output_problem, and a
    screenshot's name must end in .png."""
    if path.strip() and what == "--screenshot" and not path.lower().endswith(".png"):
        return f"{what} {shown(path)}: accepted: a file name ending in .png"
    return output_problem(path, what)


def screenshot_path(screenshot: str, scene_name: str, several: bool) -> str:
    """Where a run saves a scene's screenshot: OUT.png, or OUT-<scene>.png with several scenes."""
    if not several:
        return screenshot
    root, ext = os.path.splitext(screenshot)
    return f"{root}-{scene_name}{ext}"


@dataclass
class Extras:
    """The instruments asked for on the command line: --csv FILE, --arrows, --plot M1,M2."""
    csv: str | None = None
    arrows: bool = False
    plot: tuple[str, ...] = ()

    def instruments(self, csv_path: str | None, compare: bool,
                    seconds: float) -> "Instruments | None":
        """The run's instruments (None if none is asked for): the plot's window is the whole
        run, up to its longest; the CSV is opened at `csv_path`."""
        if not (self.csv or self.arrows or self.plot):
            return None
        from app.instruments import Instruments      # pygame: only when drawing is asked for
        inst = Instruments(self.plot, window=min(max(seconds, 1e-3), MAX_WINDOW),
                           arrows=self.arrows)
        if csv_path:
            inst.open_csv(csv_path, compare, warn=lambda text: print(text, file=sys.stderr))
        return inst


def run_headless(scene_classes: list[type[Scene]], overrides: dict[str, str], steps: int | None,
                 seconds: float | None, events: list[InputEvent] | None, screenshot: str | None,
                 as_json: bool, card: Try | None = None, extras: Extras | None = None,
                 video: str | None = None, fps: int | None = None, width: int | None = None,
                 clean: bool = False) -> int:
    """Run each scene in turn; print one JSON object per scene (or a readable summary). With
    `card` (--try) the one scene gets the card as a click gives it (Scene.apply_card); with
    `extras` the CSV, the plot and the arrows (app/instruments.py). With `video`, record a clip
    of each run (app/clips.py) at `fps`, `width` px wide."""
    from app.progress import Progress
    nonfinite = unsaved = False
    extras = extras or Extras()
    several = len(scene_classes) > 1
    bar = Progress(len(scene_classes) if several else 0, "scenes", "scenes")
    for cls in scene_classes:
        bar.update(0, note=cls.name)
        scene = cls(cls.own_settings(overrides))
        if card is not None:
            scene.apply_card(card)
        n = steps if steps is not None else steps_for(seconds, scene.dt)
        csv_path = screenshot_path(extras.csv, scene.name, several) if extras.csv else None
        inst = extras.instruments(csv_path, False, n * scene.dt)
        start = time.perf_counter()
        runner = SceneRunner(scene, events, keep_all_times=True)
        if inst is not None:
            inst.attach([runner], per_step=True)
        if video:
            clip = record_clip(scene, n, events, screenshot_path(video, scene.name, several),
                               fps, width, clean, runner=runner, inst=inst)[1]
        else:
            runner.run(n)
        result = summary(runner, time.perf_counter() - start)
        if card is not None:
            result["try"] = card_json(card)
        if video:
            unsaved = not note_clip(result, clip, scene.name) or unsaved
        late = runner.events_left
        if late:
            last = max(runner.clock - scene.dt, 0.0)   # an event is delivered before a step
            print(f"{scene.name}: {len(late)} --input event(s) not delivered: the last step "
                  f"starts at t = {last:g} s and the first of them is due at t = {late[0].t:g} s; "
                  f"give more --steps or --seconds", file=sys.stderr)
        if screenshot:
            path = screenshot_path(screenshot, scene.name, several)
            unsaved = not save_screenshot(path, scene.name, result, [runner], inst, width=width,
                                          clean=clean) or unsaved
        if inst is not None and inst.csv is not None:
            unsaved = not finish_csv(inst, [result], csv_path, scene.name) or unsaved
        note_replaced(result)
        if as_json:
            print(json.dumps(result, allow_nan=False), flush=True)
        else:
            print(describe(result), flush=True)
        nonfinite = report_stop(runner, scene.name) or nonfinite
        bar.update(1)
    bar.close()
    # a run that went non-finite says so first; a screenshot that could not be saved is bad usage
    return EXIT_NONFINITE if nonfinite else EXIT_USAGE if unsaved else EXIT_OK


def note_clip(result: dict, clip: Any, name: str) -> bool:
    """Put the clip written (or null) in `result`: its frames and seconds as counted back from
    the file; False (and a line on stderr) if it was not written."""
    done = isinstance(clip, Clip)
    result.update(video=clip.path if done else None, video_frames=clip.frames if done
                  else None, video_seconds=round(clip.seconds, 6) if done else None,
                  video_bytes=clip.bytes if done else None)
    if done and clip.replaced:
        result.setdefault("_replaced", []).append(clip.path)
    if not done:
        print(f"python -m app: error: {name}: {clip}", file=sys.stderr)
    return done


def finish_csv(inst: Any, results: list[dict], path: str, name: str) -> bool:
    """Close the run's --csv file (renamed into place) and note it in each result; False (and
    one line on stderr) if it could not be written."""
    rows = inst.csv.rows
    try:
        replaced = inst.close_csv()
    except OutputError as e:
        print(f"python -m app: error: {name}: {e}", file=sys.stderr)
        for result in results:
            result.update(csv=None, csv_rows=None)
        return False
    for result in results:
        result.update(csv=path, csv_rows=rows)
        if replaced:
            result.setdefault("_replaced", []).append(path)
    return True


def note_replaced(result: dict) -> None:
    """`replaced`: the outputs of this run that replaced a file that was there (the summary
    says so; an empty list if none did). Only in a run that writes a file."""
    written = result.pop("_replaced", [])
    if any(result.get(k) is not None for k in ("video", "screenshot", "csv")) or written:
        result["replaced"] = written


def card_json(card: Try) -> dict[str, Any]:
    out = {"label": card.label, "settings": json_clean(dict(card.settings)), "watch": card.watch}
    if card.compare:
        out["compare"] = [json_clean(dict(v)) for v in card.compare]
    return out


def save_screenshot(path: str, name: str, result: dict, runners: list, inst,
                    compare: bool = False, width: int | None = None, clean: bool = False) -> bool:
    """Render and save the screenshot; note it in `result`; False (and a line on stderr) if it
    could not be saved."""
    existed = os.path.exists(path)
    try:
        render(runners, path, width, clean, inst, compare)
        result["screenshot"] = path
        if existed:
            result.setdefault("_replaced", []).append(path)
        return True
    except OutputError as e:
        print(f"python -m app: error: {name}: {e}", file=sys.stderr)
        result["screenshot"] = None
        return False


def report_stop(runner: SceneRunner, name: str) -> bool:
    """Say on stderr why a run stopped early, if it did; True if it did (exit code 1)."""
    scene = runner.scene
    if runner.error is not None:       # a student's code failed: say where, go on with the
        print(f"{name}: {runner.error}\n(stopped at step {runner.steps + 1})",
              file=sys.stderr)         # next scene, exit 1 (like a run that went non-finite)
        return True
    if not runner.finite:
        print(f"{name}: the simulation went non-finite (NaN or inf, or past the scene's "
              f"blow-up bounds) at step {runner.steps} (t = {runner.steps * scene.dt:.3f} s). "
              f"{advice(scene)}", file=sys.stderr)
        return True
    return False


def record_clip(scene: Scene, steps: int, events: list[InputEvent] | None, path: str,
                fps: int | None, width: int | None, clean: bool, runner=None, inst=None,
                compare: bool = False) -> tuple[Any, Any]:
    """Run `steps` steps of `scene` (as run_scene; or of `runner`, a SceneRunner or a
    comparison's CompareRunner) while recording a clip of frame() to `path`; return the runner
    and the Clip written, or a one-line message if it was not."""
    from app.clips import DEFAULT_FPS, DEFAULT_WIDTH, frame_count, open_clip, record_run
    from app.frames import picture_size
    from app.progress import Progress
    fps = fps or DEFAULT_FPS
    runner = runner or SceneRunner(scene, events, keep_all_times=True)
    runners = runner.runners if compare else [runner]
    plotting = inst is not None and bool(inst.plot)
    size = picture_size(scene, width or DEFAULT_WIDTH, clean, compare, plotting)
    try:
        writer = open_clip(path, size, fps, what="--video")
    except OutputError as e:
        runner.run(steps)
        return runner, str(e)
    dt = runner.tick if compare else scene.dt
    try:
        with Progress(frame_count(steps, dt, fps), f"{scene.name}: clip", "frames") as bar:
            try:
                record_run(runner, steps, fps,
                           lambda: frame(runners, size[0], clean, inst, compare), writer, bar)
                bar.update(0, note="encoding")
            except SceneError as e:        # a student's drawing code failed: the frames so far
                for r in runners:          # are the clip, the run stops (exit 1)
                    r.fail(e)
        return runner, writer.close()      # OutputError if the file is not whole
    except OutputError as e:
        return runner, str(e)
    except (OSError, RuntimeError, ValueError) as e:
        writer.abandon()
        return runner, writer.failed(e)
    except BaseException:                  # Ctrl-C: the old file stays as it was
        writer.abandon()
        raise


def describe(summary: dict[str, Any]) -> str:
    """A readable few lines for a run without --json."""
    from app.draw.hud import fmt_number
    metrics = ", ".join(f"{k}={fmt_number(v)}" for k, v in summary["metrics"].items())
    lines = [f"{summary['scene']}: {summary['steps']} steps, {summary['sim_seconds']:.3g} s simulated "
             f"in {summary['wall_seconds']:.3g} s, {fmt_number(summary['step_ms'])} ms/step, "
             f"finite={summary['finite']}, hash {summary['state_hash']}",
             f"  metrics: {metrics}"]
    if summary.get("try"):
        lines.append(f"  try: {summary['try']['label']}: watch: {summary['try']['watch']}")
    if summary.get("screenshot"):
        lines.append(f"  screenshot: {one_line(summary['screenshot'])}")
    if summary.get("csv"):
        lines.append(f"  csv: {one_line(summary['csv'])} ({summary['csv_rows']} rows)")
    if summary.get("video"):
        lines.append(f"  video: {one_line(summary['video'])} ({summary['video_frames']} frames, "
                     f"{summary['video_seconds']:.3g} s, {summary['video_bytes'] / 1e6:.2f} MB)")
    for path in summary.get("replaced") or ():
        lines.append(f"  replaced: {one_line(path)} (the file that was there)")
    if summary.get("error"):
        lines.append(f"  error: {summary['error'].splitlines()[-1]} (details on stderr)")
    return "\n".join(lines)

