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
    # legends in the words a class reads: the integrators' titles, not their code names
    assert {"series:forward Euler", "series:RK4", "legend_1", "axes_1"} <= ids
    # text is drawn as paths (same look everywhere); matplotlib keeps each text as a comment
    texts = re.findall(r"<!-- (.*?) -->", Path(svg_path(png)).read_text())
    for wanted in ("Work-precision", "Mass on a spring", "wall time (ms)",
                   "relative error at T = 2 s", "forward Euler", "RK4"):
        assert wanted in texts
    assert "euler" not in texts and "symplectic_euler" not in " ".join(texts)
    # the error axis spans many decades: powers of ten with a superscript exponent, never
    # "1e-04" or "0.0001"; the ms axis (1 to 12 ms) reads plain numbers: 1, 2, 5, 10
    ticks = [t for t in texts if re.match(r"\d", t)]
    powers = [t for t in ticks if "10\u207b" in t or re.fullmatch("10[\u2070\u00b9\u00b2]", t)]
    assert {"10\u207b\u2074", "10\u00b9"} <= set(powers), ticks
    assert {"1", "2", "5", "10"} <= set(ticks), ticks
    assert not any("e-" in t or "e+" in t for t in ticks), ticks


def test_ms_axes_read_plain_numbers():
    from app.draw.plot import plain_number
    assert [plain_number(v) for v in (0.005, 0.05, 0.5, 2, 20, 200, 10000)] == \
        ["0.005", "0.05", "0.5", "2", "20", "200", "10000"]


def label_boxes(fig):
    """Every tick label, axis label, title and legend text of the figure, as (text, box)."""
    out = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        texts = [ax.xaxis.label, ax.yaxis.label, ax.title]
        for axis, i in ((ax.xaxis, 0), (ax.yaxis, 1)):      # the ticks drawn: inside the view
            lo, hi = sorted(axis.get_view_interval())
            texts += [t for t in axis.get_ticklabels(which="both")
                      if lo * (1 - 1e-9) <= t.get_position()[i] <= hi * (1 + 1e-9)]
        legend = ax.get_legend()
        if legend is not None:
            texts += legend.get_texts()
        out += [(t, t.get_window_extent()) for t in texts if t.get_visible() and t.get_text()]
    for legend in fig.legends:
        out += [(t, t.get_window_extent()) for t in legend.get_texts()]
    return out


def overlaps(fig) -> list[tuple[str, str]]:
    boxes = label_boxes(fig)
    bad = []
    for i, (a, ba) in enumerate(boxes):
        for b, bb in boxes[i + 1:]:
            if ba.overlaps(bb) and ba.intersection(ba, bb).width > 1 and \
                    ba.intersection(ba, bb).height > 1:
                bad.append((a.get_text(), b.get_text()))
    return bad


@pytest.mark.parametrize("sweep", ["quick", "full"])
def test_no_two_labels_of_the_mass_spring_chart_overlap(sweep):
    """The full `bench mass_spring` chart once overprinted its y labels: every tick label, axis
    label, title and legend entry is compared with every other, on the laid-out figure (the
    renderer's bounding boxes), at a quick and a full sweep's data (four materials, six
    integrators, stiffness scales over four decades)."""
    import math
    from app.bench.mass_spring import EXPLICIT, IMPLICIT_STEPS
    materials = ["cotton", "denim"] if sweep == "quick" else ["cotton", "denim", "leather", "silk"]
    scales = [1, 10, 100] if sweep == "quick" else [0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000]
    charts = []
    for m, material in enumerate(materials):
        chart = LineChart(f"{material}: wall ms per simulated second", "stiffness scale",
                          "ms per simulated second", logx=True, logy=True)
        for k, name in enumerate(EXPLICIT + ["implicit_euler"]):
            for h in (IMPLICIT_STEPS if name == "implicit_euler" else (None,)):
                label = name if h is None else f"{name} h=1/{round(1 / h)}"
                chart.add(label, scales, [0.3 * (1 + k) * math.sqrt(s) * (1 + m) for s in scales])
        charts.append(chart)
    fig = figure(charts, cols=2)
    fig.draw_without_rendering()
    assert overlaps(fig) == []
    rows: dict[float, int] = {}              # the shared legend: no name alone on a row
    for t in fig.legends[0].get_texts():
        y = round(t.get_window_extent().y0)
        rows[y] = rows.get(y, 0) + 1
    assert min(rows.values()) >= 2 or len(rows) == 1, rows


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
