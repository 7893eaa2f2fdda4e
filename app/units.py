"""How a number is written on screen: one unit per quantity, and no rounding noise shown as a value.

A scene's metrics keep the units of the JSON (pixels, seconds, kilograms; fractions, not
percent: the README's metric reference). On screen a quantity may read better in another unit
(the mass-spring cloth's energy in joules, a stretch in percent): the scene declares it once, in
`Scene.metric_units`, and the HUD and the metrics strip both write the value through `shown()`,
so the two places never disagree.

    metric_units = {"energy": Unit("J", 1 / 256**2, resolution=1e-3),
                    "max_stretch": Unit("%", 100, resolution=0.01)}

`resolution` is the smallest magnitude that means something: a value below it is written 0
(after a rollback the cloth's energy came out as 3.223e-25 J and a stretch as 3.55e-15, the
rounding of a sum of large terms, not a measurement).

Plain Python, no pygame: the Scene contract and the headless runner use it too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Unit:
    """A metric as the screen writes it: value x `factor`, followed by `symbol`; magnitudes
    below `resolution` (in the shown unit) are written 0."""

    symbol: str = ""
    factor: float = 1.0
    resolution: float = 0.0
    digits: int = 4          # significant digits written

    def convert(self, value: float) -> float:
        shown = value * self.factor
        return 0.0 if abs(shown) < self.resolution else shown


PLAIN = Unit()


def fmt_number(x: Any, digits: int = 4) -> str:
    """A compact form of a number: integers as they are, floats with `digits` significant digits
    (whole numbers below 1e5 in full, never in powers of ten), "-" for a value that does not exist
    yet (None; null in JSON), yes/no for a truth value."""
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(v):
        return str(v)
    if v.is_integer() and abs(v) < 1e9:
        return str(int(v))
    if abs(v) >= 1e5 or abs(v) < 1e-3:
        return f"{v:.{min(digits, 3)}g}"
    if abs(v) >= 10 ** (digits - 1):     # 1680.4 at 3 digits: '1680', not '1.68e+03'
        return str(round(v))
    return f"{v:.{digits}g}"


def shown(value: Any, unit: Unit = PLAIN) -> str:
    """`value` written in `unit`: '-48.51 J', '0 J' for noise, '7.3%', '-' for None."""
    if value is None or isinstance(value, (bool, str)):
        return fmt_number(value)
    try:
        v = float(value)
    except (TypeError, ValueError):
        return str(value)
    if not math.isfinite(v):
        return fmt_number(v)
    text = fmt_number(unit.convert(v), unit.digits) if unit is not PLAIN else fmt_number(value)
    if not unit.symbol:
        return text
    return text + unit.symbol if unit.symbol == "%" else f"{text} {unit.symbol}"


__all__ = ["Unit", "PLAIN", "fmt_number", "shown"]
