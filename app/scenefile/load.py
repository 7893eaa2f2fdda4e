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
import tomllib
from pathlib import Path
from typing import Any

from app.scenefile.schema import (COORD, MIN_AREA, MIN_SIZE, SCHEMA, SECTIONS, Key, Section,
                                  field_key, slider_fields)

MAX_FILE_BYTES = 1_000_000      # a scene file is a page of text; a bigger one is no scene
MAX_ITEMS = 2000                # bodies, joints, ... per section (a step must stay cheap)
NAME = re.compile(r"[A-Za-z][A-Za-z0-9_\-]{0,39}\Z")
WORLD = "world"                 # a joint's a or b that means a fixed point


class SceneFileError(ValueError):
    """A scene file that is not accepted: str() is one line, 'FILE:LINE: what; accepted: ...'."""

    def __init__(self, path: str, line: int | None, message: str):
        self.path, self.line, self.message = path, line, message
        super().__init__(f"{path}:{line}: {message}" if line else f"{path}: {message}")


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
        size = p.stat().st_size
        if size > MAX_FILE_BYTES:
            raise SceneFileError(path, None, f"{size:,} bytes; accepted: a scene file of at "
                                 f"most {MAX_FILE_BYTES:,} bytes")
        data = p.read_bytes()
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
    _check_bodies(c, spec)
    _check_joints(c, spec)
    _check_names(c, spec)
    _check_sliders(c, spec)
    _check_metrics(c, spec)
    if not spec["body"] and not spec["spawner"] and spec["cloth"] is None:
        c.fail((), "the file holds nothing to simulate; accepted: at least one [[body]], "
               "[[spawner]] or a [cloth]")
    return spec


def load_spec(path: str) -> dict[str, Any]:
    """Read, parse and check a scene file (SceneFileError if it is not accepted)."""
    text = read_text(path)
    return check_spec(parse(text, path), text, path)


# ----- cross-checks -------------------------------------------------------------------------
SHAPE_NEEDS = {"circle": ("radius",), "box": ("size",), "polygon": ("points",),
               "segment": ("a", "b")}
SHAPE_TAKES = {"circle": {"radius", "offset"}, "box": {"size", "offset", "radius"},
               "polygon": {"points", "radius"}, "segment": {"a", "b", "radius"}}
COMMON_SHAPE = {"kind", "friction", "elasticity", "group"}

JOINT_NEEDS = {"pin": (), "pivot": (), "slide": ("min", "max"), "groove": ("groove_a",
                                                                          "groove_b"),
               "damped_spring": ("stiffness",), "damped_rotary_spring": ("stiffness",),
               "rotary_limit": ("min", "max"), "motor": ("rate",)}
JOINT_TAKES = {"pin": {"anchor_a", "anchor_b"}, "pivot": {"anchor_a", "anchor_b", "pivot"},
               "slide": {"anchor_a", "anchor_b", "min", "max"},
               "groove": {"groove_a", "groove_b", "anchor_b"},
               "damped_spring": {"anchor_a", "anchor_b", "rest_length", "stiffness", "damping"},
               "damped_rotary_spring": {"rest_angle", "stiffness", "damping"},
               "rotary_limit": {"min", "max"}, "motor": {"rate"}}
COMMON_JOINT = {"kind", "name", "a", "b", "max_force", "collide", "error_bias"}


def _given(c: Checker, where: tuple) -> set[str]:
    """The keys the file itself wrote in the table at `where` (not filled-in defaults)."""
    return {p[-1] for p in c.lines if len(p) == len(where) + 1 and p[:-1] == where}


MAX_SHAPES = 5000              # shapes in all: a step of a few ms, not of seconds


