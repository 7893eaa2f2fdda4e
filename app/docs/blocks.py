"""The generated parts of the docs, each made from the code that it describes.

Each function returns one block's Markdown. `BLOCKS` names them as the markers in docs/*.md do
(`<!-- generated: NAME ... -->`). Nothing here reads the docs; app/docs/__main__.py puts the
blocks in place.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import re
import tempfile
from pathlib import Path
from typing import Any, Callable, Iterable

from app.docs.texts import METRICS, SUMMARY_FIELDS


class DocsError(Exception):
    """The code reports something the docs' texts (app/docs/texts.py) do not describe, or the
    other way round."""


def cell(text: Any) -> str:
    """Text for a Markdown table cell: '|' escaped, no line breaks."""
    return " ".join(str(text).split()).replace("|", "\\|")


def table(headers: Iterable[str], rows: Iterable[Iterable[Any]]) -> str:
    headers = list(headers)
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def number(x: Any) -> str:
    """A default or a bound as the command line takes it."""
    if isinstance(x, bool):
        return "on" if x else "off"
    if isinstance(x, float) and x.is_integer() and abs(x) < 1e15:
        return f"{x:.1f}"
    return str(x)


# ----- the key table ---------------------------------------------------------------------------
def keys() -> str:
    """The window's keys: app.keys.controls_table(), the one table the window reads."""
    from app.keys import controls_table
    return controls_table()


# ----- the command-line options ------------------------------------------------------------------
def _spelling(action: argparse.Action) -> str:
    if not action.option_strings:                        # a positional argument
        name = action.metavar or action.dest.upper()
        return f"`[{name}]`" if action.nargs == "?" else f"`{name}`"
    option = max(action.option_strings, key=len)
    if action.nargs == 0:                                # a switch (store_true)
        return f"`{option}`"
    metavar = action.metavar or action.dest.upper()
    if action.nargs == "+":
        return f"`{option} {metavar} {metavar} ...`"
    return f"`{option} {metavar}`"


def _option_rows(parser: argparse.ArgumentParser) -> list[tuple[str, str]]:
    exclusive = {a: g for g in parser._mutually_exclusive_groups for a in g._group_actions}
    rows = []
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        text = action.help or ""
        default = action.default
        if (default not in (None, False, [], argparse.SUPPRESS) and "default" not in text):
            text += f" (default {number(default)})"
        if action in exclusive:
            others = [max(a.option_strings, key=len) for a in exclusive[action]._group_actions
                      if a is not action]
            text += "; not with " + ", ".join(f"`{o}`" for o in others)
        rows.append((_spelling(action), text))
    return rows


def options() -> str:
    """Every option of `python -m app`, `bench` and `exercise`, from their argparse parsers."""
    from app.__main__ import build_bench_parser, build_exercise_parser, build_parser
    from app.bench import BENCHMARKS
    from app.exercises import exercise_names
    parts = ["`python -m app [options]`: " + build_parser().description,
             table(["option", "what it does"], _option_rows(build_parser()))]
    bench = build_bench_parser(list(BENCHMARKS) + ["all"])
    parts += [f"`python -m app bench [which] [options]`: {bench.description}",
              table(["option", "what it does"], _option_rows(bench))]
    exercise = build_exercise_parser(exercise_names())
    parts.append(f"`python -m app exercise list|check|copy`: {exercise.description}")
    sub = next(a for a in exercise._actions if isinstance(a, argparse._SubParsersAction))
    helps = {c.dest: c.help for c in sub._choices_actions}
    for name, parser in sub.choices.items():
        rows = _option_rows(parser)
        title = f"`python -m app exercise {name}`: {helps[name]}"
        parts.append(title + ("" if rows else " (no options)"))
        if rows:
            parts.append(table(["option", "what it does"], rows))
    return "\n\n".join(parts)


# ----- the scene catalogue ---------------------------------------------------------------------
def _accepted(p: dict[str, Any]) -> str:
    if "choices" in p:
        return ", ".join(f"`{number(c)}`" for c in p["choices"])
    if "range" in p:
        lo, hi = p["range"]
        return f"{number(lo)} to {number(hi)}"
    return "on, off"


