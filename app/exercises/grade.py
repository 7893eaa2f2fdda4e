"""Grading a student's module so that nothing in it can break the lab.

Every check (and the import before them) runs in a child process forked from the grader:
  * a syntax error, an import of a missing package or an exception at import is a failed
    "imports" check with the student's file and line (their traceback, trimmed to their frames);
    the other checks are then reported as not run;
  * an exception inside a check fails that check (with their traceback) and the next check runs;
  * a check that runs longer than the time limit (an endless loop) is killed and failed;
  * a child that dies (pymunk aborts the process on some values) is a failed check, not a crash.
Forking costs a few milliseconds per check: NumPy and pymunk are already loaded in the parent.
(Windows cannot fork: there the checks run in the grader's process, which still catches every
exception but cannot stop an endless loop.)
The student's prints go to stderr, so `--json` output stays clean.
"""

from __future__ import annotations

import importlib.util
import multiprocessing
import os
import sys
import traceback
import warnings
from dataclasses import asdict, dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

from app.exercises.base import BadAnswer, Check, Exercise
from app.scene import SceneError

CHECK_TIMEOUT = 10.0        # seconds a check may run before it counts as an endless loop
CAN_FORK = "fork" in multiprocessing.get_all_start_methods()
REPO = Path(__file__).resolve().parents[2]
STARTERS = REPO / "exercises"


@dataclass
class CheckReport:
    name: str
    passed: bool
    measured: str = ""
    bound: str = ""
    hint: str = ""
    error: str = ""          # the student's traceback (trimmed), a bad answer or a timeout

    def lines(self) -> list[str]:
        mark = "PASS" if self.passed else "FAIL"
        out = [f"  {mark}  {self.name:<26} measured {self.measured or '-'}; needed {self.bound}"]
        if not self.passed:
            for text in (self.error, self.hint and f"hint: {self.hint}"):
                out += [f"        {line}" for line in text.splitlines() if text]
        return out


@dataclass
class Report:
    exercise: str
    path: str
    checks: list[CheckReport]

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.checks)

    def to_json(self) -> dict[str, Any]:
        return {"exercise": self.exercise, "path": self.path, "passed": self.passed,
                "checks": [asdict(c) for c in self.checks]}

    def text(self) -> str:
        n = sum(c.passed for c in self.checks)
        head = f"{self.exercise}: {self.path}: {n}/{len(self.checks)} checks pass"
        return "\n".join([head] + [line for c in self.checks for line in c.lines()])


def starter_path(name: str) -> Path:
    return STARTERS / f"{name}.py"


def shown(path: str | os.PathLike) -> str:
    """A path as a student would type it: relative to the current folder when inside it."""
    rel = os.path.relpath(path)
    return rel if not rel.startswith("..") else os.path.abspath(path)


def load_module(path: str) -> ModuleType:
    """Import the file at `path` as a fresh module (never cached: each child imports it anew)."""
    name = "student_" + Path(path).stem
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot import {path}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module           # dataclasses and pickling look modules up by name
    spec.loader.exec_module(module)
    return module


def student_traceback(exc: BaseException, path: str | None) -> str:
    """The exception as the student should read it: only the frames in their file, then the
    error line (a SyntaxError says its own file, line and caret). A BadAnswer is its message."""
    if isinstance(exc, BadAnswer):
        return str(exc)
    lines: list[str] = []
    if path is not None:
        mine = os.path.realpath(path)
        frames = [f for f in traceback.extract_tb(exc.__traceback__)
                  if os.path.realpath(f.filename) == mine]
        repeats = 0
        for k, frame in enumerate(frames):
            # a runaway recursion repeats one frame ~1000 times: show it once, then the count
            if k and (frame.lineno, frame.name) == (frames[k - 1].lineno, frames[k - 1].name):
                repeats += 1
                continue
            if repeats:
                lines.append(f"  [the line above repeated {repeats} more times]")
                repeats = 0
            lines.append(f'File "{path}", line {frame.lineno}, in {frame.name}')
            if frame.line:
                lines.append(f"    {frame.line}")
        if repeats:
            lines.append(f"  [the line above repeated {repeats} more times]")
    lines += "".join(traceback.format_exception_only(type(exc), exc)).rstrip().splitlines()
    return "\n".join(lines)