def _check_bodies(c: Checker, spec: dict) -> None:
    shapes = sum(len(b["shape"]) for b in spec["body"])
    if shapes > MAX_SHAPES:
        c.fail(("body",), f"{shapes:,} shapes in all; accepted: at most {MAX_SHAPES:,}")
    seen: dict[str, int] = {}
    for i, body in enumerate(spec["body"]):
        where, what = ("body", i), f"body '{body['name']}'"
        if body["name"] in seen:
            c.fail(where + ("name",), f"{what}: the name is taken by body {seen[body['name']]}"
                   "; accepted: a name no other body has")
        if body["name"] == WORLD:
            c.fail(where + ("name",), f"{what}: \"world\" means a fixed point in joints; "
                   "accepted: another name")
        seen[body["name"]] = i + 1
        dynamic = body["type"] == "dynamic"
        if dynamic and body["mass"] is None and body["density"] is None:
            c.fail(where, f"{what}: a dynamic body needs a mass; accepted: mass = NUMBER or "
                   "density = NUMBER")
        if body["mass"] is not None and body["density"] is not None:
            c.fail(where + ("density",), f"{what}: give mass or density, not both")
        if not dynamic:
            for k in ("mass", "density", "moment"):
                if body[k] is not None:
                    c.fail(where + (k,), f"{what}: a {body['type']} body has no {k}; accepted: "
                           "mass, density and moment on dynamic bodies only")
        if dynamic and not body["shape"] and body["moment"] is None:
            c.fail(where, f"{what}: a dynamic body without shapes needs a moment; accepted: "
                   "a [[body.shape]] or moment = NUMBER")
        for j, shape in enumerate(body["shape"]):
            sw = where + ("shape", j)
            kind = shape["kind"]
            for k in SHAPE_NEEDS[kind]:
                if shape[k] is None or (k == "radius" and shape[k] < MIN_SIZE):
                    key = SECTIONS["body.shape"].key(k)
                    if k == "radius":
                        key = Key(k, "float", lo=MIN_SIZE, hi=key.hi, unit=key.unit)
                    c.fail(sw + ((k,) if shape[k] is not None else ()),
                           f"{what}, shape {j + 1}: a {kind} needs {k}"
                           + (f" of at least {MIN_SIZE:g}" if k == "radius" else "")
                           + f"; accepted: {key.accepted()}")
            for k in _given(c, sw) - COMMON_SHAPE - SHAPE_TAKES[kind]:
                c.fail(sw + (k,), f"{what}, shape {j + 1}: a {kind} has no '{k}'; accepted: "
                       + ", ".join(sorted(COMMON_SHAPE | SHAPE_TAKES[kind])))
        if body["density"] is not None and _area(body) < MIN_AREA:
            c.fail(where + ("density",), f"{what}: its shapes have no area, so a density gives "
                   "no mass; accepted: mass = NUMBER, or shapes with an area")
        if dynamic and body["moment"] is None and body["shape"] and _area(body) < MIN_AREA:
            c.fail(where, f"{what}: its shapes have no area to spread the mass over (segments "
                   "of radius 0); accepted: moment = NUMBER, or a segment radius above 0")


def _area(body: dict) -> float:
    import pymunk
    total = 0.0
    for s in body["shape"]:
        if s["kind"] == "circle":
            total += math.pi * s["radius"] ** 2
        elif s["kind"] == "box":
            total += s["size"][0] * s["size"][1]
        elif s["kind"] == "polygon":
            total += pymunk.area_for_poly([tuple(p) for p in s["points"]], s["radius"])
        else:
            total += pymunk.area_for_segment(tuple(s["a"]), tuple(s["b"]), s["radius"])
    return total


