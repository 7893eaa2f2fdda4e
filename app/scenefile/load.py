"""Read a scene file: TOML (the standard library's tomllib), checked against the schema
(app/scenefile/schema.py) key by key before anything reaches pymunk.

    spec = load_spec("scenes/files/seesaw.toml")    # a plain dict, every key filled in

A file that is not accepted raises SceneFileError, whose text is one line:

    scenes/files/seesaw.toml:14: body 'plank': mass -1 is out of range; accepted: a number
    above 0 to 1e+09 (kg)

with the line number wherever the TOML parser or the schema knows it. An unknown section or key
is an error (a typo such as `elastisity` would otherwise be ignored in silence).
"""

from __future__ import annotations

import math
import re
import stat
import tomllib
from pathlib import Path
from typing import Any

from app.scenefile.checks import check_all
from app.outputs import shown
from app.scenefile.schema import COORD, SCHEMA, SECTIONS, Key, Section

MAX_FILE_BYTES = 1_000_000      # a scene file is a page of text; a bigger one is no scene
MAX_ITEMS = 2000                # bodies, joints, ... per section (a step must stay cheap)
NAME = re.compile(r"[A-Za-z][A-Za-z0-9_\-]{0,39}\Z")


class SceneFileError(ValueError):
    """A scene file that is not accepted: str() is one line, 'FILE:LINE: what; accepted: ...'."""

    def __init__(self, path: str, line: int | None, message: str):
        self.path, self.line, self.message = path, line, message
        where = path if len(path) <= 160 and path.isprintable() else shown(path)  # one short line
        super().__init__(f"{where}:{line}: {message}" if line else f"{where}: {message}")


