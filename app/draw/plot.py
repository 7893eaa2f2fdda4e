"""Charts for slides, drawn with matplotlib (the field's standard): line charts with linear or log
axes, written as PNG and SVG side by side, used by the benchmarks (`python -m app bench`).

    chart = LineChart("ms per step vs iterations", "iterations", "time per step (ms)", logy=True)
    chart.add("64x64", xs, ys)
    chart.save("lab-output/bench/cloth.png")        # also writes lab-output/bench/cloth.svg
    save_grid([chart, other], "lab-output/bench/both.png", cols=2)   # several charts, one slide

What a projected slide needs, and where it is done:
  * size: every file is one 16:9 slide, 13.33 x 7.5 in at 150 dpi (2000 x 1125 px), with text
    of at least 14 pt (SLIDE, FONT_PT);
  * log axes tick at powers of ten, written 10^k with superscript digits (2x10^k, 5x10^k too
    when the axis spans under two decades); an axis of counts (substeps, balls) reads 1, 10,
    100; linear axes never switch to "1e+06" notation halfway (an offset is written x10^k);
  * the legend never covers data: it goes to the inside corner whose box no line or marker
    crosses (measured on the drawn chart, `_place_legend`), else outside the axes on the right;
    charts of a grid that show the same series share one legend below them;
  * colours are the lab's (an integrator has the same colour as in the window), darkened where
    they are too pale to read on white, and every series also has its own marker.

matplotlib is imported when a chart is saved, never at import: the window never pays for it.
The Agg canvas (no window, no display) is used through `matplotlib.figure.Figure`, not pyplot, so
no interactive backend is ever chosen.
"""

from __future__ import annotations

import math
import os
import textwrap
from dataclasses import dataclass, field
from typing import Any, Sequence

SLIDE = (40 / 3, 7.5)      # inches: a 16:9 slide (13.33 x 7.5)
DPI = 150                  # 2000 x 1125 px PNG
FONT_PT = 16               # body text; ticks and legend are 14 pt, titles 18 pt
TICK_PT = 14
TITLE_PT = 18
MARKERS = "osD^vP*Xh<>p"
# What save_figure writes, PNG first. The tests of a benchmark's numbers write the PNG only (the
# fixture png_charts, tests/conftest.py: an SVG save costs ~0.4 s a chart); tests/test_charts.py
# checks the SVG.
FORMATS = ("png", "svg")
_NO_STAMP = {"png": {"Software": None}, "svg": {"Date": None}}   # same chart, same bytes

PALETTE = [(230, 97, 76), (86, 180, 233), (240, 200, 70), (120, 200, 120), (200, 130, 230),
           (250, 150, 60), (150, 150, 150), (70, 200, 190)]


@dataclass
class Series:
    label: str
    xs: list[float]
    ys: list[float]
    color: tuple[int, int, int]
    markers: bool = True
    dashed: bool = False


@dataclass
class LineChart:
    """One chart: a title, axis labels (with units, e.g. "time per step (ms)"), linear or log
    axes, and its series."""

    title: str
    xlabel: str
    ylabel: str
    logx: bool = False
    logy: bool = False
    series: list[Series] = field(default_factory=list)

    def add(self, label: str, xs, ys, color=None, markers: bool = True) -> None:
        """A series. Without a colour, a label that starts with an integrator's name
        ("rk4", "implicit_euler h=1/30") takes that integrator's colour in the lab
        (app/draw/palette.py), dashed if an earlier series has it, and is written with the
        integrator's title ("implicit Euler h=1/30"); others take the next of PALETTE."""
        from app.draw.palette import INTEGRATOR_COLORS
        from app.physics.integrators import INTEGRATORS
        name, _, rest = label.partition(" ")
        if color is None:
            color = INTEGRATOR_COLORS.get(name) or PALETTE[len(self.series) % len(PALETTE)]
        if name in INTEGRATORS:        # a legend in the words a class reads: "symplectic Euler"
            label = " ".join(filter(None, (INTEGRATORS[name].title, rest)))
        dashed = any(s.color == tuple(color) for s in self.series)
        self.series.append(Series(label, [float(x) for x in xs], [float(y) for y in ys],
                                  tuple(color), markers, dashed))

    def save(self, path: str, size: tuple[float, float] = SLIDE) -> str:
        """Write the chart to `path` (.png) and beside it as .svg, one slide each (folders made
        as needed); return the PNG's path."""
        return save_grid([self], path, cols=1, size=size)


