"""Checks of the command line's compare mode and instruments (--compare, --try with a comparison
card, --csv, --plot, --arrows), before anything runs: each refusal is one line (UsageError) and
exit code 2, as every bad usage (app/__main__.py)."""

from __future__ import annotations

import argparse

from app.scene import shown_text


class UsageError(Exception):
    """Bad usage: the message is the one line printed on stderr."""


def compare_variants(args: argparse.Namespace, classes: list, overrides: dict, card):
    """The shared settings and the variants of a comparison (--compare, or a comparison card),
    checked as --set is; UsageError (one line) if they are refused."""
    from app.compare import Variant, parse_variant, resolve_variants
    from app.scene import ParamError, variant_text
    if len(classes) != 1:
        raise UsageError("--compare needs --scene NAME (one scene, run side by side at each "
                         "variant's settings)")
    cls = classes[0]
    if card is not None and args.compare is not None:
        raise UsageError("--try gives the settings itself (a comparison card, its variants too); "
                         "drop --compare, or give the variants without --try")
    try:
        if card is not None:
            shared = dict(card.settings)
            variants = [Variant(variant_text(v), dict(v)) for v in card.compare]
        else:
            shared, variants = overrides, [parse_variant(t) for t in args.compare]
        resolve_variants(cls, shared, variants)
    except ParamError as e:
        raise UsageError(f"--compare: {cls.name}: {e}") from None
    return shared, variants


def instrument_problem(args: argparse.Namespace, classes: list) -> None:
    """Refuse (UsageError) instruments that do not fit the run."""
    if args.headless and (args.arrows or args.plot) and not (args.screenshot or args.video):
        what = "--arrows" if args.arrows else "--plot"
        raise UsageError(f"{what} draws into --screenshot and --video when headless; give one "
                         "(or --csv FILE for the numbers)")
    if args.plot is not None and len(classes) != 1:
        raise UsageError("--plot needs --scene NAME (the metrics belong to a scene)")
    if (args.csv is not None or args.arrows) and not classes:
        raise UsageError(f"{'--csv' if args.csv is not None else '--arrows'} needs --scene NAME")


def check_plot(text: str | None, classes: list, shared: dict) -> list[str]:
    """The metrics --plot names, checked against what the scene reports (it is built once to
    ask it); UsageError naming the accepted ones."""
    if text is None:
        return []
    names = [n.strip() for n in text.split(",")]
    if not all(names):
        raise UsageError(f"--plot {shown_text(text)}: accepted: METRIC[,METRIC...], e.g. "
                         "--plot max_stretch,mean_stretch")
    from app.outputs import listed
    from app.series import plottable
    cls = classes[0]
    accepted = list(plottable(cls(cls.own_settings(shared)).metrics()))
    unknown = [n for n in names if n not in accepted]
    if unknown:
        raise UsageError(f"--plot {shown_text(unknown[0])}: {cls.name} reports no such number; "
                         "accepted: " + listed(accepted, unknown[0],
                                               rest="all in docs/scenes.md"))
    return list(dict.fromkeys(names))


def scene_file_path(name: str) -> str:
    """The file --scene NAME.toml reads: NAME from here, or a shipped file by its path from the
    repository's root (scenes.file_scene)."""
    import os
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return name if os.path.exists(name) else os.path.join(root, name)


def check_outputs(args: argparse.Namespace, classes: list, clips: list[str]) -> None:
    """Refuse (UsageError, one line) before the run: one path named for two outputs, an output
    that is also an input (--input, the exercise file), and an output that cannot be written
    (a folder, a FIFO, a device, a folder that cannot be made). `clips`: the --video files."""
    from app.headless import check_output_path, screenshot_path
    from app.outputs import clash
    several = len(classes) > 1
    shots = [screenshot_path(args.screenshot, c.name, several) for c in classes
             if args.headless and args.screenshot]     # the names the run will write
    tables = [screenshot_path(args.csv, c.name, several) for c in classes
              if args.csv and several]
    outputs = [*((s, "--screenshot") for s in (shots or [args.screenshot])),
               (args.record, "--record"), *((t, "--csv") for t in (tables or [args.csv])),
               *((clip, "--video") for clip in clips)]
    outputs = [o for o in outputs if o[0] is not None]
    inputs = [(args.input, "--input")]
    if args.scene and args.scene.startswith("exercise:") and args.scene.endswith(".py"):
        inputs.append((args.scene.removeprefix("exercise:"), "the exercise file"))
    if args.scene and args.scene.endswith(".toml"):     # a scene file is read: never written
        inputs.append((scene_file_path(args.scene), "the scene file"))
    problem = clash([o for o in outputs if o[0]], [i for i in inputs if i[0]])
    if problem:                       # before anything is written: nothing is lost
        raise UsageError(problem)
    for path, what in outputs:
        problem = check_output_path(path, what)
        if problem:
            raise UsageError(problem)
