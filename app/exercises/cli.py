"""`python -m app exercise list | check NAME|all [--path P] [--reference] [--json] [--seed N] | copy DIR`.

The command line's parser (app/__main__.py) checks the usage; these functions do the work and
return the exit code: 0 every check passed, 1 a check failed.
"""

from __future__ import annotations

import functools
import json
import os
import sys
from typing import Callable

from app.exercises import EXERCISES, Exercise
from app.exercises.grade import CHECK_TIMEOUT, Report, grade_many
from app.exercises.loading import shown, starter_path
from app.outputs import shown as shown_value, write_bytes


def quiet_pipe(command: Callable[..., int]) -> Callable[..., int]:
    """`... | head` closes the pipe early: stop printing quietly (no traceback), keep the code."""
    @functools.wraps(command)
    def run(*args, **kwargs) -> int:
        try:
            return command(*args, **kwargs)
        except BrokenPipeError:
            # Python would complain again when it flushes stdout at exit
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            return 1
    return run


@quiet_pipe
def list_exercises() -> int:
    for e in EXERCISES:
        print(f"{e.name:18} {e.title}\n{'':18} slide: {e.slide}")
    return 0


@quiet_pipe
def check(exercises: list[Exercise], paths: list[str | None], as_json: bool,
          timeout: float = CHECK_TIMEOUT, seed: int | None = None) -> int:
    """Grade each exercise on its file (None: the lab's reference), several at once, on the
    random cases of `seed` (None: a new one, printed); print the reports in order (what the
    student's code printed first, on stderr, capped), and a summary table for more than one."""
    from app.progress import Progress
    reports: list[Report] = []
    bar = Progress(len(exercises) if len(exercises) > 1 else 0, "exercises checked")
    for report in grade_many(list(zip(exercises, paths)), timeout, seed=seed):
        reports.append(report)
        bar.update(1, note=report.exercise)
        if report.output_bytes:
            bar.say(report.output_text())
        if as_json:
            print(json.dumps(report.to_json()), flush=True)
        else:
            print(report.text() + "\n", flush=True)
    bar.close()
    if len(reports) > 1 and not as_json:
        print(f"{'exercise':18} {'checks':>7}  result")
        for r in reports:
            n = sum(c.passed for c in r.checks)
            print(f"{r.exercise:18} {n:>3}/{len(r.checks):<3}  {'pass' if r.passed else 'FAIL'}")
        print(f"seed {reports[0].seed}: python -m app exercise check ... --seed "
              f"{reports[0].seed} repeats these random cases")
    return 0 if all(r.passed for r in reports) else 1


def existing_copies(folder: str) -> list[str]:
    return [os.path.join(folder, f"{e.name}.py") for e in EXERCISES
            if os.path.exists(os.path.join(folder, f"{e.name}.py"))]


def copy(folder: str) -> int:
    """Copy every starter into `folder` (the caller has checked that none exists there yet)."""
    try:
        os.makedirs(folder, exist_ok=True)
        for e in EXERCISES:         # each file whole or not at all (app/outputs.py)
            with open(starter_path(e.name), "rb") as f:
                write_bytes(os.path.join(folder, f"{e.name}.py"), f.read(), what="copy")
    except OSError as e:            # bad usage: one line, exit 2 (the files copied so far stay)
        print(f"python -m app: error: copy: cannot write to {shown_value(folder)} "
              f"({getattr(e, 'strerror', None) or e}); accepted: a folder you can write to",
              file=sys.stderr)
        return 2
    where = shown(folder)
    print(f"copied {len(EXERCISES)} exercises to {where}/: "
          + ", ".join(f"{e.name}.py" for e in EXERCISES))
    print(f"grade one:   python -m app exercise check verlet --path {where}/verlet.py")
    print(f"grade all:   python -m app exercise check all --path {where}")
    print(f"run it live: python -m app --scene exercise:{where}/verlet.py")
    return 0
