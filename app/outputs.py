"""Every file the lab writes, written so that it is never lost (CSV, JSON, PNG, SVG, GIF, MP4,
recordings, reports, gradebooks, scene files).

The way databases write (SQLite, git's lock files, `atomicwrites`): the bytes go to a temporary
file beside the target (same folder, so the same file system), are flushed to the disk, and the
temporary file is renamed over the target (`os.replace`, atomic) only when it is complete. A
failed write (a full disk, an encoder that stops, an exception in the writer) or an interrupted
one (Ctrl-C) removes the temporary file and leaves the old file exactly as it was.

    from app.outputs import atomic_write, atomic_path, write_text, write_bytes

    with atomic_write("out/table.csv", "w", what="--csv") as f:   # a file object ("w" or "wb")
        f.write("step,t\\n")
    with atomic_path("out/shot.png", what="--screenshot") as tmp:   # a path, for writers that
        pygame.image.save(surface, tmp)                            # open the file themselves
    write_text("report.md", text)          # the whole text at once
    write_bytes("clip.gif", data)

Each raises OutputError (an OSError with a one-line message: what could not be written, why,
and that the file that was there is left as it was) if the write fails; a KeyboardInterrupt
passes through after the temporary file is removed. A `Pending` (what atomic_write and
atomic_path use) can also stay open across a whole run, as the --csv file does: `commit()` at
the end, `discard()` on the way out; `discard_all()` removes every one still open (the command
line calls it on Ctrl-C).

Before a run, `output_problem(path, what)` says why a file could not be written there (a folder,
a FIFO or a device where a file is expected, a folder that cannot be made or written) and
`clash(outputs, inputs)` whether one path is named for two outputs, or for an output and an
input. `shown(value)` is how every message echoes a user's value: once, shortened with reprlib,
control characters and newlines escaped, so a message is always one line.
"""

from __future__ import annotations

import os
import reprlib
import stat
import tempfile
from contextlib import contextmanager
from typing import IO, Iterator, Sequence

from app.ctrl_c import held

_SHORT = reprlib.Repr()
_SHORT.maxstring = 60          # a pasted page, a 100k-character path: cut in the middle
_SHORT.maxother = 60

OUTPUT_DIR = "lab-output"      # where the lab's own outputs go unless told (F12, F9, bench):
                               # one folder, in .gitignore, named by the docs
MAX_LINE = 600                 # characters in one error line, at most (a safety net)


def shown(value: object) -> str:
    """A user's value for a message: repr (quotes, and control characters and newlines escaped:
    one line always), cut to about 60 characters with reprlib."""
    text = _SHORT.repr(os.fspath(value) if isinstance(value, os.PathLike) else value)
    return one_line(text)


def one_line(text: str, limit: int = MAX_LINE) -> str:
    """`text` as one line: control characters (newline, tab, escape, ...) written as escapes,
    cut to `limit` characters."""
    if any(ord(c) < 32 or 127 <= ord(c) < 160 or c in "\u2028\u2029" for c in text):
        text = "".join(c if not (ord(c) < 32 or 127 <= ord(c) < 160 or c in "\u2028\u2029")
                       else repr(c)[1:-1] for c in text)
    if len(text) > limit:
        text = text[:limit - 30] + f"... ({len(text):,} characters)"
    return text


def listed(names: Sequence[str], near: str | None = None, limit: int = 90,
           rest: str = "") -> str:
    """Accepted names for a one-line message: those closest to `near` (what was typed) first,
    then the others, cut to about `limit` characters with how many were left out and `rest`
    (where to read them all), so that a refusal stays one readable line."""
    import difflib
    names = list(dict.fromkeys(names))
    close = difflib.get_close_matches(near, names, n=3, cutoff=0.6) if near else []
    ordered = close + [n for n in names if n not in close]
    text = ", ".join(ordered)
    if len(text) <= limit:
        return text
    shown_names: list[str] = []
    for n in ordered:
        if len(", ".join(shown_names + [n])) > limit:
            break
        shown_names.append(n)
    more = len(ordered) - len(shown_names)
    return ", ".join(shown_names) + f", ... and {more} more" + (f" ({rest})" if rest else "")


class OutputError(OSError):
    """A file that could not be written; str() is the one line to print (exit code 2)."""

    def __init__(self, message: str):
        super().__init__(message)
        self.message = message

    def __str__(self) -> str:
        return self.message


def _reason(e: BaseException) -> str:
    if isinstance(e, OSError) and e.strerror:
        return e.strerror
    return one_line(str(e) or type(e).__name__, 200)


_PENDING: "set[Pending]" = set()


