"""Timing from outside the formulas: a stopwatch that adds up wall time per name.

The physics reads like its formulas; what each part costs is measured around it, not inside it:

    watch = Stopwatch()
    with watch("gravity"):
        v[1] += g * h * h
    watch.spent["gravity"]       # seconds, summed over every use

The HUD's cost per effect (and the benchmark's) comes from these sums.
"""

from __future__ import annotations

import time
from collections import defaultdict


class _Lap:
    """The context one name times with (a plain class: a few hundred ns per use, where a
    generator-based contextmanager costs a few microseconds, which a sweep of a small cloth
    would notice)."""

    __slots__ = ("watch", "spent", "name", "t0")

    def __init__(self, watch: "Stopwatch", name: str) -> None:
        self.watch, self.spent, self.name, self.t0 = watch, watch.spent, name, 0.0

    def __enter__(self) -> None:
        self.t0 = self.watch.clock()

    def __exit__(self, *exc: object) -> None:
        self.spent[self.name] += self.watch.clock() - self.t0


class Stopwatch:
    """Wall seconds spent per name, summed (`spent`, a dict: 0.0 for a name never timed).
    `clock` is what it reads (a benchmark on a busy machine may set time.process_time)."""

    def __init__(self) -> None:
        self.clock = time.perf_counter
        self.spent: defaultdict[str, float] = defaultdict(float)
        self._laps: dict[str, _Lap] = {}

    def __call__(self, name: str) -> _Lap:
        lap = self._laps.get(name)
        if lap is None:
            lap = self._laps[name] = _Lap(self, name)
        return lap