def _check_joints(c: Checker, spec: dict) -> None:
    bodies = {b["name"]: b for b in spec["body"]}
    for i, joint in enumerate(spec["joint"]):
        where, kind = ("joint", i), joint["kind"]
        what = f"joint {i + 1} ({kind}" + (f" '{joint['name']}')" if joint["name"] else ")")
        for end in ("a", "b"):
            if joint[end] != WORLD and joint[end] not in bodies:
                c.fail(where + (end,), f"{what}: {end} = \"{joint[end]}\" names no body; "
                       f"accepted: \"world\" or one of " + ", ".join(
                           f"\"{n}\"" for n in list(bodies)[:20]) + (" ..." if len(bodies) > 20
                                                                    else ""))
        if joint["a"] == joint["b"]:
            c.fail(where + ("b",), f"{what}: a and b are the same body; accepted: two bodies")
        ends = [bodies.get(joint[e]) for e in ("a", "b")]
        if all(e is None or e["type"] != "dynamic" for e in ends):
            c.fail(where, f"{what}: neither end is a dynamic body, so it holds nothing; "
                   "accepted: at least one dynamic body")
        for k in JOINT_NEEDS[kind]:
            if joint[k] is None:
                c.fail(where, f"{what}: a {kind} joint needs '{k}'; accepted: "
                       f"{SECTIONS['joint'].key(k).accepted()}")
        for k in _given(c, where) - COMMON_JOINT - JOINT_TAKES[kind]:
            c.fail(where + (k,), f"{what}: a {kind} joint has no '{k}'; accepted: "
                   + ", ".join(sorted(COMMON_JOINT | JOINT_TAKES[kind])))
        if kind in ("slide", "rotary_limit") and joint["min"] > joint["max"]:
            c.fail(where + ("max",), f"{what}: min {joint['min']:g} is above max "
                   f"{joint['max']:g}; accepted: min <= max")
        if kind == "slide" and joint["min"] < 0:
            c.fail(where + ("min",), f"{what}: a slide joint's min is a distance; accepted: "
                   "min from 0")
        if kind == "groove" and joint["groove_a"] == joint["groove_b"]:
            c.fail(where + ("groove_b",), f"{what}: the groove's two ends are one point; "
                   "accepted: two different points")
        if kind == "groove" and joint["a"] == WORLD:
            pass       # a groove on the world: fine, its ends are world points


def _check_names(c: Checker, spec: dict) -> None:
    for sec, key in (("joint", "name"), ("spawner", "name"), ("metric", "name"),
                     ("slider", "name"), ("try", "label")):
        seen: set[str] = set()
        for i, item in enumerate(spec[sec]):
            name = item[key]
            if not name:
                continue
            if name in seen:
                c.fail((sec, i, key), f"{sec} {i + 1}: {key} \"{name}\" is given twice; "
                       f"accepted: a {key} no other {sec} has")
            seen.add(name)
    bodies = {b["name"] for b in spec["body"]}
    for i, sp in enumerate(spec["spawner"]):
        clash = next((b for b in bodies if re.fullmatch(re.escape(sp["name"]) + r"\d+", b)),
                     None)
        if clash:
            c.fail(("spawner", i, "name"), f"spawner '{sp['name']}': its balls would be called "
                   f"like body '{clash}'; accepted: another name")


def matches(target: str, name: str) -> bool:
    """A target is a name, 'prefix*' (every name that starts with prefix) or '*' (all)."""
    return name.startswith(target[:-1]) if target.endswith("*") else name == target


def _check_sliders(c: Checker, spec: dict) -> None:
    from app.pymunk_scene import PYMUNK_PARAMS
    from app.scene import COMMON_PARAMS
    taken = {p.name for p in PYMUNK_PARAMS + COMMON_PARAMS} | {"gravity"}
    for i, s in enumerate(spec["slider"]):
        where, what = ("slider", i), f"slider '{s['name']}'"
        if s["name"] in taken:
            c.fail(where + ("name",), f"{what}: the name is the lab's own setting; accepted: "
                   "a name other than " + ", ".join(sorted(taken)))
        found = field_key(s["field"])
        if found is None:
            prefix = s["field"].split(".")[0]
            fields = [f for f in slider_fields() if f.startswith(prefix + ".")]
            c.fail(where + ("field",), f"{what}: field \"{s['field']}\" is no number a slider "
                   "can set; accepted: " + (", ".join(fields) if fields else
                                            "SECTION.KEY, SECTION one of world, body, shape, "
                                            "joint, spawner, cloth (e.g. joint.stiffness)"))
        sec, key, part = found
        if s["lo"] >= s["hi"]:
            c.fail(where + ("hi",), f"{what}: lo {s['lo']:g} is not below hi {s['hi']:g}")
        inside = Key(key.name, "float", None, lo=key.lo, hi=key.hi, above=key.above,
                     unit=key.unit)
        for end in ("lo", "hi"):
            v = s[end]
            if (key.lo is not None and (v <= key.lo if key.above else v < key.lo)) or (
                    key.hi is not None and v > key.hi):
                c.fail(where + (end,), f"{what}: {end} {v:g} is outside what {s['field']} "
                       f"accepts; accepted: {inside.accepted()}")
            if key.kind == "int" and not float(v).is_integer():
                c.fail(where + (end,), f"{what}: {end} {v:g}: {s['field']} is an integer")
        items = _targets(spec, sec.name, s["target"])
        if not items:
            c.fail(where + ("target",), f"{what}: target \"{s['target']}\" matches no "
                   f"{_owner(sec.name)}; accepted: a name, \"prefix*\" or \"*\"")
        start = slider_start(spec, s)
        if start is None:
            c.fail(where, f"{what}: its targets do not set {s['field']}, so there is no "
                   "value to start from; accepted: default = NUMBER")
        if not s["lo"] <= start <= s["hi"]:
            c.fail(where + ("default",), f"{what}: its starting value {start:g} is "
                   f"outside lo..hi ({s['lo']:g}..{s['hi']:g}); accepted: a default within them")


