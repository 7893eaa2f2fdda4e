"""Write a scene file: checked data (app/scenefile/load.py) back to TOML with tomli-w, in the
schema's order, leaving out every key at its default (a file as short as a person would write).

    text = dumps(load_spec("scenes/files/seesaw.toml"))
    save(spec, "my_seesaw.toml")          # a temporary file beside it, then renamed into place

Reading what was written gives the same data back (tests/test_scenefiles.py), and writing that
again gives the same text.
"""

from __future__ import annotations

import re
from typing import Any

import tomli_w

from app.outputs import write_text
from app.scenefile.schema import SCHEMA, Section

HEADER = ("# A scene file of the physics lab: python -m app --scene THIS.toml "
          "(docs/experiments.md)\n")


def _table(sec: Section, data: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key in sec.keys:
        value = data.get(key.name)
        if value is None or (not key.required and value == key.default):
            continue
        out[key.name] = value
    for inner in SCHEMA:
        if inner.name.startswith(sec.name + "."):
            label = inner.name.split(".")[-1]
            items = [_table(inner, d) for d in data.get(label) or []]
            if items:
                out[label] = items
    return out


def to_data(spec: dict[str, Any]) -> dict[str, Any]:
    """The file's data without the keys at their defaults (sections left empty dropped)."""
    out: dict[str, Any] = {}
    for sec in SCHEMA:
        if "." in sec.name or spec.get(sec.name) is None:
            continue
        if sec.many:
            items = [_table(sec, d) for d in spec[sec.name]]
            if items:
                out[sec.name] = items
        else:
            table = _table(sec, spec[sec.name])
            if table or sec.required or sec.name == "cloth":
                out[sec.name] = table
    return out


# tomli-w writes every array one item a line; a point [x, y] and a short list of points read
# better on one line, as a person writes them.
_NUMBER = r"-?[0-9][0-9.eE+\-]*"
_FLAT = re.compile(r"\[\n(?:[ ]+" + _NUMBER + r",\n)+[ ]*\]")
_POINTS = re.compile(r"\[\n(?:[ ]+\[[^\[\]\n]*\],\n)+[ ]*\]")


def _one_line(m: re.Match) -> str:
    items = [i.strip().rstrip(",") for i in m.group(0)[1:-1].split("\n") if i.strip()]
    return "[" + ", ".join(items) + "]"


def dumps(spec: dict[str, Any]) -> str:
    text = tomli_w.dumps(to_data(spec), multiline_strings=True)
    text = _POINTS.sub(_one_line, _FLAT.sub(_one_line, text))
    return HEADER + "\n" + text


def save(spec: dict[str, Any], path: str) -> None:
    """Write the file whole or not at all (app/outputs.py: a temporary file beside `path`,
    then renamed into place; OutputError, an OSError, if it cannot be written)."""
    write_text(path, dumps(spec), what="scene file")