def save_grid(charts: Sequence[LineChart], path: str, cols: int = 2,
              cell: tuple[int, int] | None = None, size: tuple[float, float] = SLIDE,
              title: str | None = None) -> str:
    """Several charts on one slide, `cols` per row (fewer when there are fewer charts, so no
    panel is left empty), under an optional slide `title`, written as PNG at `path` and as SVG
    beside it; return the PNG's path.
    `cell` (pixels per chart) is accepted for older callers and ignored: the slide sets the size.
    """
    return save_figure(figure(charts, cols, size, title), path)


def figure(charts: Sequence[LineChart], cols: int = 2, size: tuple[float, float] = SLIDE,
           title: str | None = None):
    """The matplotlib Figure of save_grid (laid out, legends placed), not yet saved."""
    from matplotlib import rc_context
    from matplotlib.figure import Figure

    charts = list(charts)
    if not charts:
        raise ValueError("a chart figure needs at least one chart")
    cols = max(1, min(cols, len(charts)))
    rows = math.ceil(len(charts) / cols)
    shared = _shared_labels(charts)
    with rc_context(_STYLE):
        fig = Figure(figsize=size, dpi=DPI, layout="constrained")
        axes = fig.subplots(rows, cols, squeeze=False)
        texts = [(fig.suptitle(title, x=0.01, ha="left", fontweight="bold"), None)] if title \
            else []
        handles: dict[str, Any] = {}
        for i, chart in enumerate(charts):
            ax = axes[i // cols][i % cols]
            handles.update(_draw(chart, ax))
            texts += [(ax.set_title(chart.title, loc="left"), ax), (ax.xaxis.get_label(), ax)]
        for ax in axes.flat[len(charts):]:
            ax.set_visible(False)
        if shared and len(shared) > 1:
            rows = math.ceil(len(shared) / 6)          # as few rows as 6 a row need, filled
            fig.legend([handles[k] for k in shared], shared, loc="outside lower center",
                       ncols=math.ceil(len(shared) / rows), frameon=False)   # evenly: none alone
        _fit_texts(fig, texts)
        outside = False
        if not shared:
            for i, chart in enumerate(charts):
                if len(chart.series) > 1:
                    outside |= not _place_legend(fig, axes[i // cols][i % cols])
        if outside:                      # the layout makes room for a legend outside the axes
            fig.draw_without_rendering()
        fig.set_layout_engine("none")    # the layout is kept as it is: saving twice redoes none
    return fig


def save_figure(fig, path: str) -> str:
    """Write `fig` as PNG at `path` and as SVG beside it (folders made as needed; no date or
    software version inside, so the same chart gives the same files); return the PNG's path.
    OutputError (one line) if one cannot be written: the old file is left as it was."""
    from matplotlib import rc_context

    from app.outputs import atomic_path
    root, _ = os.path.splitext(os.fspath(path))
    with rc_context(_STYLE):          # each file whole or not at all (app/outputs.py)
        for fmt in FORMATS:
            with atomic_path(f"{root}.{fmt}", "the chart") as tmp:
                fig.savefig(tmp, format=fmt, metadata=_NO_STAMP[fmt])
    return root + ".png"


def svg_path(png_path: str) -> str:
    """The SVG written beside a chart's PNG."""
    return os.path.splitext(png_path)[0] + ".svg"


# --------------------------------------------------------------------------------------------
_STYLE = {
    "font.size": FONT_PT, "axes.titlesize": TITLE_PT, "axes.labelsize": FONT_PT,
    "xtick.labelsize": TICK_PT, "ytick.labelsize": TICK_PT, "legend.fontsize": TICK_PT,
    "figure.titlesize": TITLE_PT + 2, "axes.grid": True, "grid.color": "#d9d9d9",
    "grid.linewidth": 0.8, "axes.spines.top": False, "axes.spines.right": False,
    "lines.linewidth": 2.6, "lines.markersize": 8, "axes.titlepad": 10,
    "svg.fonttype": "path", "svg.hashsalt": "physics-lab",    # same chart, same SVG bytes
    "axes.formatter.use_mathtext": True, "axes.formatter.limits": (-3, 5),
}


def _draw(chart: LineChart, ax) -> dict[str, Any]:
    """Draw one chart into `ax`; return its line handles by label."""
    from matplotlib.ticker import LogLocator, MaxNLocator
    handles = {}
    for k, s in enumerate(chart.series):
        pts = [(x, y) for x, y in zip(s.xs, s.ys) if _shown(x, chart.logx) and _shown(y, chart.logy)]
        if not pts:
            continue
        xs, ys = zip(*pts)
        (line,) = ax.plot(xs, ys, color=_on_white(s.color), label=s.label,
                          marker=MARKERS[k % len(MARKERS)] if s.markers else None,
                          linestyle="--" if s.dashed else "-",
                          gid=f"series:{s.label}")
        handles[s.label] = line
    for log, axis, values in ((chart.logx, ax.xaxis, [x for s in chart.series for x in s.xs]),
                              (chart.logy, ax.yaxis, [y for s in chart.series for y in s.ys])):
        counts = bool(values) and all(math.isfinite(v) and v >= 1 and v == int(v) and v < 1e5
                                      for v in values)
        shown = [v for v in values if math.isfinite(v) and v > 0]
        plain = bool(shown) and all(1e-3 <= v < 1e5 for v in shown)   # ms, s: 0.5, 2, 200
        if log:
            # major ticks at powers of ten, labelled 10^k; on an axis spanning under two
            # decades the 2x10^k and 5x10^k ticks are labelled too.
            # An axis of counts (substeps, balls) reads 1, 2, 5, 10, 100 instead of 10^0.
            (ax.set_xscale if axis is ax.xaxis else ax.set_yscale)("log")
            axis.set_minor_locator(LogLocator(subs=(2.0, 5.0)))   # minor ticks at 2 and 5
            axis.set_minor_formatter(_MinorLabels(axis, counts, plain))
            axis.set_major_formatter(_count_label if counts else _plain_label if plain
                                     else _power_label)
        elif counts:
            axis.set_major_locator(MaxNLocator(integer=True, steps=[1, 2, 5, 10]))    # 1, 2, 3: no 1.5 iterations
    ax.set_xlabel(chart.xlabel)
    ax.set_ylabel(chart.ylabel)
    if not handles:
        ax.text(0.5, 0.5, "no data to show", transform=ax.transAxes, ha="center", va="center",
                color="#888888")
    return handles


def _count_label(value: float, pos=None) -> str:
    return f"{value:.0f}"


def plain_number(value: float) -> str:
    """A tick of a log axis of times or sizes as a plain number: 0.005, 0.5, 2, 200, 10000
    (no 10^k to decode at a glance)."""
    if value <= 0:
        return ""
    k = math.floor(math.log10(value) + 1e-9)
    return f"{value:.{max(0, -k)}f}"


def _plain_label(value: float, pos=None) -> str:
    return plain_number(value)


_SUPERSCRIPT = str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076"
                             "\u2077\u2078\u2079")


def power(m: int, k: int) -> str:
    """m x 10^k as a slide writes it: 10\u207b\u00b3, 2\u00d710\u00b2 (plain text with superscript
    digits: the same look as matplotlib's math text, and ten times cheaper to lay out)."""
    ten = "10" + str(k).translate(_SUPERSCRIPT)
    return ten if m == 1 else f"{m}\u00d7{ten}"


def _power_label(value: float, pos=None) -> str:
    """A major tick of a log axis: a power of ten, 10^k."""
    if value <= 0:
        return ""
    return power(1, round(math.log10(value)))


def _fit_texts(fig, texts: list) -> None:
    """Wrap texts (the slide title, each panel's title and x label, given as (text, its axes or
    None for the slide)) onto more lines until each fits in the slide's or its panel's width,
    measured on the laid-out figure."""
    texts = [(t, ax) for t, ax in texts if t.get_text()]
    full = {id(t): t.get_text() for t, _ in texts}
    chars = {id(t): len(t.get_text()) for t, _ in texts}
    for _ in range(12):
        fig.draw_without_rendering()
        too_wide = False
        for t, ax in texts:
            box = t.get_window_extent()
            room = fig.bbox if ax is None else ax.get_window_extent()
            if (box.x1 > room.x1 + 1 or box.x0 < room.x0 - 1) and chars[id(t)] > 12:
                # as many characters a line as the room holds, by the width measured (one more
                # drawing, not one per 15 % step: each costs ~0.3 s on a grid of charts)
                fits = chars[id(t)] * (room.x1 - room.x0) / max(box.x1 - box.x0, 1.0) * 0.95
                chars[id(t)] = max(12, min(int(chars[id(t)] * 0.85), int(fits)))
                t.set_text("\n".join(textwrap.wrap(full[id(t)], chars[id(t)])))
                too_wide = True
        if not too_wide:
            return


class _MinorLabels:
    """Labels for a log axis's minor ticks (at 2 x 10^k and 5 x 10^k): written m x 10^k (or as
    the plain count) when the axis spans fewer than two decades, none otherwise (the 10^k say
    enough)."""

    def __init__(self, axis, counts: bool = False, plain: bool = False):
        self.axis = axis
        self.counts = counts
        self.plain = plain

    def __call__(self, value: float, pos=None) -> str:
        lo, hi = sorted(self.axis.get_view_interval())
        span = math.log10(hi / lo) if lo > 0 and hi > 0 else 99.0
        if value <= 0 or span >= 2.0:
            return ""
        k = math.floor(math.log10(value) + 1e-9)
        m = round(value / 10.0 ** k)
        if m not in (2, 5):
            return ""
        return f"{value:.0f}" if self.counts else plain_number(value) if self.plain \
            else power(m, k)


def _shown(v: float, log: bool) -> bool:
    return math.isfinite(v) and (v > 0 or not log)


def _shared_labels(charts: Sequence[LineChart]) -> list[str]:
    """The series labels every chart of a grid shows (in order), if there are several charts and
    they all show the same ones; else []."""
    if len(charts) < 2:
        return []
    first = [s.label for s in charts[0].series]
    same = all([s.label for s in c.series] == first for c in charts[1:])
    return first if same else []


def _on_white(rgb: tuple[int, int, int]) -> tuple[float, float, float]:
    """The lab's colour (chosen for a dark background) as a matplotlib colour, darkened until its
    luminance is at most 0.55 so it reads on white (yellow becomes ochre, same hue)."""
    r, g, b = (c / 255.0 for c in rgb)
    lum = 0.2126 * r + 0.7152 * g + 0.0722 * b
    k = min(1.0, 0.55 / lum) if lum > 0 else 1.0
    return (r * k, g * k, b * k)


PLACES = ("upper right", "upper left", "lower left", "lower right", "center right", "center left",
          "upper center", "lower center", "center")


def _place_legend(fig, ax) -> bool:
    """Put the axes' legend in the first inside place (the corners first) where its box covers
    no line and no marker (measured in pixels on the laid-out figure: the box's size once, its
    place at each candidate as matplotlib anchors it); if every place covers data, outside the
    axes on the right. Return True if it is inside."""
    from matplotlib.transforms import Bbox
    legend = ax.legend(loc="upper right")
    size = legend.get_window_extent()
    w, h = size.width, size.height
    pad = legend.borderaxespad * fig.dpi / 72 * legend.prop.get_size_in_points()
    frame = ax.get_window_extent()
    points = _data_pixels(ax)
    air = 6.0                                  # pixels of air between legend and data
    for loc in PLACES:
        vertical, _, horizontal = loc.partition(" ")
        horizontal = horizontal or vertical    # "center"
        x0 = {"left": frame.x0 + pad, "right": frame.x1 - pad - w,
              "center": frame.x0 + (frame.width - w) / 2}[horizontal]
        y0 = {"upper": frame.y1 - pad - h, "lower": frame.y0 + pad,
              "center": frame.y0 + (frame.height - h) / 2}[vertical]
        box = Bbox.from_extents(x0 - air, y0 - air, x0 + w + air, y0 + h + air)
        if not any(box.contains(x, y) for x, y in points):
            legend.set_loc(loc)
            return True
    legend.remove()
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    return False


def _data_pixels(ax) -> list[tuple[float, float]]:
    """Points along every line of `ax`, in display pixels, at most ~3 px apart, grown by the
    marker's radius at the data points (what a legend box must not touch)."""
    out: list[tuple[float, float]] = []
    for line in ax.get_lines():
        xy = ax.transData.transform(line.get_xydata())
        r = line.get_markersize() * ax.figure.dpi / 72 / 2 if line.get_marker() not in (
            None, "None", "") else 0.0
        for (x0, y0), (x1, y1) in zip(xy[:-1], xy[1:]):
            n = max(1, int(math.hypot(x1 - x0, y1 - y0) / 3))
            out += [(x0 + (x1 - x0) * t / n, y0 + (y1 - y0) * t / n) for t in range(n)]
        for x, y in xy:
            out += [(x, y), (x - r, y), (x + r, y), (x, y - r), (x, y + r)]
    return out
