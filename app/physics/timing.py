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
from contextlib import contextmanager
from typing import Iterator


class Stopwatch:
    """Wall seconds spent per name, summed (`spent`, a dict: 0.0 for a name never timed)."""

    def __init__(self) -> None:
        self.spent: defaultdict[str, float] = defaultdict(float)

    @contextmanager
    def __call__(self, name: str) -> Iterator[None]:
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.spent[name] += time.perf_counter() - t0
