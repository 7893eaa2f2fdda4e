"""Reading a student's file and telling them what went wrong in it.

`load_module` imports a file as a fresh module, reading at most MAX_SOURCE_BYTES of it: a name
that is a link to /dev/zero, a pipe or a huge file is refused instead of read until the time
limit. `student_traceback` shows an exception as the student should read it: their frames only,
and never more than MAX_ERROR_LINES lines of MAX_LINE_CHARS characters (an exception with a
100 MB message would otherwise fill the terminal, the JSON and the window's error box).
"""

from __future__ import annotations

import importlib.util
import os
import stat
import sys
import traceback
import types
from pathlib import Path

from app.exercises.base import BadAnswer

REPO = Path(__file__).resolve().parents[2]
STARTERS = REPO / "exercises"
MAX_SOURCE_BYTES = 1 << 20      # a student's file: the starters are ~3 kB
MAX_ERROR_LINES = 40
MAX_LINE_CHARS = 300


class NotASourceFile(ImportError):
    """The path names no readable Python file of a sensible size (the message says why)."""


def starter_path(name: str) -> Path:
    return STARTERS / f"{name}.py"


def shown(path: str | os.PathLike) -> str:
    """A path as a student would type it: relative to the current folder when inside it."""
    rel = os.path.relpath(path)
    return rel if not rel.startswith("..") else os.path.abspath(path)


def read_source(path: str) -> bytes:
    """The file's bytes, if it is a regular file of at most MAX_SOURCE_BYTES; NotASourceFile
    otherwise (checked before opening: opening a pipe would wait for a writer)."""
    try:
        info = os.stat(path)
    except OSError as e:
        raise NotASourceFile(f"cannot read {path}: {e.strerror or e}") from None
    if not stat.S_ISREG(info.st_mode):
        raise NotASourceFile(f"{path} is not a regular file (a device, a pipe or a folder: "
                             "nothing to import)")
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_SOURCE_BYTES + 1)
    except OSError as e:
        raise NotASourceFile(f"cannot read {path}: {e.strerror or e}") from None
    if len(data) > MAX_SOURCE_BYTES:
        raise NotASourceFile(f"{path} is larger than {MAX_SOURCE_BYTES >> 20} MB; a Python "
                             "file of an exercise is a few kB")
    return data


def load_module(path: str, shown_as: str | None = None) -> types.ModuleType:
    """Import the file at `path` as a fresh module named student_<stem> (never cached); its
    tracebacks and __file__ name `shown_as` (the grader's sandbox reads a copy of the file)."""
    source = importlib.util.decode_source(read_source(path))
    shown_as = shown_as or path
    name = "student_" + Path(shown_as).stem
    code = compile(source, shown_as, "exec", dont_inherit=True)
    module = types.ModuleType(name)
    module.__file__ = shown_as
    sys.modules[name] = module           # dataclasses and pickling look modules up by name
    LOADED.append(path)                  # app/__main__.py leaves at once after their code ran
    exec(code, module.__dict__)
    return module


LAB_PACKAGES = ("app", "scenes")
LOADED: list[str] = []          # the students' files run in this process


def lab_borrowings(module: types.ModuleType) -> list[str]:
    """The names in a student's module that ARE the lab's own code: a function, class or module
    of app/ or scenes/ imported into it (`from app.physics.jakobsen import verlet_step`). The
    grader grades code the student wrote; it says so instead of grading the lab's answer."""
    found = []
    for name, value in vars(module).items():
        owner = value.__name__ if isinstance(value, types.ModuleType) else \
            getattr(value, "__module__", None) if callable(value) else None
        if isinstance(owner, str) and owner.split(".")[0] in LAB_PACKAGES:
            found.append(f"{name} (from {owner})")
    return found


def cap_text(text: str, lines: int = MAX_ERROR_LINES, width: int = MAX_LINE_CHARS) -> str:
    """At most `lines` lines of at most `width` characters, saying what was cut."""
    out = text.splitlines()
    cut_lines = len(out) - lines
    if cut_lines > 0:
        out = out[:lines // 2] + [f"[... {cut_lines} more lines ...]"] + out[-(lines // 2):]
    out = [t if len(t) <= width else t[:width] + f" [... {len(t) - width} more characters]"
           for t in out]
    return "\n".join(out)


def _message(exc: BaseException) -> str:
    """format_exception_only, but a huge message is cut before it is formatted."""
    try:
        text = str(exc)
    except Exception:                   # noqa: BLE001 - a __str__ that raises is theirs too
        text = "<the exception's message could not be shown>"
    if len(text) > 4 * MAX_LINE_CHARS * MAX_ERROR_LINES:     # cut short enough for one line
        keep = MAX_LINE_CHARS // 2
        text = f"{text[:keep]} [... {len(text) - keep:,} more characters]"
    if isinstance(exc, SyntaxError):
        return "".join(traceback.format_exception_only(type(exc), exc)).rstrip()
    name = type(exc).__name__
    return f"{name}: {text}" if text else name


def student_traceback(exc: BaseException, path: str | None) -> str:
    """The exception as the student should read it: only the frames in their file, then the
    error line (a SyntaxError says its own file, line and caret). A BadAnswer is its message."""
    if isinstance(exc, BadAnswer):
        return cap_text(str(exc))
    lines: list[str] = []
    if path is not None:
        frames = their_frames(exc, path)
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
    lines += _message(exc).splitlines()
    return cap_text("\n".join(lines))


def their_frames(exc: BaseException, path: str) -> list[traceback.FrameSummary]:
    """The traceback's frames that lie in the student's file."""
    mine = os.path.realpath(path)
    return [f for f in traceback.extract_tb(exc.__traceback__)
            if os.path.realpath(f.filename) == mine]


def lab_frame(exc: BaseException) -> str:
    """Where in the lab's code an exception was raised (its innermost frame), as 'file:line'."""
    frames = traceback.extract_tb(exc.__traceback__)
    if not frames:
        return "?"
    f = frames[-1]
    return f"{shown(f.filename)}:{f.lineno}"


__all__ = ["load_module", "read_source", "student_traceback", "their_frames", "lab_frame",
           "starter_path", "shown", "cap_text", "NotASourceFile", "STARTERS", "REPO",
           "MAX_SOURCE_BYTES", "lab_borrowings"]