def slider_start(spec: dict, slider: dict) -> float | None:
    """A slider's starting value: its `default`, else the file's value of its first target."""
    if slider["default"] is not None:
        return slider["default"]
    found = field_key(slider["field"])
    if found is None:
        return None
    sec, key, part = found
    items = _targets(spec, sec.name, slider["target"])
    value = items[0][key.name] if items else None
    if value is None:
        return None
    return float(value[part] if part is not None else value)


def _owner(section: str) -> str:
    return {"body": "body", "body.shape": "body", "joint": "joint with a name",
            "spawner": "spawner", "cloth": "cloth"}.get(section, section)


def _targets(spec: dict, section: str, target: str) -> list[dict]:
    """The tables a slider's field points at: bodies, the shapes of matching bodies, joints,
    spawners, the world or the cloth."""
    if section == "world":
        return [spec["world"]]
    if section == "cloth":
        return [spec["cloth"]] if spec["cloth"] is not None else []
    if section == "body.shape":
        return [s for b in spec["body"] if matches(target, b["name"]) for s in b["shape"]]
    return [x for x in spec[section] if x.get("name") and matches(target, x["name"])]


def _check_metrics(c: Checker, spec: dict) -> None:
    from app.scenefile.schema import METRIC_HELP
    bodies = [b["name"] for b in spec["body"]]
    joints = {j["name"]: j for j in spec["joint"] if j["name"]}
    spawners = {s["name"] for s in spec["spawner"]}
    for i, m in enumerate(spec["metric"]):
        where, what = ("metric", i), f"metric '{m['name']}'"
        owner = METRIC_HELP[m["kind"]][1]
        if owner == "joint" and not any(matches(m["target"], n) for n in joints):
            c.fail(where + ("target",), f"{what}: target \"{m['target']}\" names no joint; "
                   "accepted: " + (", ".join(f"\"{n}\"" for n in joints) or
                                   "a joint's name (give the joint a name = \"...\")"))
        if owner == "spawner" and m["target"] not in spawners:
            c.fail(where + ("target",), f"{what}: target \"{m['target']}\" names no spawner; "
                   "accepted: " + (", ".join(f"\"{n}\"" for n in spawners) or "none: the file "
                                   "has no [[spawner]]"))
        if owner == "cloth" and spec["cloth"] is None:
            c.fail(where + ("kind",), f"{what}: {m['kind']} measures the cloth and the file "
                   "has no [cloth]")
        if owner == "bodies" and m["target"] != "*" and not m["target"].endswith("*") \
                and m["target"] not in bodies:
            c.fail(where + ("target",), f"{what}: target \"{m['target']}\" names no body; "
                   "accepted: a body's name, \"prefix*\" or \"*\"")
        if m["zero_y"] is not None and m["kind"] not in ("potential_energy", "energy",
                                                         "energy_ratio", "energy_drift"):
            c.fail(where + ("zero_y",), f"{what}: zero_y is for the energies only")
