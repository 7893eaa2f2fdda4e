"""The command line: `python -m app ...` (see docs/reference.md).

    python -m app                          window, scene menu
    python -m app --scene cloth            window, open one scene
    python -m app --list [--json]          one line per scene: name, title (--json: the catalogue)
    python -m app [--headless] --scene NAME --try LABEL    a "try this" card, as a click applies it
    python -m app --headless --scene NAME [--seconds S | --steps N] [--set KEY=VALUE]...
                  [--input EVENTS.json] [--screenshot OUT.png] [--json]
                  [--video OUT.gif|OUT.mp4 [--fps N]] [--width PX] [--clean]
    python -m app --headless --scene all   every scene in turn
    python -m app [--headless] --scene NAME --compare A B [C [D]]   variants side by side
    python -m app [--headless] ... [--csv FILE] [--plot M1,M2] [--arrows]   the instruments
    python -m app bench [cloth|integrators|pymunk|mass_spring|particles|clips|frames|all] [--json] [--out DIR] [--quick]
    python -m app exercise list | check NAME|all [--path P] [--reference] [--json] [--seed N] | copy DIR

Bad usage prints one line on stderr that names the problem and the accepted values, and exits 2.
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import NoReturn

from app.ctrl_c import interrupted_inside
from app.clips import DEFAULT_FPS, DEFAULT_WIDTH, check_video, frame_count
from app.headless import (EXIT_NONFINITE, EXIT_OK, EXIT_USAGE, MAX_STEPS, Extras,
                          InputFileError, check_output_path, load_events, run_headless,
                          screenshot_path, steps_for)
from app.cli_checks import (UsageError, check_outputs, check_plot, compare_variants,
                            instrument_problem)
from app.outputs import OutputError, discard_all, listed, one_line, shown
from app.scene import shown_text
from app.cli_args import (_Parser, _fps, _int_in, _positive_float, _positive_int, _seed,
                          _timeout, _width, _window_size, parse_sets, use_dummy_video)

def build_parser() -> argparse.ArgumentParser:
    # allow_abbrev=False: --scen is not --scene (a stable command line; docs/reference.md)
    p = _Parser(prog="python -m app", allow_abbrev=False, description="A classroom lab for "
                "physics in computer animation and games. Without options: a window with the "
                "scene menu.")
    p.add_argument("--scene", help="scene to open (see --list); 'all' with --headless")
    p.add_argument("--list", action="store_true", help="list the scenes: name, title; with "
                   "--json the catalogue (params, effects, try cards)")
    p.add_argument("--try", dest="card", metavar="LABEL", help="apply one of the scene's "
                   "\"try this\" cards (its defaults plus the card's settings), as a click does")
    p.add_argument("--headless", action="store_true", help="run without a window")
    length = p.add_mutually_exclusive_group()
    length.add_argument("--seconds", type=_positive_float, help="simulated seconds to run "
                        "(headless; default 5); with --screenshot in the window: wall seconds")
    length.add_argument("--steps", type=_positive_int, help="fixed steps to run (headless)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="set a parameter or effect (on/off); repeatable")
    p.add_argument("--input", metavar="EVENTS.json", help="replay timed mouse and key events")
    p.add_argument("--screenshot", metavar="OUT.png", help="save the last frame as a PNG")
    p.add_argument("--video", metavar="OUT.gif|OUT.mp4", help="headless: a clip of the run "
                   "(GIF, or MP4 with imageio-ffmpeg); window: where F9's clips go")
    p.add_argument("--fps", type=_fps, help=f"clip frames per simulated second, headless and "
                   f"F9 (default {DEFAULT_FPS})")
    p.add_argument("--width", type=_width, help=f"width in pixels of headless clips and "
                   f"screenshots and of F9's clips (default: clips {DEFAULT_WIDTH}, screenshots "
                   "the world's)")
    p.add_argument("--clean", action="store_true", help="headless: no HUD or metrics in "
                   "--screenshot and --video, cropped to the scene's content")
    p.add_argument("--json", action="store_true", help="print one JSON summary per scene")
    p.add_argument("--record", metavar="FILE", help="window: save your mouse and key events "
                   "in the --input format")
    p.add_argument("--large-text", action="store_true", help="window: start with large text")
    p.add_argument("--size", type=_window_size, metavar="WxH", help="window: its size in "
                   "pixels, e.g. 1920x1080 (default 1280x800; F11 comes back to it)")
    p.add_argument("--fullscreen", action="store_true", help="window: start full screen (F11 "
                   "toggles it)")
    p.add_argument("--compare", nargs="+", metavar="KEY=VALUE[,KEY=VALUE]", help="run 2 to 4 "
                   "variants of the scene side by side in lockstep (--set values are shared)")
    p.add_argument("--csv", metavar="FILE", help="write every metric over time: a row per step "
                   "(headless) or per frame (window), with a header")
    p.add_argument("--plot", metavar="METRIC[,METRIC]", help="plot these metrics over time "
                   "(window: at start, P picks others; headless: in --screenshot)")
    p.add_argument("--arrows", action="store_true", help="velocity and force arrows (window: "
                   "at start, V toggles; headless: in --screenshot)")
    return p


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    from app.physics.linear_solve import one_blas_thread
    one_blas_thread()           # threads only wait for a core here (measured: linear_solve.py)
    try:
        if argv and argv[0] == "bench":
            return bench_main(argv[1:])
        if argv and argv[0] == "exercise":
            return exercise_main(argv[1:])
        if argv and argv[0] == "scene":
            return scene_main(argv[1:])
        return app_main(argv)
    except (UsageError, OutputError) as e:    # bad usage, or a file that could not be written
        print(f"python -m app: error: {one_line(str(e), 278)}", file=sys.stderr)   # <= 300
        return EXIT_USAGE
    except BrokenPipeError:     # stdout closed early (`... --json | head -1`): stop quietly
        discard_all()
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())   # no error at exit
        return EXIT_OK
    except KeyboardInterrupt:   # Ctrl-C: one line, no traceback; no half-written file is left
        return interrupted()
    except Exception as e:      # a Ctrl-C some library wrapped in its own error: the same
        if interrupted_inside(e):
            return interrupted()
        raise


def interrupted() -> int:
    """Ctrl-C: remove the outputs being written (the files that were there stay as they were),
    say so in one line, exit code 130."""
    discard_all()
    try:
        print("python -m app: interrupted (Ctrl-C); no output was left half-written: files being "
              "written were not, and files that were there are as they were", file=sys.stderr,
              flush=True)
    except (OSError, ValueError):
        pass
    return EXIT_INTERRUPTED


EXIT_INTERRUPTED = 130          # 128 + SIGINT, as shells report it


def app_main(argv: list[str]) -> int:
    args = build_parser().parse_args(argv)
    from app.scene import ParamError
    from scenes import FINDERS, SCENES, get_scene, menu_scenes, scene_names
    from app.scenefile.load import SceneFileError
    if args.scene and args.scene.startswith("exercise:"):
        from app.exercises.live import exercise_scene    # the exercises' scenes, by name
        FINDERS["exercise"] = exercise_scene

    if args.list:
        if args.json:
            import json
            from app.catalogue import catalogue
            print(json.dumps(catalogue(menu_scenes()), indent=1))
            return EXIT_OK
        for cls in menu_scenes():       # the registry, then the shipped scene files (by path)
            print(f"{cls.name:18} {cls.title}")
        return EXIT_OK

    accepted = ", ".join(scene_names()) + ", exercise:NAME, PATH/FILE.toml"
    if args.scene is None:
        classes = []
    elif args.scene == "all":
        if not args.headless:
            raise UsageError("--scene all runs every scene in turn and needs --headless")
        classes = list(SCENES)
    else:
        student_file = args.scene.removeprefix("exercise:")
        if student_file != args.scene and student_file.endswith(".py") and not os.path.isfile(
                student_file):
            raise UsageError(f"--scene {shown(args.scene)}: no such file; accepted: "
                             "exercise:NAME, or exercise:PATH/NAME.py of a file that exists")
        try:
            cls = get_scene(args.scene)
        except SceneFileError as e:      # a scene file that is not accepted: one line, exit 2
            raise UsageError(str(e)) from None
        if cls is None:
            raise UsageError(f"unknown scene {shown_text(args.scene)}; accepted: {accepted}"
                             + (", all" if args.headless else ""))
        classes = [cls]

    overrides = parse_sets(args.set)
    if overrides and not classes:
        raise UsageError("--set needs --scene NAME (parameters belong to a scene)")
    card = find_card(args.card, classes, overrides) if args.card is not None else None
    shared, variants = overrides, None
    if args.compare is not None or (card is not None and card.compare):
        shared, variants = compare_variants(args, classes, overrides, card)
    unknown = [k for k in overrides if not any(k in c.setting_names() for c in classes)]
    if unknown:
        names = sorted({n for c in classes for n in c.setting_names()})
        where = f"scene '{classes[0].name}' has" if len(classes) == 1 else "no scene has"
        what = "no parameter or effect" if len(classes) == 1 else "a parameter or effect"
        raise UsageError(f"--set: {where} {what} {shown_text(unknown[0])}; accepted: "
                         + listed(names, unknown[0], rest="all in docs/scenes.md"))
    for cls in classes:
        try:
            values, _ = cls.resolve(cls.own_settings(overrides))   # what the run will build
        except ParamError as e:
            raise UsageError(f"--set: {cls.name} {e}") from None
        hertz = max([values["hertz"]] + [cls.resolve({**shared, **v.settings})[0]["hertz"]
                                         for v in variants or ()])
        if args.headless and args.seconds is not None and args.seconds * hertz > MAX_STEPS:
            raise UsageError(f"--seconds {args.seconds:g} at {hertz} Hz is more than "
                             f"{MAX_STEPS:,} steps; accepted: at most "
                             f"{MAX_STEPS // hertz:,} seconds for {cls.name}")
    if args.headless and args.record:
        raise UsageError("--record records what you do in the window; it needs no --headless")
    if args.headless and (args.size or args.fullscreen):
        raise UsageError(f"--{'size' if args.size else 'fullscreen'} is the window's; headless "
                         "pictures take --width")
    clip_problem(args, classes)

    events = None
    if args.input is not None:        # '' too: an empty name is refused, not ignored
        try:
            events = load_events(args.input, classes)
        except InputFileError as e:
            raise UsageError(str(e)) from None

    instrument_problem(args, classes)
    check_outputs(args, classes, clip_paths(args, classes))   # last: it may create folders

    for cls in classes:     # an exercise's scene imports the student's file in this process
        problem = cls.import_problem() if hasattr(cls, "import_problem") else None
        if problem:
            print(problem, file=sys.stderr)
            return EXIT_NONFINITE      # like their code raising: exit 1 (docs/reference.md)

    plot = check_plot(args.plot, classes, shared)
    extras = Extras(args.csv, args.arrows, tuple(plot))
    if args.headless:
        if not classes:
            raise UsageError(f"--headless needs --scene NAME or --scene all; accepted: {accepted}")
        use_dummy_video()
        if variants is not None:
            from app.headless_compare import run_compare
            return run_compare(classes[0], shared, variants, args.steps, args.seconds, events,
                               args.screenshot, args.json, card, extras, video=args.video,
                               fps=args.fps, width=args.width, clean=args.clean)
        return run_headless(classes, overrides, args.steps, args.seconds, events,
                            args.screenshot, args.json, card, extras, video=args.video,
                            fps=args.fps, width=args.width, clean=args.clean)

    if args.steps is not None or args.json:
        raise UsageError("--steps and --json are for --headless runs")
    from app.window import run_window
    return run_window(classes[0].name if classes else None, shared, record=args.record,
                      screenshot=args.screenshot, seconds=args.seconds,
                      large_text=args.large_text, events=events, card=card,
                      compare=variants, extras=extras,
                      clips=dict(path=args.video, fps=args.fps, width=args.width),
                      size=args.size, fullscreen=args.fullscreen)


def find_card(label: str, classes: list, overrides: dict):
    """The scene's try card called `label`; UsageError if there is none, if the scene is not
    one, or with --set (a card is the scene's defaults plus its own settings)."""
    if len(classes) != 1:
        raise UsageError("--try needs --scene NAME (a card belongs to one scene)")
    cls = classes[0]
    if overrides:
        raise UsageError("--try sets the scene's values itself (its defaults plus the card's, as "
                         "a click does); drop --set, or give the values as --set without --try")
    card = cls.find_card(label)
    if card is None:
        labels = ", ".join(repr(c.label) for c in cls.tries + cls.comparisons) or \
            "none (this scene has no cards)"
        raise UsageError(f"--try {shown_text(label)}: scene '{cls.name}' has no such card; "
                         f"accepted: {labels}")
    return card


def clip_problem(args: argparse.Namespace, classes: list) -> None:
    """Refuse (UsageError) clip options that do not fit together, and a clip that cannot be
    made (its extension, its frame rate, a GIF too long, MP4 without imageio-ffmpeg), before
    the run. Headless, --video records the run; in the window it names where F9's clips go."""
    if args.clean and not args.headless:
        raise UsageError("--clean is for --headless --screenshot and --video; in the window, F3 "
                         "hides the HUD")
    if args.clean and not (args.screenshot or args.video):
        raise UsageError("--clean leaves the HUD out of --screenshot and --video; give one")
    if args.fps is not None and args.video is None and args.headless:
        raise UsageError("--fps is a clip's frame rate; give --video OUT.gif|OUT.mp4")
    if args.width is not None and args.headless and not (args.screenshot or args.video):
        raise UsageError("--width sizes --screenshot and --video; give one")
    if args.video is None:
        return
    fps = args.fps or DEFAULT_FPS
    for cls in classes or [None]:
        frames = None
        if args.headless and cls is not None:
            dt = 1.0 / cls.resolve(cls.own_settings(parse_sets(args.set)))[0]["hertz"]
            steps = args.steps if args.steps is not None else steps_for(args.seconds, dt)
            frames = frame_count(steps, dt, fps)
        problem = check_video(args.video, fps, frames, width=args.width or DEFAULT_WIDTH)
        if problem:
            raise UsageError((f"{cls.name}: " if cls and len(classes) > 1 else "") + problem)


def clip_paths(args: argparse.Namespace, classes: list) -> list[str]:
    """The clip files a run will write (OUT-<scene>.gif with --scene all), or where the
    window's first F9 clip goes."""
    if args.video is None:
        return []
    several = args.headless and len(classes) > 1
    return [screenshot_path(args.video, c.name, several) for c in classes] if several \
        else [args.video]


def writable_folder(path: str, what: str, example: str, probe: str) -> None:
    """Refuse (UsageError) a folder argument that is empty, names a file, or cannot be written
    (tried with a file called `probe`, before any work is done)."""
    if not path.strip():
        raise UsageError(f"{what} needs a folder name, e.g. {example}")
    if os.path.exists(path) and not os.path.isdir(path):
        raise UsageError(f"{what} {shown(path)} is not a folder; accepted: a folder")
    problem = check_output_path(os.path.join(path, probe), f"{what} folder")
    if problem:
        raise UsageError(problem)


def build_bench_parser(choices: list[str]) -> argparse.ArgumentParser:
    p = _Parser(prog="python -m app bench", allow_abbrev=False,
                description="benchmark tables and PNG charts")
    p.add_argument("which", nargs="?", default="all",
                   help=f"what to measure; accepted: {', '.join(choices)}")
    p.add_argument("--json", action="store_true", help="print the numbers as JSON on stdout")
    p.add_argument("--out", default="lab-output/bench", help="folder for the PNG charts")
    p.add_argument("--quick", action="store_true", help="tiny sizes and few repeats (a smoke run)")
    p.add_argument("--full", action="store_true", help="the whole sweeps (mass_spring: every "
                   "material and stiffness; pymunk: piles of 1000, and instruction counts "
                   "with valgrind; minutes)")
    return p


def bench_main(argv: list[str]) -> int:
    from app.bench import BENCHMARKS, run_benchmarks
    choices = list(BENCHMARKS) + ["all"]
    args = build_bench_parser(choices).parse_args(argv)
    if args.which not in choices:
        raise UsageError(f"unknown benchmark {shown_text(args.which)}; accepted: "
                         f"{', '.join(choices)}")
    writable_folder(args.out, "--out", "--out lab-output/bench", "chart.png")
    use_dummy_video()
    if args.quick and args.full:
        raise UsageError("--quick and --full ask for opposite sweeps; give one")
    return run_benchmarks(args.which, args.json, args.out, args.quick, args.full)


def build_exercise_parser(names: list[str]) -> argparse.ArgumentParser:
    from app.exercises.grade import CHECK_TIMEOUT
    # allow_abbrev=False on every level: --ref is not --reference (docs/reference.md)
    p = _Parser(prog="python -m app exercise", allow_abbrev=False, description="student "
                "exercises: list them, grade an answer, copy the starters")
    sub = p.add_subparsers(dest="command", metavar="list|check|copy|grade", parser_class=_Parser)
    sub.add_parser("list", help="name, title and slide of every exercise", allow_abbrev=False)
    c = sub.add_parser("check", help="grade an answer (headless)", allow_abbrev=False)
    c.add_argument("name", help=f"accepted: {', '.join(names)}, all")
    c.add_argument("--path", help="the file to grade (default exercises/NAME.py); with 'all': "
                   "a folder holding NAME.py files")
    c.add_argument("--reference", action="store_true", help="grade the lab's own answer")
    c.add_argument("--json", action="store_true", help="one JSON object per exercise")
    c.add_argument("--timeout", type=_timeout, default=CHECK_TIMEOUT,
                   help=f"seconds a check may run (default {CHECK_TIMEOUT:g})")
    c.add_argument("--seed", type=_seed, default=None,
                   help="the random cases' seed, 0 to 2**32-1 (default: a new one each run, "
                   "printed with the verdict; give it to repeat that run's cases)")
    k = sub.add_parser("copy", help="copy the starters into a folder of your own",
                       allow_abbrev=False)
    k.add_argument("folder")
    g = sub.add_parser("grade", help="grade a whole class: a folder per student",
                       allow_abbrev=False)
    g.add_argument("class_dir", metavar="CLASS_DIR", help="a folder holding a folder per student "
                   "(each with the student's NAME.py files)")
    g.add_argument("--jobs", type=lambda t: _int_in(t, 1, 256, "--jobs"),
                   default=os.cpu_count() or 1,
                   help="files graded at once, each in its own sandbox (default: the CPU count)")
    g.add_argument("--out", help="the gradebook CSV (default CLASS_DIR/gradebook.csv); the "
                   "reports go to a folder beside it, OUT-reports/")
    g.add_argument("--gradescope", action="store_true", help="also write each student's "
                   "results.json in Gradescope's autograder format "
                   "(OUT-reports/STUDENT.results.json)")
    g.add_argument("--timeout", type=_timeout, default=CHECK_TIMEOUT,
                   help=f"seconds a check may run at least (default {CHECK_TIMEOUT:g}; or 20x the "
                   "reference's time on this machine, if longer)")
    g.add_argument("--seed", type=lambda t: _int_in(t, 0, 2 ** 32 - 1, "--seed"), default=None,
                   help="the random cases' seed (default: a new one, written in the gradebook)")
    return p


def exercise_main(argv: list[str]) -> int:
    """`exercise list | check NAME|all [--path P] [--reference] [--json] [--seed N] | copy DIR`."""
    from app.exercises import cli, exercise_names, get_exercise
    from app.exercises.loading import shown as as_typed, starter_path   # messages: outputs.shown
    names = exercise_names()
    args = build_exercise_parser(names).parse_args(argv)
    if args.command is None:
        raise UsageError("exercise needs a command; accepted: list, check NAME|all, copy DIR, "
                         "grade CLASS_DIR")
    if args.command == "list":
        return cli.list_exercises()
    if args.command == "grade":
        return grade_class_main(args)
    if args.command == "copy":
        writable_folder(args.folder, "copy", "exercise copy mywork", "verlet.py")
        taken = cli.existing_copies(args.folder)
        if taken:
            raise UsageError(f"copy: {shown(taken[0])} exists; nothing copied (your work is never "
                             "overwritten): pick another folder or move it away")
        return cli.copy(args.folder)
    if args.name != "all" and get_exercise(args.name) is None:
        raise UsageError(f"unknown exercise {shown_text(args.name)}; accepted: "
                         f"{', '.join(names)}, all")
    if args.path is not None and not args.path.strip():
        raise UsageError("--path needs a file name (with 'all': a folder of NAME.py files)")
    if args.reference and args.path:
        raise UsageError("--reference grades the lab's own answer; it takes no --path")
    chosen = [get_exercise(n) for n in (names if args.name == "all" else [args.name])]
    if args.reference:
        paths: list[str | None] = [None] * len(chosen)
    elif args.name == "all":
        folder = args.path
        if folder is not None and not os.path.isdir(folder):
            raise UsageError(f"--path {shown(folder)}: with 'all' it names a folder of NAME.py "
                             "files")
        paths = [as_typed(os.path.join(folder, f"{e.name}.py")) if folder else
                 as_typed(starter_path(e.name)) for e in chosen]
    else:
        paths = [args.path or as_typed(starter_path(args.name))]
        if not os.path.isfile(paths[0]):
            what = "not a regular file" if os.path.exists(paths[0]) else "no such file"
            raise UsageError(f"--path {shown(paths[0])}: {what}; accepted: a .py file, "
                             f"e.g. exercises/{args.name}.py")
    return cli.check(chosen, paths, args.json, args.timeout, args.seed)


def build_scene_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="python -m app scene", allow_abbrev=False,
                description="scene files (TOML): check one without running it")
    sub = p.add_subparsers(dest="command", metavar="check", parser_class=_Parser)
    sub.add_parser("check", help="check scene files against the format (docs/experiments.md)",
                   allow_abbrev=False).add_argument("files", nargs="+", metavar="FILE.toml")
    return p


