"""Benchmark charts for slides (app/draw/plot.py, matplotlib): PNG and SVG of slide size, axis
labels and ticks as written, legends off the data, no empty panels, matplotlib never imported by
the window."""

from __future__ import annotations

import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from app.draw.plot import DPI, SLIDE, LineChart, _data_pixels, figure, save_grid, svg_path

ROOT = Path(__file__).resolve().parent.parent
SVG = "{http://www.w3.org/2000/svg}"


def work_precision() -> LineChart:
    chart = LineChart("Mass on a spring", "wall time (ms)", "relative error at T = 2 s",
                      logx=True, logy=True)
    chart.add("euler", [1, 2, 4, 8], [30, 5, 1.5, 0.6])
    chart.add("rk4", [1.5, 3, 6, 12], [5e-2, 4e-3, 2.5e-4, 1.6e-5])
    return chart


def test_a_chart_is_written_as_a_slide_sized_png_and_an_svg_with_its_texts(tmp_path):
    from PIL import Image
    png = save_grid([work_precision()], str(tmp_path / "wp.png"), title="Work-precision")
    assert png == str(tmp_path / "wp.png")
    with Image.open(png) as im:
        assert im.size == (round(SLIDE[0] * DPI), round(SLIDE[1] * DPI))     # 2000 x 1125
    root = ET.parse(svg_path(png)).getroot()
    assert root.tag == f"{SVG}svg" and (root.get("width"), root.get("height")) == ("960pt", "540pt")
    ids = {el.get("id") for el in root.iter()}
    assert {"series:euler", "series:rk4", "legend_1", "axes_1"} <= ids
    # text is drawn as paths (same look everywhere); matplotlib keeps each text as a comment
    texts = re.findall(r"<!-- (.*?) -->", Path(svg_path(png)).read_text())
    for wanted in ("Work-precision", "Mass on a spring", "wall time (ms)",
                   "relative error at T = 2 s", "euler", "rk4"):
        assert wanted in texts
    # log ticks are powers of ten written with a superscript exponent, never "1e-04" or
    # "0.0001" (2x10^k and 5x10^k too on the x axis: it spans about one decade)
    ticks = [t for t in texts if re.match(r"\d", t)]
    assert ticks and all(re.fullmatch("([25]\u00d7)?10\u207b?[\u2070\u00b9\u00b2\u00b3\u2074-\u2079]+",
                                      t) for t in ticks), ticks
    assert {"10\u207b\u2074", "10\u00b9"} <= set(ticks)


def test_the_legend_never_covers_a_line_or_a_marker():
    """Data in every corner and along the middle: the legend finds no free place inside, so it
    goes outside the axes; with a free corner it stays inside, clear of every line."""
    crowded = LineChart("crowded", "x (s)", "y (m)")
    crowded.add("a", [0, 1, 2, 3, 4], [0, 4, 0, 4, 0])
    crowded.add("b", [0, 1, 2, 3, 4], [4, 0, 4, 0, 4])
    crowded.add("c", [0, 4], [2, 2])
    roomy = LineChart("roomy", "x (s)", "y (m)")
    roomy.add("rising", [0, 1, 2, 3], [0, 1, 2, 3])
    roomy.add("rising too", [0, 1, 2, 3], [0.5, 1.5, 2.5, 3.5])
    fig = figure([crowded, roomy], cols=2)
    fig.draw_without_rendering()
    for ax in fig.axes:
        legend = ax.get_legend()
        box = legend.get_window_extent()
        assert not any(box.contains(x, y) for x, y in _data_pixels(ax)), ax.get_title()
    a_crowded, a_roomy = fig.axes
    assert a_crowded.get_legend().get_window_extent().x0 >= a_crowded.get_window_extent().x1
    inside = a_roomy.get_legend().get_window_extent()
    assert a_roomy.get_window_extent().contains((inside.x0 + inside.x1) / 2,
                                                (inside.y0 + inside.y1) / 2)


def test_one_chart_asked_for_in_two_columns_fills_the_slide():
    """`bench mass_spring --quick` draws one material with cols=2: half the slide was empty."""
    fig = figure([work_precision()], cols=2)
    fig.draw_without_rendering()
    (ax,) = [a for a in fig.axes if a.get_visible()]
    assert ax.get_window_extent().width > 0.75 * fig.bbox.width


def test_counts_read_as_numbers_and_integer_steps_have_no_halves():
    chart = LineChart("cost", "substeps", "time per step (ms)", logx=True, logy=True)
    chart.add("ms", [1, 2, 5, 10], [0.9, 0.95, 1.0, 1.1])
    iters = LineChart("stretch", "iterations", "stretch (%)")
    iters.add("mean", [1, 5], [6.0, 2.0])
    fig = figure([chart, iters], cols=2)
    fig.draw_without_rendering()
    log_ax, lin_ax = fig.axes
    shown = [t.get_text() for t in log_ax.get_xticklabels(minor=True) + log_ax.get_xticklabels()
             if t.get_text() and log_ax.get_xlim()[0] <= t.get_position()[0] <= log_ax.get_xlim()[1]]
    assert {"1", "2", "5", "10"} <= set(shown)
    lo, hi = lin_ax.get_xlim()
    ticks = [v for v in lin_ax.get_xticks() if lo <= v <= hi]
    assert len(ticks) >= 3 and all(v == int(v) for v in ticks)     # 1, 2, 3, 4, 5: no 1.5


def test_the_window_and_the_command_line_do_not_import_matplotlib():
    code = ("import sys, app.__main__, app.window.window, app.headless, app.clips; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                         env={"SDL_VIDEODRIVER": "dummy", "PATH": "/usr/bin:/bin"}, timeout=60)
    assert out.stdout.strip() == "False", out.stderr


def test_no_chart_without_data():
    with pytest.raises(ValueError):
        figure([])
