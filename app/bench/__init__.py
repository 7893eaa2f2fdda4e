"""Benchmarks: `python -m app bench [cloth|integrators|pymunk|mass_spring|particles|clips|frames|all] [--json] [--out DIR] [--quick]`.

Speed is measured here, never asserted in tests. Every figure is a median over repeated runs, and
every comparison is a ratio against a baseline run in the same process, so the numbers mean the
same on a slow machine and a fast one. Each benchmark module has

    def run(report: Report) -> dict      # prints tables, writes charts, returns the numbers

and is listed in BENCHMARKS below.
"""

from __future__ import annotations

import importlib
import json
import math
import os
import statistics
import sys
import textwrap
import time
from typing import Any, Callable, Sequence

BENCHMARKS = {           # name -> module (imported only when run)
    "cloth": "app.bench.cloth",
    "integrators": "app.bench.integrators",
    "pymunk": "app.bench.pymunk_bench",
    "mass_spring": "app.bench.mass_spring",
    "particles": "app.bench.particles",
    "clips": "app.bench.clips",
    "frames": "app.bench.frames",
}


class Report:
    """Where a benchmark prints tables, shows progress and saves charts."""

    def __init__(self, out_dir: str = "lab-output/bench", as_json: bool = False,
                 quick: bool = False, full: bool = False):
        self.out_dir = out_dir
        self.as_json = as_json        # with --json, tables go to stderr and JSON to stdout
        self.quick = quick            # fewer repeats and sizes (used by the tests)
        self.full = full and not quick   # the whole sweeps (minutes); default: what a user
                                         # can wait for
        self.charts: list[str] = []

    def _out(self):
        return sys.stderr if self.as_json else sys.stdout

    bar = None          # app.progress.Progress over the benchmarks run (set by run_benchmarks)

    def progress(self, msg: str) -> None:
        """One line of progress on stderr (never mixed into --json output; on a terminal,
        above the bar)."""
        if self.bar is not None:
            self.bar.say(f"  .. {msg}")
        else:
            print(f"  .. {msg}", file=sys.stderr, flush=True)

    def say(self, msg: str = "") -> None:
        print(msg, file=self._out(), flush=True)

    def table(self, title: str, headers: Sequence[str], rows: Sequence[Sequence[Any]]) -> None:
        """Print an aligned text table (numbers formatted with 4 significant digits)."""
        cells = [[_cell(v) for v in row] for row in rows]
        widths = [max(len(h), *(len(r[i]) for r in cells)) if cells else len(h)
                  for i, h in enumerate(headers)]
        out = self._out()
        print(f"\n{_wrapped(title)}", file=out)
        print("  ".join(h.rjust(w) for h, w in zip(headers, widths)), file=out)
        print("  ".join("-" * w for w in widths), file=out)
        for r in cells:
            print("  ".join(c.rjust(w) for c, w in zip(r, widths)), file=out)
        out.flush()

    def live_table(self, title: str, headers: Sequence[str],
                   widths: Sequence[int]) -> Callable[[Sequence[Any]], None]:
        """A table printed as it is measured: the title and header now, each row as it comes
        (call the returned function with it), so a long sweep shows its numbers at once.
        `widths`: each column's least width (a wider cell pushes its row along)."""
        widths = [max(len(h), w) for h, w in zip(headers, widths)]
        out = self._out()
        print(f"\n{_wrapped(title)}", file=out)
        print("  ".join(h.rjust(w) for h, w in zip(headers, widths)), file=out)
        print("  ".join("-" * w for w in widths), file=out, flush=True)

        def row(values: Sequence[Any]) -> None:
            print("  ".join(_cell(v).rjust(w) for v, w in zip(values, widths)), file=self._out(),
                  flush=True)
        return row

    def chart_path(self, name: str) -> str:
        path = os.path.join(self.out_dir, name)
        self.charts.append(path)
        return path


TITLE_WIDTH = 100      # a table's title is wrapped to lines this long (one was 1,128 characters)


def _wrapped(title: str) -> str:
    """A table's title in lines of at most TITLE_WIDTH characters (words kept whole)."""
    return "\n".join(textwrap.fill(part, TITLE_WIDTH, break_long_words=False,
                                   break_on_hyphens=False) for part in title.split("\n"))


def _cell(v: Any) -> str:
    from app.draw.hud import fmt_number
    if isinstance(v, Timing):
        return v.text()         # the median, its interquartile range, the repeats
    return fmt_number(v) if isinstance(v, float) else str(v)