def scene_main(argv: list[str]) -> int:
    """`scene check FILE...`: read and check each file and build its world once (no step):
    one line per file, 'FILE: ok ...' or the first thing wrong with it (exit 2)."""
    args = build_scene_parser().parse_args(argv)
    if args.command is None:
        raise UsageError("scene needs a command; accepted: check FILE.toml")
    from app.scenefile.load import SceneFileError
    from app.scenefile.load import checked_line
    from scenes import get_scene
    use_dummy_video()
    for path in args.files:
        try:
            print(checked_line(path, get_scene(path)))
        except SceneFileError as e:
            raise UsageError(str(e)) from None
    return EXIT_OK


def grade_class_main(args: argparse.Namespace) -> int:
    """`exercise grade CLASS_DIR`: the usage checked (classroom.usage_problem), then graded."""
    from app.exercises import classroom
    folder = args.class_dir
    out = args.out or os.path.join(folder, "gradebook.csv")
    problem = classroom.usage_problem(folder, out, check_output_path)
    if problem:
        raise UsageError(problem)
    return classroom.grade_class(folder, args.jobs, out, args.gradescope, args.timeout, args.seed)


def leave(code: int) -> NoReturn:
    """Exit with `code`. An exercise scene runs the student's file in this process, and what it
    left behind must not keep the lab open nor write after the JSON: a thread (even a non-daemon
    one, which Python waits for at exit, for ever), an atexit handler, a __del__ that runs at
    shutdown. Once a student's file ran here, or with such a thread alive, flush and leave at
    once; after a Ctrl-C too (its line is printed, its outputs discarded): Python exits by the
    signal itself, not with 130, if a KeyboardInterrupt was raised in some of its C paths."""
    import signal
    import threading
    stray = [t for t in threading.enumerate()
             if t is not threading.main_thread() and t.is_alive() and not t.daemon]
    loading = sys.modules.get("app.exercises.loading")
    # the command is done and its outputs are written: a Ctrl-C from here on has nothing left
    # to stop, and in Python's own shutdown it would end the process by the signal (exit -2,
    # not the command's code: hostile run, seed 7), so it is ignored
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if not stray and not getattr(loading, "LOADED", None) and code != EXIT_INTERRUPTED:
        sys.exit(code)     # (after Ctrl-C, os._exit: Python would end by the signal, not 130)
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    sandbox = sys.modules.get("app.exercises.sandbox")     # its temporary folders (no atexit)
    if sandbox is not None:
        sandbox.cleanup()
    os._exit(code)


if __name__ == "__main__":
    sys.modules["app"].started()   # Ctrl-C is main's from here (app/__init__.py)
    try:
        code = main()
    except KeyboardInterrupt:      # Ctrl-C between main's own handlers (at exit)
        code = interrupted()
    leave(code)