def scenes() -> str:
    """Every scene: summary, parameters, effects, try cards and comparison cards, from the
    catalogue that `python -m app --list --json` prints (app/catalogue.py)."""
    from app.catalogue import catalogue
    from scenes import SCENES
    parts = []
    for s in catalogue(list(SCENES)):
        parts.append(f"### `{s['name']}`: {s['title']}\n\n{s['summary']} "
                     f"(menu: {s['category']}; metrics: [below](#metrics-{s['name']}))")
        parts.append(table(
            ["parameter", "default", "accepted", "changes", "what it sets"],
            [(f"`{p['name']}`", f"`{number(p['default'])}`", _accepted(p),
              "live" if p["live"] else "rebuilds", p["help"]) for p in s["params"]]))
        if s["effects"]:
            parts.append(table(
                ["effect", "default", "what it simulates"],
                [(f"`{e['name']}`", e["default"], e["help"] +
                  (f" (strength: `{e['strength']}`)" if e["strength"] else ""))
                 for e in s["effects"]]))
        if s["tries"]:
            parts.append(table(
                ["try card (`--try`)", "sets", "watch for"],
                [(c["label"], ", ".join(f"{k}={number(v)}" for k, v in c["settings"].items()),
                  c["watch"]) for c in s["tries"]]))
        if s["comparisons"]:
            parts.append(table(
                ["comparison card (`--try`)", "panes (`--compare`)", "watch for"],
                [(c["label"], " vs ".join(f"`{v}`" for v in c["compare"]) +
                  "".join(f", {k}={number(v)}" for k, v in c["settings"].items()), c["watch"])
                 for c in s["comparisons"]]))
    return "\n\n".join(parts)


# ----- the metrics -------------------------------------------------------------------------------
def _reported(cls) -> list[str]:
    """The metric names a scene reports, after one step at its defaults."""
    scene = cls()
    scene.advance()
    return list(scene.metrics())


def _pattern(scene: str, name: str) -> str:
    """The integrator lab reports one set per integrator: `rk4_error` is `<integrator>_error`."""
    if scene != "integrators":
        return name
    from app.physics.integrators import INTEGRATORS
    for integrator in sorted(INTEGRATORS, key=len, reverse=True):
        if name.startswith(integrator + "_"):
            return "<integrator>" + name[len(integrator):]
    return name


def _on_screen(unit) -> str:
    if unit is None:
        return "as in JSON"
    if unit.symbol == "%" and math.isclose(unit.factor, 100.0):
        return "%"
    if math.isclose(unit.factor, 1.0):
        return unit.symbol
    if unit.factor < 1.0:
        return f"{unit.symbol} (JSON / {1.0 / unit.factor:.6g})"
    return f"{unit.symbol} (JSON x {unit.factor:.6g})"


def metrics() -> str:
    """Every scene's metrics: the names the scene reports (run for one step), their JSON units and
    meaning (app/docs/texts.py), and the unit the HUD writes them in (the scene's
    metric_units)."""
    from scenes import SCENES
    parts = []
    for cls in SCENES:
        described = METRICS.get(cls.name, {})
        names = list(dict.fromkeys(_pattern(cls.name, n) for n in _reported(cls)))
        missing = [n for n in names if n not in described]
        stale = [n for n in described if n not in names]
        if missing or stale:
            raise DocsError(f"{cls.name}: metrics without a description in app/docs/texts.py: "
                            f"{missing}; described but not reported: {stale}")
        units = {_pattern(cls.name, k): u for k, u in cls.metric_units.items()}
        rows = [(f"`{n}`", described[n][0], _on_screen(units.get(n)), described[n][1])
                for n in names]
        parts.append(f"<a id=\"metrics-{cls.name}\"></a>**`{cls.name}`**\n\n" +
                     table(["metric", "JSON unit", "on screen", "meaning"], rows))
    return "\n\n".join(parts)


# ----- the --json summary ----------------------------------------------------------------------
def _json_objects(argv: list[str]) -> list[dict[str, Any]]:
    from app.__main__ import main
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = main(argv)
    if code != 0:
        raise DocsError(f"python -m app {' '.join(argv)} exited {code}")
    decoder, text, at, objects = json.JSONDecoder(), out.getvalue(), 0, []
    while text[at:].strip():
        at += len(text[at:]) - len(text[at:].lstrip())
        obj, at = decoder.raw_decode(text, at)
        objects.append(obj)
    return objects