class Timing(float):
    """A median time (it is that float) with its spread: the interquartile range `lo`-`hi` and
    the number of `repeats` it is the median of. Multiplied or divided by a plain number (ms,
    per step) it keeps its spread; tables print it as 1.67 (1.5-1.9, n=7)."""

    lo: float
    hi: float
    repeats: int

    def __new__(cls, median: float, lo: float, hi: float, repeats: int) -> "Timing":
        t = super().__new__(cls, median)
        t.lo, t.hi, t.repeats = lo, hi, repeats
        return t

    @classmethod
    def of(cls, values: Sequence[float]) -> "Timing":
        """The median of `values` with their quartiles (the extremes for fewer than 4)."""
        xs = sorted(values)
        if len(xs) >= 4:
            q = statistics.quantiles(xs, n=4, method="inclusive")
            lo, hi = q[0], q[2]
        else:
            lo, hi = xs[0], xs[-1]
        return cls(statistics.median(xs), lo, hi, len(xs))

    def _scaled(self, k: float) -> "Timing":
        a, b = sorted((self.lo * k, self.hi * k))
        return Timing(float(self) * k, a, b, self.repeats)

    def __mul__(self, k):
        return self._scaled(k) if isinstance(k, (int, float)) and not isinstance(k, Timing) \
            else float(self) * k

    __rmul__ = __mul__

    def __truediv__(self, k):
        return self._scaled(1.0 / k) if isinstance(k, (int, float)) and \
            not isinstance(k, Timing) else float(self) / k

    def text(self) -> str:
        from app.draw.hud import fmt_number
        return f"{fmt_number(float(self))} ({fmt_number(self.lo)}-{fmt_number(self.hi)}, " \
               f"n={self.repeats})"


def median_time(fn: Callable[[], Any], repeats: int = 7, warmup: int = 1,
                number: int = 1) -> Timing:
    """Median wall time in seconds of `number` calls of fn, over `repeats` runs (after warm-up),
    with its interquartile range and repeat count (a Timing: a float)."""
    for _ in range(warmup):
        fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return Timing.of(times)


def load_average() -> float:
    """The load average over the last minute, printed beside a timing; NaN where the system
    has none."""
    try:
        return os.getloadavg()[0]
    except (AttributeError, OSError):
        return math.nan


def machine_note() -> str:
    """CPU count, load average and BLAS kernels, printed first: timings made on a busy machine
    are noisy, and the kernels change more than the products (blas_kernels)."""
    cores = os.cpu_count() or 1
    load = load_average()
    if math.isnan(load):
        return f"{cores} cores (load average unknown){blas_kernels()}"
    busy = "  (busy: timings will be noisy)" if load > 0.75 * cores else ""
    return f"{cores} cores, load average {load:.2f} over the last minute{blas_kernels()}{busy}"


def blas_kernels() -> str:
    """', BLAS: <library> <version>, <kernels> kernels' for the BLAS NumPy loaded (threadpoolctl),
    or '' if it cannot tell. Which kernels OpenBLAS picked for this CPU (OPENBLAS_CORETYPE sets
    them) changes more than its own products: on a Xeon with AVX-512 the engine's substeps
    after one AVX-512 dot product ran slower (bench pymunk: the cradle's lab/bare 1.30-1.33
    with the SkylakeX kernels in is_finite, 1.24-1.27 with the Haswell ones; 2026-11-27)."""
    try:
        import numpy  # noqa: F401 (its BLAS loaded: threadpoolctl lists the loaded ones)
        from threadpoolctl import threadpool_info
        blas = [i for i in threadpool_info() if i.get("user_api") == "blas"]
    except Exception:                  # (no threadpoolctl, or a library it cannot read)
        return ""
    if not blas:
        return ""
    b = blas[0]
    kernels = f", {b['architecture']} kernels" if b.get("architecture") else ""
    return f", BLAS: {b.get('internal_api', '?')} {b.get('version') or ''}".rstrip() + kernels


def run_benchmarks(which: str, as_json: bool = False, out_dir: str = "lab-output/bench",
                   quick: bool = False, full: bool = False) -> int:
    """Run one benchmark or all; print tables (or JSON); return an exit code."""
    names = list(BENCHMARKS) if which == "all" else [which]
    report = Report(out_dir, as_json, quick, full)
    results: dict[str, Any] = {}
    from app.progress import Progress
    report.say(machine_note())
    with Progress(len(names), "benchmarks", "benchmarks") as bar:
        report.bar = bar
        for name in names:
            module = importlib.import_module(BENCHMARKS[name])
            bar.update(0, note=name)
            report.say(f"=== bench {name} ===")
            t0 = time.perf_counter()
            results[name] = module.run(report)
            report.progress(f"{name} done in {time.perf_counter() - t0:.1f} s")
            bar.update(1)
        report.bar = None
    if report.charts:
        report.say("\ncharts (each PNG has an SVG beside it): " + ", ".join(report.charts))
    if as_json:
        print(json.dumps(results if which == "all" else results[which], indent=1))
    return 0
