"""Metrics over time: the live plot's rolling history and the `--csv` file.

    python -m app --headless --scene cloth --seconds 5 --csv cloth.csv           a row per step
    python -m app --scene cloth --csv cloth.csv                                 a row per frame

The CSV has a header row: `step` (fixed steps since the run started, R included), `t (s)` (the
scene's simulated seconds since it was last built: R starts it at 0 again), then every metric the
scene reports, in its order (with --compare a first column `variant`: the variant as given, one
row per variant per step). Values are written as --json writes them: numbers in full precision
and in the JSON's units (pixels, seconds, fractions), true/false, text as it is, and an empty
cell for null (a value that does not exist yet). A column's header is the metric's name followed
by that unit, `penetration_max (px)`, `energy (kg px^2/s^2)` (Scene.json_unit: the reference's
unit); a count, a ratio, a truth value or text has the bare name, and so has a metric the
reference does not describe (an exercise scene's own, whose names carry their unit: `apart_px`).

Plain Python, no pygame.
"""

from __future__ import annotations

import csv
import json
import math
from collections import deque
from typing import Any, Callable, Mapping

MAX_WINDOW = 120.0       # seconds of history kept for the live plot (its longest window)


def clean(value: Any) -> Any:
    """Make a value JSON-safe: NumPy scalars to Python numbers, NaN and infinities to None."""
    if isinstance(value, dict):
        return {str(k): clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def cell(value: Any) -> str:
    """One CSV cell, as --json writes the value ('' for null)."""
    value = clean(value)
    if value is None:
        return ""
    if isinstance(value, str):
        return value
    return json.dumps(value)


def header(name: str, unit: str) -> str:
    """A CSV column's header: the name, then its unit in parentheses (none for a count, a
    ratio, text, a truth value or an unknown unit)."""
    from app.docs.texts import UNITLESS
    return f"{name} ({unit})" if unit and unit not in UNITLESS else name


def plottable(metrics: Mapping[str, Any]) -> dict[str, float]:
    """The metrics a plot can draw: numbers (a truth value as 0 or 1); a value that does not
    exist yet (None) or is not finite is NaN (a gap in the line); text is left out."""
    out: dict[str, float] = {}
    for k, v in metrics.items():
        if isinstance(v, str):
            continue
        if v is None:
            out[k] = math.nan
            continue
        try:
            out[k] = float(v)
        except (TypeError, ValueError):
            continue
    return out


class History:
    """A pane's metrics over the last MAX_WINDOW simulated seconds, for the live plot. A sample
    at a time not after the last one (a reset, a rollback) first drops what lies at or after it:
    the plot shows the world that is."""

    def __init__(self, keep: float = MAX_WINDOW):
        self.keep = keep
        self.samples: deque[tuple[float, dict[str, float]]] = deque()

    def add(self, t: float, metrics: Mapping[str, Any]) -> None:
        while self.samples and self.samples[-1][0] >= t:
            self.samples.pop()
        self.samples.append((t, plottable(metrics)))
        while self.samples and self.samples[0][0] < t - self.keep:
            self.samples.popleft()

    def clear(self) -> None:
        self.samples.clear()

    @property
    def now(self) -> float | None:
        return self.samples[-1][0] if self.samples else None

    def series(self, name: str, since: float) -> tuple[list[float], list[float]]:
        """(times, values) of metric `name` from `since` on."""
        ts, vs = [], []
        for t, m in self.samples:
            if t >= since and name in m:
                ts.append(t)
                vs.append(m[name])
        return ts, vs

    def names(self) -> list[str]:
        """The plottable metrics of the last sample, in the scene's order."""
        return list(self.samples[-1][1]) if self.samples else []


class CsvLog:
    """The --csv file: a header from the first row's metrics, then a row per call. A metric that
    first appears later has no column: `warn` is told once per such name (nothing is lost
    silently). The rows go to a temporary file beside `path` (app/outputs.py), renamed into
    place by close(): a run that fails or is interrupted leaves the old file as it was. A write
    that fails (a full disk) stops the rows; close() then raises OutputError, one line."""

    def __init__(self, path: str, compare: bool = False,
                 warn: Callable[[str], None] | None = None):
        from app.outputs import Pending
        self.path = path
        self.compare = compare
        self.warn = warn
        self.pending = Pending(path, "--csv")
        self.file = open(self.pending.tmp, "w", newline="", encoding="utf-8")
        self.writer = csv.writer(self.file)
        self.error: OSError | None = None      # the write that failed, if one did
        self.columns: list[str] | None = None
        self.rows = 0
        self._warned: set[str] = set()

    def row(self, step: int, t: float, metrics: Mapping[str, Any], variant: str = "",
            unit: Callable[[str], str] | None = None) -> None:
        """One row; the first also writes the header, each metric with its `unit(name)`."""
        if self.error is not None:
            return
        try:
            self._row(step, t, metrics, variant, unit)
        except OSError as e:            # a full disk: the run goes on, close() says so
            self.error = e

    def _row(self, step: int, t: float, metrics: Mapping[str, Any], variant: str,
             unit: Callable[[str], str] | None) -> None:
        if self.columns is None:
            self.columns = list(metrics)
            self.writer.writerow((["variant"] if self.compare else []) + ["step", header("t", "s")]
                                 + [header(k, unit(k) if unit else "") for k in self.columns])
        extra = [k for k in metrics if k not in self.columns and k not in self._warned]
        if extra and self.warn is not None:
            self._warned.update(extra)
            self.warn(f"--csv {self.path}: metric(s) {', '.join(extra)} appeared after the "
                      "header was written; not in the file")
        self.writer.writerow(([variant] if self.compare else []) + [cell(step), cell(t)]
                             + [cell(metrics.get(k)) for k in self.columns])
        self.rows += 1

    @property
    def replaced(self) -> bool:
        """True if the file renamed into place replaced one that was there."""
        return self.pending.replaced

    def flush(self) -> None:
        if not self.file.closed and self.error is None:
            try:
                self.file.flush()
            except OSError as e:
                self.error = e

    def close(self) -> None:
        """Finish the file and rename it into place; OutputError (one line) if a write failed:
        then the old file is left as it was."""
        from app.outputs import OutputError
        if self.file.closed:
            return
        try:
            self.file.close()
        except OSError as e:
            self.error = self.error or e
        if self.error is not None:
            self.pending.discard()
            raise OutputError(self.pending.failed(self.error))
        self.pending.commit(allow_empty=True)

    def discard(self) -> None:
        """Stop without writing: the old file is left as it was."""
        try:
            self.file.close()
        except OSError:
            pass
        self.pending.discard()


__all__ = ["clean", "cell", "header", "plottable", "History", "CsvLog", "MAX_WINDOW"]