def summary_fields() -> str:
    """The fields of a --json summary: those a run, a comparison and a clip actually print,
    described in app/docs/texts.py."""
    run = ["--headless", "--scene", "falling_balls", "--steps", "1", "--json"]
    with tempfile.TemporaryDirectory() as tmp:
        clip = str(Path(tmp) / "clip.gif")
        seen = [*_json_objects(run),
                *_json_objects(run + ["--compare", "g=900", "g=450"]),
                *_json_objects(run + ["--video", clip, "--width", "160"])]
    names = list(dict.fromkeys(k for obj in seen for k in obj))
    missing = [n for n in names if n not in SUMMARY_FIELDS]
    stale = [n for n in SUMMARY_FIELDS if n not in names]
    if missing or stale:
        raise DocsError(f"--json fields without a description in app/docs/texts.py: {missing}; "
                        f"described but not printed: {stale}")
    return table(["field", "what it holds"], [(f"`{n}`", SUMMARY_FIELDS[n])
                                               for n in SUMMARY_FIELDS])


# ----- exercises and benchmarks ----------------------------------------------------------------
def exercises() -> str:
    """The exercises (the registry app/exercises/__init__.py): name, title, slide and the
    settings its scene takes with --set."""
    from app.exercises import EXERCISES, scene_class
    common = {"hertz", "substeps", "seed"}
    rows = []
    for e in EXERCISES:
        own = [f"{p.name}={number(p.default)}" for p in scene_class(e.name).all_params()
               if p.name not in common]
        rows.append((f"`{e.name}`", e.title, e.slide, ", ".join(own) or "-"))
    return table(["exercise", "what you write", "from the slide", "its scene's own settings"],
                 rows)


def benchmarks() -> str:
    """The benchmarks (app.bench.BENCHMARKS) with the first line of each module's docstring."""
    import importlib
    from app.bench import BENCHMARKS
    rows = []
    for name, module in BENCHMARKS.items():
        doc = (importlib.import_module(module).__doc__ or "").strip().split("\n\n")[0]
        what = re.sub(r"`python -m app bench \w+`", "", " ".join(doc.split())).strip(" :.")
        rows.append((f"`{name}`", what[:1].upper() + what[1:] + "."))
    return table(["benchmark", "what it measures"], rows)


# ----- scene files ---------------------------------------------------------------------------
def scene_format() -> str:
    """The scene-file format: every section and key from the one schema the loader checks files
    against (app/scenefile/schema.py), the metric kinds and the fields a slider may set."""
    from app.scenefile.schema import METRIC_HELP, SCHEMA, slider_fields
    parts = []
    for sec in SCHEMA:
        head = f"[[{sec.name}]]" if sec.many else f"[{sec.name}]"
        how = ("required" if sec.required else "as many as you like" if sec.many
               else "optional")
        parts.append(f"#### `{head}`\n\n{sec.help[:1].upper() + sec.help[1:]} ({how}).")
        parts.append(table(["key", "default", "accepted", "what it sets"],
                           [(f"`{k.name}`", k.default_text(), k.accepted(), k.help)
                            for k in sec.keys]))
    parts.append("#### Metric kinds (`kind` of a `[[metric]]`)")
    parts.append(table(["kind", "JSON unit", "`target` names", "what it measures"],
                       [(f"`{kind}`", unit, owner, what)
                        for kind, (unit, owner, what) in METRIC_HELP.items()]))
    parts.append("#### What a slider's `field` may point at\n\n"
                 + ", ".join(f"`{f}`" for f in slider_fields()) + ".")
    return "\n\n".join(parts)


def scene_files() -> str:
    """The shipped scene files (scenes/__init__.py SCENE_FILES): path, title, sliders, cards."""
    from scenes import file_scenes
    rows = []
    for cls in file_scenes():
        sliders = ", ".join(f"`{s['name']}`" for s in cls.spec["slider"]) or "-"
        cards = ", ".join(c.label for c in cls.tries + cls.comparisons) or "-"
        rows.append((f"[{cls.name}](../{cls.name})", cls.title, sliders, cards))
    return table(["file", "title", "its own sliders", "try cards"], rows)


BLOCKS: dict[str, Callable[[], str]] = {
    "keys": keys,
    "options": options,
    "summary-fields": summary_fields,
    "scenes": scenes,
    "metrics": metrics,
    "exercises": exercises,
    "benchmarks": benchmarks,
    "scene-format": scene_format,
    "scene-files": scene_files,
}
