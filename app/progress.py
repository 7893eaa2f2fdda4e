"""Progress on long work (benchmarks, clip export, `--scene all`, `exercise check all`, a class's
grading): a bar with the time remaining on a terminal (tqdm), plain lines when stderr is not a
terminal (a log, CI, a pipe). Always on stderr, never mixed into --json on stdout.

    from app.progress import Progress

    with Progress(total=len(students), what="grading") as bar:
        for s in students:
            grade(s)
            bar.update(1)                   # or bar.update(1, note=s.name)
    bar.say("a line that must not tear the bar")

Plain lines are few: the first after PLAIN_FIRST seconds (a short run prints none), then one
every PLAIN_EVERY seconds, each with the count, the percentage and the estimated time left, and
a last line if any was printed. tqdm is a well-kept library (the de-facto Python progress bar:
terminal width, rate smoothing, nested bars); `PHYSICS_LAB_PROGRESS=off` turns both off.
"""

from __future__ import annotations

import os
import sys
import time
from typing import IO, Any

PLAIN_FIRST = 10.0      # seconds before the first plain line
PLAIN_EVERY = 10.0      # seconds between plain lines


def on_terminal(stream: IO | None = None) -> bool:
    stream = stream or sys.stderr
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def _duration(seconds: float) -> str:
    seconds = max(0, round(seconds))
    return f"{seconds // 60}:{seconds % 60:02d}" if seconds >= 60 else f"{seconds} s"


class Progress:
    """`total` units of work called `what` (e.g. "steps", "scenes"), shown on `stream`
    (stderr): a tqdm bar on a terminal, else plain lines now and then; total 0: nothing."""

    def __init__(self, total: int, what: str, unit: str = "", stream: IO | None = None,
                 clock=time.monotonic):
        self.total, self.what, self.unit = max(0, int(total)), what, unit
        self.stream = stream or sys.stderr
        self.out = self.stream          # where say() prints, bar or not
        self.done = 0
        self.note = ""
        self._clock = clock
        self._start = clock()
        self._next_line = self._start + PLAIN_FIRST
        self._printed = False
        self._bar: Any = None
        if self.total == 0 or os.environ.get("PHYSICS_LAB_PROGRESS", "").lower() in (
                "off", "0", "no"):         # nothing to count (one scene of `--scene all`), or off
            self.stream = None
        elif on_terminal(self.stream):
            try:
                from tqdm import tqdm
            except ImportError:          # not installed: plain lines on the terminal too
                tqdm = None
            if tqdm is not None:
                self._bar = tqdm(total=self.total, desc=what, unit=unit or "it",
                                 file=self.stream, leave=False, dynamic_ncols=True,
                                 mininterval=0.5)

    def update(self, n: int = 1, note: str = "") -> None:
        self.done += n
        if note:
            self.note = note
        if self.stream is None:
            return
        if self._bar is not None:
            if note:
                self._bar.set_postfix_str(note, refresh=False)
            self._bar.update(n)
            return
        now = self._clock()
        if now >= self._next_line and self.done < self.total:
            self._next_line = now + PLAIN_EVERY
            self._line(now)

    def _line(self, now: float) -> None:
        elapsed = now - self._start
        part = self.done / self.total if self.total else 1.0
        left = f", ~{_duration(elapsed * (1 - part) / part)} left" if 0 < part < 1 else ""
        note = f" ({self.note})" if self.note else ""
        unit = f" {self.unit}" if self.unit else ""
        print(f"  .. {self.what}: {self.done}/{self.total}{unit} ({100 * part:.0f}%), "
              f"{_duration(elapsed)}{left}{note}", file=self.stream, flush=True)
        self._printed = True

    def say(self, text: str) -> None:
        """A line on the stream that does not tear the bar."""
        if self._bar is not None:
            self._bar.write(text, file=self.out)
        else:
            print(text, file=self.out, flush=True)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        elif self._printed and self.stream is not None:
            self._printed = False
            self._line(self._clock())

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


__all__ = ["Progress", "on_terminal", "PLAIN_FIRST", "PLAIN_EVERY"]