class Pending:
    """One output being written: `tmp` (a path beside `path`) is where the bytes go; commit()
    renames it over `path`, discard() removes it. `replaced` tells, after commit(), whether a
    file was there before (the summary says so)."""

    def __init__(self, path: str | os.PathLike, what: str = "output"):
        self.path = os.fspath(path)
        self.what = what
        self.stop: list = []      # what writes the file (an encoder process): stopped first
        folder = os.path.dirname(os.path.abspath(self.path))
        root, ext = os.path.splitext(os.path.basename(self.path))
        try:
            os.makedirs(folder, exist_ok=True)
            # the extension stays last: writers that pick a format by name (ffmpeg) see it
            # in plain ASCII: a writer given a name that is not UTF-8 (pygame's image.save)
            # would write another file, and leave it behind. A Ctrl-C between the file's making
            # and its listing (a KeyboardInterrupt as mkstemp returns) left it behind: held
            # back until it is listed, from where a Ctrl-C removes it (seen once in a CI run)
            with held():
                fd, self.tmp = tempfile.mkstemp(dir=folder, prefix=f".{_ascii(root)[:40]}.",
                                                suffix=f".part{_ascii(ext)[:12]}")
                _PENDING.add(self)
            os.close(fd)
        except OSError as e:
            raise OutputError(self.failed(e)) from None
        self.replaced = os.path.exists(self.path)
        self.done = False

    def left(self) -> str:
        return ("the file that was there is left as it was" if os.path.exists(self.path)
                else "nothing was written")

    def failed(self, e: BaseException | str) -> str:
        """The one line that says this output could not be written, and why."""
        reason = e if isinstance(e, str) else _reason(e)
        return (f"could not write {self.what} {shown(self.path)}: {one_line(reason, 200)}; "
                f"{self.left()}")

    def commit(self, allow_empty: bool = False) -> None:
        """Flush the temporary file to the disk and rename it over the target (keeping the
        target's permissions, or the umask's for a new file). OutputError if it is empty (a
        writer that wrote nothing has failed) or cannot be moved."""
        try:
            size = os.path.getsize(self.tmp)
            if size == 0 and not allow_empty:
                raise OSError(0, "the writer wrote nothing")
            fd = os.open(self.tmp, os.O_RDONLY)
            try:
                os.fsync(fd)
            except OSError:              # a file system without fsync (some FUSE): renamed anyway
                pass
            finally:
                os.close(fd)
            os.chmod(self.tmp, _mode_for(self.path))
            self.replaced = os.path.exists(self.path)
            os.replace(self.tmp, self.path)
            self.done = True
        except OSError as e:
            self.discard()
            raise OutputError(self.failed(e)) from None
        finally:
            _PENDING.discard(self)

    def discard(self) -> None:
        """Stop what writes the temporary file (an encoder that outlived the run would write
        it again), then remove it: the target stays as it was."""
        _PENDING.discard(self)
        for stop in self.stop:
            try:
                stop()
            except Exception:
                pass
        try:
            os.remove(self.tmp)
        except FileNotFoundError:
            pass
        except OSError:
            pass


def _ascii(text: str) -> str:
    """`text` with every character outside [A-Za-z0-9._-] written as '_'."""
    return "".join(c if c.isascii() and (c.isalnum() or c in "._-") else "_" for c in text)


def _mode_for(path: str) -> int:
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def discard_all() -> list[str]:
    """Remove every temporary file still open (an interrupted run); return their targets."""
    targets = []
    for p in list(_PENDING):
        p.discard()
        targets.append(p.path)
    return targets


@contextmanager
def atomic_path(path: str | os.PathLike, what: str = "output",
                allow_empty: bool = False) -> Iterator[str]:
    """Yield a temporary path beside `path` for a writer that opens files itself (pygame's
    image.save, matplotlib's savefig, Pillow, ffmpeg); rename it into place when the block ends
    without an exception. OutputError (one line) if writing or renaming fails; the old file is
    left as it was either way."""
    pending = Pending(path, what)
    try:
        yield pending.tmp
    except OutputError:
        pending.discard()
        raise
    except (OSError, ValueError, RuntimeError) as e:
        pending.discard()
        raise OutputError(pending.failed(e)) from None
    except BaseException:
        pending.discard()
        raise
    pending.commit(allow_empty)


@contextmanager
def atomic_write(path: str | os.PathLike, mode: str = "w", what: str = "output",
                 encoding: str | None = "utf-8", newline: str | None = None,
                 allow_empty: bool = False) -> Iterator[IO]:
    """Yield a file object ("w" text or "wb" bytes) that writes beside `path`; renamed into
    place when the block ends without an exception (see atomic_path)."""
    if mode not in ("w", "wb", "x", "xb"):
        raise ValueError(f"atomic_write writes a whole file: mode 'w' or 'wb', not {mode!r}")
    binary = "b" in mode
    with atomic_path(path, what, allow_empty) as tmp:
        with open(tmp, "wb" if binary else "w", encoding=None if binary else encoding,
                  newline=None if binary else newline) as f:
            yield f
            f.flush()


