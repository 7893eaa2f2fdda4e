"""Declared settings: a scene's parameters (`Param`) and effects (`Effect`), and the one
validation behind the command line, the panel and the try cards (`Param.parse`).

Plain Python and NumPy (no pygame); app.scene re-exports every name, so a scene imports them from
there: `from app.scene import Param, Effect, common`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np


class ParamError(ValueError):
    """A parameter value (or name) that the scene does not accept; the message is one line."""


TRUE_WORDS = ("on", "true", "yes", "1")
FALSE_WORDS = ("off", "false", "no", "0")


@dataclass(frozen=True)
class Param:
    """A tunable value of a scene.

    kind is int, float, bool or str (str needs `choices`). Numbers need `lo` and `hi` (inclusive).
    `rebuild=True` means a change rebuilds the scene (e.g. grid size); False means the scene reads
    the new value on its next step (e.g. constraint iterations).
    """

    name: str
    default: Any
    kind: type
    lo: float | None = None
    hi: float | None = None
    choices: tuple[str, ...] | None = None
    help: str = ""
    rebuild: bool = True

    def accepted(self) -> str:
        """Describe the accepted values, for error messages and the help text."""
        if self.kind is bool:
            return "on or off"
        if self.choices is not None:
            return "one of " + ", ".join(self.choices)
        word = "an integer" if self.kind is int else "a number"
        return f"{word} from {_fmt(self.lo)} to {_fmt(self.hi)}"

    def parse(self, value: Any) -> Any:
        """Return `value` (text from the command line or the panel, or a Python value) converted
        to this parameter's type; raise ParamError naming the problem and what is accepted."""
        bad = f"parameter '{self.name}' got {shown_text(value)}"
        if self.kind is bool:
            if isinstance(value, (bool, np.bool_)):
                return bool(value)
            word = str(value).strip().lower()
            if word in TRUE_WORDS:
                return True
            if word in FALSE_WORDS:
                return False
            raise ParamError(f"{bad}: accepted values are {self.accepted()}")
        if self.choices is not None:
            word = str(value).strip()
            if word not in self.choices:
                raise ParamError(f"{bad}: accepted values are {self.accepted()}")
            return word
        if isinstance(value, (bool, np.bool_)):
            raise ParamError(f"{bad}: not a number; accepted: {self.accepted()}")
        if isinstance(value, str) and not plain_number(value):
            word = "an integer" if self.kind is int else "a number"
            raise ParamError(f"{bad}: not {word} in plain ASCII digits (no '_' separators); "
                             f"accepted: {self.accepted()}")
        if self.kind is int:
            number = _parse_int(value)
            if number is None:
                raise ParamError(f"{bad}: not an integer; accepted: {self.accepted()}")
        else:
            try:
                number = float(value)
            except (TypeError, ValueError):
                raise ParamError(f"{bad}: not a number; accepted: {self.accepted()}") from None
            if not math.isfinite(number):
                raise ParamError(f"{bad}: must be finite; accepted: {self.accepted()}")
        if (self.lo is not None and number < self.lo) or (self.hi is not None and number > self.hi):
            raise ParamError(f"{bad}: out of range; accepted: {self.accepted()}")
        return number


def plain_number(text: str) -> bool:
    """Python's int() and float() also read '1_0' and other scripts' digits ('١٠' is 10); a
    command line that means one thing everywhere accepts ASCII digits, sign, point and exponent
    only (and the words inf and nan, which the range check then refuses by name)."""
    t = text.strip()
    return t.isascii() and "_" not in t


def _parse_int(value: Any) -> int | None:
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return int(value) if math.isfinite(value) and float(value).is_integer() else None
    try:
        return int(str(value).strip())
    except ValueError:
        return None


def shown_text(value: Any, limit: int = 40) -> str:
    """repr(value) for a one-line message, cut to about `limit` characters (a 5,000-digit
    number or a pasted file echoed in full would bury the message)."""
    text = repr(value)
    if len(text) <= limit:
        return text
    return f"{text[:limit - 10]}... ({len(str(value)):,} characters)"


def _fmt(x: float | None) -> str:
    if x is None:
        return "any"
    return str(int(x)) if float(x).is_integer() else f"{x:g}"


@dataclass(frozen=True)
class Effect:
    """A physical effect a scene can simulate. Off means it costs nothing: the scene's step must
    not compute it at all (no zero-filled force, no loop skipped by an `if` per element)."""

    name: str
    default: bool = True
    help: str = ""
    rebuild: bool = False
    amount: str = ""      # the param that sets how strong it is, if any (named in errors)


# Every scene has these; a scene may re-declare one (same name) to change its default or range.
COMMON_PARAMS: tuple[Param, ...] = (
    Param("hertz", 60, int, 1, 1000, help="physics steps per simulated second (dt = 1/hertz)",
          rebuild=False),
    Param("substeps", 1, int, 1, 50, help="sub-steps inside each step (each of dt/substeps)",
          rebuild=False),
    Param("seed", 0, int, 0, 2**31 - 1, help="seed of the scene's random numbers"),
)


def common(name: str, **changes: Any) -> Param:
    """A common param (hertz, substeps, seed) with some fields changed, for a scene that needs,
    say, another default: `params = (common("substeps", default=30), ...)`."""
    prm = next(p for p in COMMON_PARAMS if p.name == name)
    return replace(prm, **changes)
