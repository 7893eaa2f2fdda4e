"""The grader's child process: import the student's file once, run the measuring half of each
check on it, and send the raw values back, one frame per check (app/exercises/channel.py).

It runs in a process forked from the grader, in a process group of its own (so the grader can end
every process the student's code started), with stdin from /dev/null and stdout and stderr on a
pipe the grader reads and caps. It never decides a verdict: `measure` returns what the student's
functions gave, and the parent judges it (app/exercises/grade.py). When it is done it leaves with
os._exit: a thread the student started (even a non-daemon one) cannot keep it alive.
"""

from __future__ import annotations

import io
import os
import resource
import sys
import warnings
from typing import Any

from app.exercises import base
from app.exercises.base import BadAnswer, Check, Exercise, plain
from app.exercises.channel import encode, write_all
from app.exercises.loading import NotASourceFile, lab_frame, load_module, student_traceback, \
    their_frames
from app.scene import SceneError


def fd_limit() -> int:
    """One past the highest file descriptor this process may have open."""
    soft, _ = resource.getrlimit(resource.RLIMIT_NOFILE)
    return soft if 0 < soft < 1 << 20 else 1 << 16


def import_answer(path: str | None, exercise: Exercise) -> Any:
    """The module to grade: the student's file, or the lab's reference answer (path None)."""
    if path is None:
        return exercise.reference()
    module = load_module(path)
    missing = [f for f in exercise.functions if not callable(getattr(module, f, None))]
    if missing:
        raise BadAnswer(f"{path} defines no function {', '.join(missing)}")
    return module


def outcome(exc: BaseException, path: str | None) -> tuple[str, str]:
    """(status, message) for an exception raised while importing or measuring: the student's
    (with their frames), a bad answer, an unwritten function, or the lab's own code failing."""
    if isinstance(exc, BadAnswer):
        return "bad", student_traceback(exc, path)
    if isinstance(exc, NotImplementedError):
        return "unwritten", student_traceback(exc, path)
    if isinstance(exc, NotASourceFile):
        return "error", str(exc)
    if isinstance(exc, SceneError):        # the exercise's scene ran their code (pymunk ones)
        text = str(exc)
        return ("unwritten" if "NotImplementedError" in text else "error"), text
    if isinstance(exc, SyntaxError) or path is None or their_frames(exc, path):
        return "error", student_traceback(exc, path)
    # raised in the lab's code with none of their frames: say so, and where
    return "lab", (f"{student_traceback(exc, None)}\n(raised in the lab's code at "
                   f"{lab_frame(exc)}, not in your file: a value your code returned may have "
                   "caused it; if not, it is a bug in the lab)")


def run_child(exercise: Exercise, path: str | None, checks: list[tuple[int, Check]],
              token: str, channel: int) -> None:
    """The child's work (the caller has set up its fds): the import, then each check in turn.
    Returns when done; the caller leaves with os._exit."""
    # a wrong answer overflows or divides by zero on purpose-built cases: the check reports the
    # result (NaN, a huge error); NumPy's warnings would only bury the report
    warnings.simplefilter("ignore", RuntimeWarning)

    def send(index: int, status: str, raw: Any = None, error: str = "") -> None:
        sys.stdout.flush()
        sys.stderr.flush()
        write_all(channel, encode(token, index, status, plain(raw), error,
                                  list(base.NOTES.values())))

    try:
        module = import_answer(path, exercise)
    except BaseException as e:     # noqa: BLE001 - anything at import is a failed import
        status, error = outcome(e, path)
        send(-1, status, error=error)
        return
    send(-1, "ok")
    for index, check in checks:
        base.NOTES.clear()
        try:
            raw = check.measure(module)
        except BaseException as e:  # noqa: BLE001 - anything the student's code does is a fail
            status, error = outcome(e, path)
            send(index, status, error=error)
            continue
        send(index, "ok", raw)


def child_main(exercise: Exercise, path: str | None, checks: list[tuple[int, Check]],
               token: str, channel: int, output: int) -> None:
    """Entry point in the forked child: set up the process, run, and leave (never returns)."""
    code = 0
    try:
        try:
            os.setpgid(0, 0)             # the parent does it too: whoever runs first
        except OSError:
            pass
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)                 # input() gets EOF instead of waiting for the terminal
        os.dup2(output, 1)               # prints, os.write(1, ...) and subprocesses: captured
        os.dup2(output, 2)
        # every other inherited file (the other children's pipes, a test runner's sockets) is
        # closed: the student's code gets its own output and the channel, nothing else
        os.closerange(3, channel)
        os.closerange(channel + 1, fd_limit())
        sys.stdout = io.TextIOWrapper(io.FileIO(1, "w", closefd=False), encoding="utf-8",
                                      errors="backslashreplace")
        sys.stderr = io.TextIOWrapper(io.FileIO(2, "w", closefd=False), encoding="utf-8",
                                      errors="backslashreplace", line_buffering=True)
        sys.stdin = io.TextIOWrapper(io.FileIO(0, "r", closefd=False))
        run_child(exercise, path, checks, token, channel)
    except BaseException:                # noqa: BLE001 - e.g. the channel closed by their code
        code = 3
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except BaseException:            # noqa: BLE001
            pass
        os._exit(code)


__all__ = ["child_main", "run_child", "import_answer", "outcome"]