def write_text(path: str | os.PathLike, text: str, what: str = "output",
               encoding: str = "utf-8") -> bool:
    """Write `text` to `path` whole or not at all; return True if it replaced a file."""
    existed = os.path.exists(path)
    with atomic_write(path, "w", what, encoding, allow_empty=True) as f:
        f.write(text)
    return existed


def write_bytes(path: str | os.PathLike, data: bytes, what: str = "output") -> bool:
    """Write `data` to `path` whole or not at all; return True if it replaced a file."""
    existed = os.path.exists(path)
    with atomic_write(path, "wb", what, allow_empty=True) as f:
        f.write(data)
    return existed


# --- checks before a run ------------------------------------------------------------------------

def output_problem(path: str, what: str) -> str | None:
    """None if a file can be written at `path`, else a one-line reason: an empty name, a folder,
    a FIFO, a device or a socket where a file is expected, a folder that cannot be made or
    written. Makes the folder (it would be made anyway) but writes no file."""
    if not path.strip():
        return f"{what} needs a file name"
    if path.endswith((os.sep, "/")) or os.path.basename(path) in (".", ".."):
        return (f"{what} {shown(path)} names a folder; accepted: a file name (for a file in "
                f"it, add {shown('out' + _ext(what))})")
    try:
        info = os.stat(path)
    except FileNotFoundError:
        info = None
    except OSError as e:
        return f"{what} {shown(path)}: cannot write there ({e.strerror or e})"
    if info is not None:
        if stat.S_ISDIR(info.st_mode):
            return (f"{what} {shown(path)} is a folder; accepted: a file name (for a file in "
                    f"it, add {shown(os.sep + 'out' + _ext(what))})")
        if not stat.S_ISREG(info.st_mode):
            return (f"{what} {shown(path)} is {_kind(info.st_mode)}, not a file; accepted: a "
                    "regular file (it is written whole, then renamed into place)")
    folder = os.path.dirname(os.path.abspath(path))
    try:
        os.makedirs(folder, exist_ok=True)
        with held():                # (a Ctrl-C between the two would leave the probe behind)
            fd, probe = tempfile.mkstemp(dir=folder, prefix=".probe.")  # the very folder
            os.close(fd)
            os.remove(probe)
        name = os.path.basename(path).encode("utf-8", "surrogateescape")
        if len(name) > os.pathconf(folder, "PC_NAME_MAX"):      # renamed into place at the end
            raise OSError(36, "File name too long")
    except OSError as e:
        return f"{what} {shown(path)}: cannot write in {shown(folder)} ({e.strerror or e})"
    return None


def input_problem(path: str, what: str) -> str | None:
    """None if `path` is a regular file that can be opened, else a one-line reason (checked
    before opening: opening a FIFO would wait for a writer for ever)."""
    if not path.strip():
        return f"{what} needs a file name"
    try:
        info = os.stat(path)
    except OSError as e:
        return f"cannot read {what} file {shown(path)}: {e.strerror or e}"
    if not stat.S_ISREG(info.st_mode):
        return (f"{what} {shown(path)} is {_kind(info.st_mode)}, not a file; accepted: a "
                "regular file")
    return None


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _ext(what: str) -> str:
    return {"--screenshot": ".png", "--video": ".mp4", "--csv": ".csv",
            "--record": ".json"}.get(what, "")


def _key(path: str) -> tuple:
    """What identifies a file: its device and inode if it exists (a hard link or a symlink is
    the same file), else its real absolute path."""
    try:
        info = os.stat(path)
        return ("inode", info.st_dev, info.st_ino)
    except OSError:
        return ("path", os.path.normcase(os.path.realpath(path)))


def clash(outputs: Sequence[tuple[str, str]],
          inputs: Sequence[tuple[str, str]] = ()) -> str | None:
    """None if every output names its own file and none is an input, else a one-line reason.
    `outputs` and `inputs` are (path, option) pairs."""
    seen: dict[tuple, str] = {}
    for path, what in inputs:
        if path:
            seen.setdefault(_key(path), what)
    n_inputs = len(seen)
    for path, what in outputs:
        if not path:
            continue
        key = _key(path)
        if key in seen:
            other = seen[key]
            is_input = list(seen).index(key) < n_inputs
            return (f"{what} {shown(path)} is also {other}{' (an input)' if is_input else ''}: "
                    f"one file cannot be {'an output and an input' if is_input else 'two outputs'}; "
                    "give each its own name")
        seen[key] = what
    return None


__all__ = ["shown", "one_line", "OutputError", "Pending", "atomic_path", "atomic_write",
           "write_text", "write_bytes", "discard_all", "output_problem", "input_problem",
           "clash", "listed", "MAX_LINE", "OUTPUT_DIR"]
