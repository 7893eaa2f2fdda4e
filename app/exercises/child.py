"""The grader's child process: import the student's file once, run the measuring half of each
check on it, and send the raw values back, one frame per check (app/exercises/channel.py).

On Linux it is a fresh `python -I` in the operating system's walls (app/exercises/sandbox.py):
`sandbox_main` is its entry point, with only the harness on its path, stdin from /dev/null,
stdout and stderr on a pipe the grader reads and caps, the channel on fd 3. Elsewhere
`child_main` runs in a plain fork of the grader. It never decides a verdict: `measure` returns
what the student's functions gave, and the parent judges it (app/exercises/grade.py). When it is
done it leaves with os._exit: a thread the student started (even a non-daemon one) cannot keep it
alive.
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
from app.exercises.loading import NotASourceFile, lab_borrowings, lab_frame, load_module, \
    student_traceback, their_frames
from app.scene import SceneError


CHANNEL_LOST = 86    # the child's exit code when it could not write on its channel


MEMORY_ROOM = 2 << 30    # bytes of data a student's code may add to the child (the checks use MBs)


def limit_memory(room: int | None = None) -> None:
    """Cap the child's data (heap and private mappings, RLIMIT_DATA) at what it holds now plus
    `room`: a runaway allocation is a MemoryError in the student's code, not a machine that
    swaps until the time limit. Where the limit cannot be read or set, nothing changes."""
    try:
        with open("/proc/self/status") as f:
            held = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmData:"))
        soft, hard = resource.getrlimit(resource.RLIMIT_DATA)
        want = held + (MEMORY_ROOM if room is None else room)
        if hard != resource.RLIM_INFINITY:
            want = min(want, hard)
        if soft == resource.RLIM_INFINITY or soft > want:
            resource.setrlimit(resource.RLIMIT_DATA, (want, hard))
    except (OSError, ValueError, StopIteration, AttributeError):
        pass


def fd_limit() -> int:
    """One past the highest file descriptor this process may have open."""
    soft, _ = resource.getrlimit(resource.RLIMIT_NOFILE)
    return soft if 0 < soft < 1 << 20 else 1 << 16


def import_answer(path: str | None, exercise: Exercise, shown_as: str | None = None) -> Any:
    """The module to grade: the student's file, or the lab's reference answer (path None). The
    sandboxed child reads a copy of the file (`path`) and names the student's (`shown_as`)."""
    if path is None:
        return exercise.reference()
    module = load_module(path, shown_as)
    path = shown_as or path
    missing = [f for f in exercise.functions if not callable(getattr(module, f, None))]
    if missing:
        raise BadAnswer(f"{path} defines no function {', '.join(missing)}")
    refuse_borrowed(module, path)
    return module


def refuse_borrowed(module: Any, path: str) -> None:
    """BadAnswer if the file hands in the lab's own code instead of its own."""
    borrowed = lab_borrowings(module)
    if borrowed:
        raise BadAnswer(f"the file uses the lab's own code: {', '.join(borrowed[:4])}. The grader "
                        "grades the code you write; the lab's answer is there to read, not to "
                        "import (numpy, math and pymunk are yours to use)")


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
              token: str, channel: int, copy: str | None = None,
              refused: str | None = None) -> None:
    """The child's work (the caller has set up its fds): the import, then each check in turn.
    Returns when done; the caller leaves with os._exit. `copy`: the file to read (the sandbox's
    copy of `path`); `refused`: why the grader could not copy it (the import fails with it)."""
    # a wrong answer overflows or divides by zero on purpose-built cases: the check reports the
    # result (NaN, a huge error); NumPy's warnings would only bury the report
    warnings.simplefilter("ignore", RuntimeWarning)

    def send(index: int, status: str, raw: Any = None, error: str = "") -> None:
        sys.stdout.flush()
        sys.stderr.flush()
        write_all(channel, encode(token, index, status, plain(raw), error,
                                  list(base.NOTES.values())))

    try:
        if refused is not None:
            raise NotASourceFile(refused)
        module = import_answer(copy or path, exercise, path)
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
        limit_memory()
        run_child(exercise, path, checks, token, channel)
    except BaseException:                # noqa: BLE001 - e.g. the channel closed by their code
        code = CHANNEL_LOST
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except BaseException:            # noqa: BLE001
            pass
        os._exit(code)


READY = -2       # the frame the sandboxed child sends once its harness is imported


def sandbox_main() -> None:
    """Entry point of the sandboxed child (app/exercises/sandbox.py: a fresh `python -I` in the
    walls, its harness on sys.path); its one argument says what to grade. Never returns."""
    import json
    from app.exercises import get_exercise
    from app.exercises.sandbox import CHANNEL_FD
    code = 0
    try:
        args = json.loads(sys.argv[1])
        exercise = get_exercise(args["exercise"])
        only = args["only"]
        checks = [c for c in exercise.checks if only is None or c.name in only]
        if args.get("seed") is not None and hasattr(base, "set_seed"):
            base.set_seed(args["seed"])
        sys.stdout.reconfigure(errors="backslashreplace")
        sys.stderr.reconfigure(errors="backslashreplace", line_buffering=True)
        write_all(CHANNEL_FD, encode(args["token"], READY, "ok"))
        first = args["first"]
        run_child(exercise, args["path"], [(k, checks[k]) for k in range(first, len(checks))],
                  args["token"], CHANNEL_FD, args["copy"], args["refused"])
    except BaseException:                # noqa: BLE001 - e.g. the channel closed by their code
        code = CHANNEL_LOST
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except BaseException:            # noqa: BLE001
            pass
        os._exit(code)


__all__ = ["child_main", "sandbox_main", "run_child", "import_answer", "outcome", "refuse_borrowed",
           "CHANNEL_LOST", "MEMORY_ROOM", "limit_memory"]