# ----- where each key is written ------------------------------------------------------------
_HEADER = re.compile(r"\s*(\[\[?)\s*([A-Za-z0-9_.\- ]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(r"\s*([A-Za-z0-9_\-]+|\"[^\"]*\")\s*=")


def key_lines(text: str) -> dict[tuple, int]:
    """The line (1-based) of each table header and key, by its path in the data:
    ("body", 2) is the third [[body]], ("body", 2, "shape", 0, "radius") the radius of its first
    shape. A plain scan of the usual layout (headers, `key = value` lines; multi-line strings
    and arrays skipped), not a TOML parser: keys it cannot place get no line."""
    lines: dict[tuple, int] = {}
    counts: dict[tuple, int] = {}
    path: tuple = ()
    depth, quote = 0, None
    for number, line in enumerate(text.splitlines(), 1):
        if quote is not None:                       # inside a multi-line string
            if line.count(quote) % 2:
                quote = None
            continue
        if depth == 0:
            m = _HEADER.match(line)
            if m and not _KEY.match(line):
                names = [n.strip() for n in m.group(2).split(".")]
                path = _table_path(names, m.group(1) == "[[", counts, path)
                lines.setdefault(path, number)
                continue
            k = _KEY.match(line)
            if k:
                lines.setdefault(path + (k.group(1).strip('"'),), number)
        body = re.sub(r'"(\\.|[^"\\])*"|\'[^\']*\'', '""', line.split("#")[0]
                      if '"' not in line else line)
        for q in ('"""', "'''"):
            if body.count(q) % 2 == 1 or line.count(q) % 2 == 1:
                quote = q
                break
        depth = max(0, depth + body.count("[") - body.count("]")) if _KEY.match(line) or depth \
            else depth
    return lines


def _table_path(names: list[str], array: bool, counts: dict[tuple, int], old: tuple) -> tuple:
    """The data path of a header [a.b] or [[a.b]], counting array tables (a new [[body]] starts
    its own count of [[body.shape]])."""
    path: tuple = ()
    for i, name in enumerate(names):
        path += (name,)
        last = i == len(names) - 1
        if last and array:
            n = counts.get(path, -1) + 1
            counts[path] = n
            for k in [k for k in counts if len(k) > len(path) and k[:len(path)] == path]:
                del counts[k]
            path += (n,)
        elif not last and path in counts:           # inside the latest of an array of tables
            path += (counts[path],)
    return path


# ----- checking values -------------------------------------------------------------------------
class Checker:
    """Checks one file's data; `fail` raises the one-line error with the line it knows."""

    def __init__(self, path: str, text: str):
        self.path = path
        self.lines = key_lines(text)

    def line(self, where: tuple) -> int | None:
        while where:
            if where in self.lines:
                return self.lines[where]
            where = where[:-1]
        return None

    def fail(self, where: tuple, message: str) -> None:
        raise SceneFileError(self.path, self.line(where), message)

    # one value of a key
    def value(self, key: Key, value: Any, where: tuple, what: str) -> Any:
        bad = f"{what}: {key.name} = {_shown(value)}"
        kind = key.kind
        if kind in ("float", "int"):
            return self.number(key, value, where, bad)
        if kind == "vec2":
            if not isinstance(value, list) or len(value) != 2:
                self.fail(where, f"{bad} is not a pair; accepted: {key.accepted()}")
            return [float(self.number(key, v, where, bad)) for v in value]
        if kind == "bool":
            if not isinstance(value, bool):
                self.fail(where, f"{bad} is not true or false; accepted: {key.accepted()}")
            return value
        if kind in ("str", "name", "choice"):
            if not isinstance(value, str):
                self.fail(where, f"{bad} is not text in quotes; accepted: {key.accepted()}")
            if len(value) > 4000:
                self.fail(where, f"{bad} is {len(value):,} characters long; accepted: at most "
                          "4,000")
            if kind == "name" and not NAME.match(value):
                self.fail(where, f"{bad} is not a name; accepted: {key.accepted()}")
            if kind == "choice" and value not in key.choices:
                self.fail(where, f"{bad} is not known; accepted: {key.accepted()}")
            return value
        if kind == "color":
            if (not isinstance(value, list) or len(value) != 3 or not all(
                    isinstance(c, int) and not isinstance(c, bool) and 0 <= c <= 255
                    for c in value)):
                self.fail(where, f"{bad} is not a colour; accepted: {key.accepted()}")
            return list(value)
        if kind == "points":
            if not isinstance(value, list) or not 3 <= len(value) <= 64:
                self.fail(where, f"{bad} is not a list of 3 to 64 points; accepted: "
                          f"{key.accepted()}")
            pts = [self.value(Key(key.name, "vec2", lo=key.lo, hi=key.hi), p, where, what)
                   for p in value]
            if not _convex(pts):
                self.fail(where, f"{bad} does not go round a convex shape with an area (no "
                          f"three corners in a line, no crossing); accepted: {key.accepted()}")
            return pts
        if kind == "settings":
            return self.settings(value, where, bad, key)
        if kind == "variants":
            if not isinstance(value, list) or not 2 <= len(value) <= 4:
                self.fail(where, f"{bad} is not a list of 2 to 4 tables; accepted: "
                          f"{key.accepted()}")
            return [self.settings(v, where, bad, key) for v in value]
        raise AssertionError(kind)

    def number(self, key: Key, value: Any, where: tuple, bad: str) -> float | int:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(where, f"{bad} is not a number; accepted: {key.accepted()}")
        if key.kind == "int" and not isinstance(value, int):
            if not (math.isfinite(value) and float(value).is_integer()):
                self.fail(where, f"{bad} is not an integer; accepted: {key.accepted()}")
            value = int(value)
        if not math.isfinite(value):
            self.fail(where, f"{bad} is not finite; accepted: {key.accepted()}")
        lo, hi = key.lo, key.hi
        if (lo is not None and (value <= lo if key.above else value < lo)) or (
                hi is not None and value > hi):
            self.fail(where, f"{bad} is out of range; accepted: {key.accepted()}")
        return int(value) if key.kind == "int" else float(value)

    def settings(self, value: Any, where: tuple, bad: str, key: Key) -> dict[str, Any]:
        if not isinstance(value, dict):
            self.fail(where, f"{bad} is not a table; accepted: {key.accepted()}")
        for k, v in value.items():
            if isinstance(v, (dict, list)) or (isinstance(v, float) and not math.isfinite(v)):
                self.fail(where, f"{bad}: {k} = {_shown(v)} is not a setting's value; accepted: "
                          "a number, true or false, or text")
        return dict(value)

    # a whole table
    def table(self, sec: Section, data: Any, where: tuple, what: str) -> dict[str, Any]:
        if not isinstance(data, dict):
            self.fail(where, f"{what} is not a table; write it as [{sec.name}]")
        out: dict[str, Any] = {}
        inner = [s for s in SCHEMA if s.name.startswith(sec.name + ".")]
        for name in data:
            if sec.key(name) is None and not any(s.name == f"{sec.name}.{name}" for s in inner):
                known = [k.name for k in sec.keys] + [s.name.split(".")[-1] for s in inner]
                self.fail(where + (name,), f"{what}: unknown key '{name}'; accepted: "
                          + ", ".join(known))
        for key in sec.keys:
            if key.name in data:
                out[key.name] = self.value(key, data[key.name], where + (key.name,), what)
            elif key.required:
                self.fail(where, f"{what}: '{key.name}' is missing; accepted: {key.accepted()}")
            else:
                out[key.name] = _copy(key.default)
        for s in inner:
            out[s.name.split(".")[-1]] = self.many(s, data.get(s.name.split(".")[-1], []),
                                                   where + (s.name.split(".")[-1],), what)
        return out

    def many(self, sec: Section, data: Any, where: tuple, owner: str = "") -> list[dict]:
        label = sec.name.split(".")[-1]
        if not isinstance(data, list) or not all(isinstance(d, dict) for d in data):
            self.fail(where, f"'{label}' is not a list of tables; write each as "
                      f"[[{sec.name}]]")
        if len(data) > MAX_ITEMS:
            self.fail(where, f"{len(data):,} [[{sec.name}]] tables; accepted: at most "
                      f"{MAX_ITEMS:,}")
        out = []
        for i, d in enumerate(data):
            name = d.get("name") or d.get("label") or d.get("kind")
            what = (f"{owner}, " if owner else "") + f"{label} {i + 1}" + (
                f" ('{name}')" if isinstance(name, str) and name else "")
            out.append(self.table(sec, d, where + (i,), what))
        return out


def _copy(v: Any) -> Any:
    return list(v) if isinstance(v, list) else dict(v) if isinstance(v, dict) else v


def _shown(value: Any, limit: int = 40) -> str:
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = '"' + value + '"'
    else:
        text = repr(value)
    return text if len(text) <= limit else text[:limit - 5] + " ..."


def _convex(pts: list[list[float]]) -> bool:
    """The points go round a convex polygon (either way) with an area: every turn the same way."""
    n = len(pts)
    sign = 0.0
    for i in range(n):
        (ax, ay), (bx, by), (cx, cy) = pts[i], pts[(i + 1) % n], pts[(i + 2) % n]
        cross = (bx - ax) * (cy - by) - (by - ay) * (cx - bx)
        if abs(cross) < 1e-9:
            return False
        if sign and (cross > 0) != (sign > 0):
            return False
        sign = cross
    area = sum(pts[i][0] * pts[(i + 1) % n][1] - pts[(i + 1) % n][0] * pts[i][1]
               for i in range(n))
    return abs(area) > 1e-6 and abs(area) / 2 <= 4 * COORD * COORD


# ----- the file -------------------------------------------------------------------------------
def read_text(path: str) -> str:
    p = Path(path)
    if p.suffix != ".toml":
        raise SceneFileError(path, None, "a scene file's name ends in .toml")
    try:
        if p.is_dir():
            raise SceneFileError(path, None, "is a folder; accepted: a .toml scene file")
        info = p.stat()
        if not stat.S_ISREG(info.st_mode):     # a FIFO would wait for a writer for ever, and
            raise SceneFileError(path, None, "is not a regular file (a FIFO or a device); "
                                 "accepted: a .toml scene file")   # /dev/zero never ends
        if info.st_size > MAX_FILE_BYTES:
            raise SceneFileError(path, None, f"{info.st_size:,} bytes; accepted: a scene file "
                                 f"of at most {MAX_FILE_BYTES:,} bytes")
        with open(p, "rb") as f:
            data = f.read(MAX_FILE_BYTES + 1)    # the file may have grown since stat
    except FileNotFoundError:
        raise SceneFileError(path, None, "no such file; accepted: a .toml scene file that "
                             "exists (python -m app --list shows the shipped ones)") from None
    except OSError as e:
        raise SceneFileError(path, None, f"cannot be read ({e.strerror or e})") from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data[:e.start].count(b"\n") + 1
        raise SceneFileError(path, line, "is not UTF-8 text; accepted: a TOML file in "
                             "UTF-8") from None


def parse(text: str, path: str) -> dict[str, Any]:
    """The TOML data; a syntax error becomes a SceneFileError with the parser's line."""
    try:
        return tomllib.loads(text)
    except RecursionError:          # tomllib parses nested arrays by recursion: [[[[...]]]]
        raise SceneFileError(path, None, "not valid here: arrays or tables nested too deeply; "
                             "accepted: a scene file (docs/experiments.md)") from None
    except tomllib.TOMLDecodeError as e:
        msg = str(e)
        m = re.search(r"\(at line (\d+), column \d+\)", msg)
        line = int(m.group(1)) if m else None
        if m is None and "end of document" in msg:
            line = text.count("\n") + 1
        msg = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", msg)
        raise SceneFileError(path, line, f"not valid TOML: {msg}; accepted: TOML "
                             "(https://toml.io), e.g. key = 1.5 under a [section]") from None


def check_spec(data: dict[str, Any], text: str, path: str) -> dict[str, Any]:
    """Every key checked against the schema and every cross-reference resolved; returns the
    data with every key filled in (defaults where the file is silent), in the schema's order."""
    c = Checker(path, text)
    tops = [s for s in SCHEMA if "." not in s.name]
    for name in data:
        if name not in SECTIONS or "." in name:
            c.fail((name,), f"unknown section '{name}'; accepted: "
                   + ", ".join(f"[{s.name}]" if not s.many else f"[[{s.name}]]" for s in tops))
    spec: dict[str, Any] = {}
    for sec in tops:
        if sec.many:
            spec[sec.name] = c.many(sec, data.get(sec.name, []), (sec.name,))
        elif sec.name in data:
            if isinstance(data[sec.name], list):
                c.fail((sec.name, 0), f"[[{sec.name}]] is written once, as [{sec.name}]")
            spec[sec.name] = c.table(sec, data[sec.name], (sec.name,), f"[{sec.name}]")
        elif sec.required:
            c.fail((), f"the [{sec.name}] table is missing; accepted: a file that starts with "
                   f"[{sec.name}] and a title = \"...\"")
        elif sec.name == "cloth":
            spec[sec.name] = None
        else:
            spec[sec.name] = c.table(sec, {}, (sec.name,), f"[{sec.name}]")
    check_all(c, spec)
    if not spec["body"] and not spec["spawner"] and spec["cloth"] is None:
        c.fail((), "the file holds nothing to simulate; accepted: at least one [[body]], "
               "[[spawner]] or a [cloth]")
    return spec


def load_spec(path: str) -> dict[str, Any]:
    """Read, parse and check a scene file (SceneFileError if it is not accepted)."""
    text = read_text(path)
    return check_spec(parse(text, path), text, path)


def checked_line(path: str, cls) -> str:
    """What `scene check` prints for a file that is accepted: its title, what it holds and its
    metrics (the world is built once, not stepped). SceneFileError for a name that is no file."""
    if cls is None or not path.endswith(".toml"):
        raise SceneFileError(path, None, "a scene file's name ends in .toml")
    scene, spec = cls(), cls.spec
    words = {"body": "bodies", "joint": "joints", "spawner": "spawners", "slider": "sliders",
             "metric": "metrics", "try": "cards"}
    counts = ", ".join(f"{len(spec[k])} {words[k]}" for k in words if spec[k])
    cloth = ", a cloth" if spec["cloth"] is not None else ""
    return (f"{path}: ok: '{cls.title}': {counts}{cloth}; metrics "
            f"{', '.join(scene.metrics()) or 'none'}")