def _import(path: str | None, exercise: Exercise) -> Any:
    """The module to grade: the student's file, or the lab's reference answer (path None)."""
    if path is None:
        return exercise.reference()
    module = load_module(path)
    missing = [f for f in exercise.functions if not callable(getattr(module, f, None))]
    if missing:
        raise BadAnswer(f"{path} defines no function {', '.join(missing)}")
    return module


def _run_check(exercise: Exercise, check: Check | None, path: str | None) -> CheckReport:
    """In the child: import, then run one check (None: only import). Never raises."""
    name = check.name if check else "imports"
    try:
        module = _import(path, exercise)
        if check is None:
            return CheckReport(name, True, "it imports", "no error at import")
        r = check.run(module)
        return CheckReport(name, bool(r.passed), str(r.measured), str(r.bound),
                           "" if r.passed else r.hint)
    except BadAnswer as e:
        return CheckReport(name, False, "unusable answer", "see the message", error=str(e))
    except NotImplementedError as e:
        return CheckReport(name, False, "not written yet", "a working answer",
                           error=student_traceback(e, path))
    except SceneError as e:         # the exercise's scene ran the student's code (pymunk ones)
        unwritten = "NotImplementedError" in str(e)
        return CheckReport(name, False, "not written yet" if unwritten else "an exception",
                           "a working answer" if unwritten else "no exception", error=str(e))
    except BaseException as e:      # noqa: BLE001 - anything the student's code does is a fail
        return CheckReport(name, False, "an exception", "no exception",
                           error=student_traceback(e, path))


def _child(conn, exercise: Exercise, check: Check | None, path: str | None) -> None:
    os.dup2(2, 1)                   # the student's prints go to stderr (keeps --json clean)
    sys.stdout = sys.stderr
    # a wrong answer overflows or divides by zero on purpose-built cases: the check reports
    # the result (NaN, a huge error); NumPy's warnings would only bury the report
    warnings.simplefilter("ignore", RuntimeWarning)
    try:
        conn.send(_run_check(exercise, check, path))
    finally:
        conn.close()


def run_isolated(exercise: Exercise, check: Check | None, path: str | None,
                 timeout: float) -> CheckReport:
    """Run one check in a forked child; kill it after `timeout` seconds. Where the system cannot
    fork (Windows), the check runs in this process: exceptions are still caught, but an endless
    loop cannot be stopped there."""
    name = check.name if check else "imports"
    if not CAN_FORK:
        return _run_check(exercise, check, path)
    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_child, args=(send, exercise, check, path), daemon=True)
    sys.stdout.flush()
    sys.stderr.flush()
    proc.start()
    send.close()
    try:
        if receive.poll(timeout):
            try:
                return receive.recv()
            except EOFError:        # the child died without an answer (a crash, an abort)
                proc.join()
                return CheckReport(name, False, f"the process died (exit code {proc.exitcode})",
                                   "a normal return", error="the check's process ended without "
                                   "a result: a crash in a library (pymunk aborts on some "
                                   "values, e.g. a negative radius or mass) or os._exit")
        proc.kill()
        return CheckReport(name, False, f"still running after {timeout:g} s",
                           f"done within {timeout:g} s", error=f"stopped after {timeout:g} s: an "
                           "endless loop (a while loop whose condition never changes)? Or a "
                           "step far too slow: a check calls your function hundreds of times, "
                           "so a sleep or a print of whole arrays in it adds up")
    finally:
        proc.join()
        receive.close()


def grade(exercise: Exercise, path: str | None, timeout: float = CHECK_TIMEOUT,
          only: tuple[str, ...] | None = None) -> Report:
    """Grade the module at `path` (None: the lab's reference answer): the import, then every
    check (or those named in `only`), each in its own child process."""
    checks = [c for c in exercise.checks if only is None or c.name in only]
    where = "the lab's reference" if path is None else str(path)
    first = run_isolated(exercise, None, path, timeout)
    if not first.passed:            # only a failed import gets a line of its own
        return Report(exercise.name, where, [first] + [
            CheckReport(c.name, False, "not run", "the module imports",
                        error="not run: the module does not import (see above)")
            for c in checks])
    return Report(exercise.name, where, [run_isolated(exercise, c, path, timeout) for c in checks])


__all__ = ["grade", "Report", "CheckReport", "load_module", "student_traceback", "starter_path",
           "CHECK_TIMEOUT", "STARTERS", "shown"]
