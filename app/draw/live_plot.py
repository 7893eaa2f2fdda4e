"""The live plot: metrics over the last N simulated seconds, drawn in a strip of the window (or of a
headless screenshot), with autoscaled axes, tick labels in the HUD's text size (they grow with
F2) and a legend.

One line per metric; in compare mode one line per variant in the variant's colour, and a dash
pattern per metric (solid, dashed, dotted, dash-dot). Values are drawn in the unit the HUD writes
them in (Scene.metric_units: a stretch in %, an energy in J), named in the legend. A value that
does not exist yet (null) leaves a gap. With `log` the y axis is logarithmic (errors that span
decades) and values <= 0 leave gaps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pygame

from app.draw.text import TEXT, font, px
from app.units import fmt_number

PLOT_SIZE = 20                  # the plot's text size (as font() takes it)
BACKGROUND = (12, 14, 19)
FRAME = (70, 76, 88)
GRID = (38, 42, 50)
LABEL = (170, 178, 190)
PALETTE = [(86, 180, 233), (240, 140, 60), (120, 210, 120), (220, 120, 220), (240, 200, 70),
           (70, 220, 200), (230, 97, 76), (180, 180, 180)]
DASHES = ((), (10, 6), (3, 5), (10, 5, 3, 5))    # on/off lengths at text scale 1; () solid


@dataclass
class Line:
    """One line of the plot: its legend text, colour, dash style index and samples."""
    label: str
    color: tuple[int, int, int]
    ts: list[float]
    vs: list[float]
    dash: int = 0
    scales: bool = True     # False: the axis is not scaled to it (a run that blew up leaves the
                            # top of the plot instead of flattening every other line)
    unit: str = ""          # its unit: lines in another unit than the first get their own axis,
                            # on the right (a stretch in % beside an energy in J is not flat)


def nice_ticks(lo: float, hi: float, most: int = 6) -> list[float]:
    """Round values between lo and hi, at most `most` of them (1, 2 or 5 x 10^k apart)."""
    span = hi - lo
    if not (span > 0 and math.isfinite(span)):
        return [lo]
    step = 10 ** math.floor(math.log10(span / most))
    for m in (1, 2, 5, 10, 20):
        if span / (step * m) <= most:
            step *= m
            break
    first = math.ceil(lo / step - 1e-9) * step
    n = int(math.floor((hi - first) / step + 1e-9)) + 1
    return [0.0 if abs(first + k * step) < step * 1e-9 else first + k * step for k in range(n)]


def _decades(lo: float, hi: float, most: int) -> list[float]:
    """Whole powers of ten (as exponents) between lo and hi, every k-th so at most `most`."""
    ks = list(range(math.ceil(lo), math.floor(hi) + 1))
    every = max(1, -(-len(ks) // most))
    return [float(k) for k in ks[::every]]


def y_range(lines: list[Line], t0: float, log: bool) -> tuple[float, float] | None:
    """The y range the visible samples need (with a margin), or None if none is drawable."""
    scaling = [ln for ln in lines if ln.scales] or lines
    values = [v for ln in scaling for t, v in zip(ln.ts, ln.vs)
              if t >= t0 and math.isfinite(v) and (v > 0 or not log)]
    if not values:
        return None
    lo, hi = min(values), max(values)
    if log:
        lo, hi = math.log10(lo), math.log10(hi)
        if hi - lo < 1:
            mid = (hi + lo) / 2
            lo, hi = mid - 0.5, mid + 0.5
        return math.floor(lo * 4) / 4, math.ceil(hi * 4) / 4
    if hi - lo <= 1e-12 * max(abs(hi), abs(lo), 1e-300):
        pad = abs(hi) * 0.1 if hi else 1.0
        return lo - pad, hi + pad
    pad = (hi - lo) * 0.08
    return lo - pad, hi + pad


def _in_view(ln: Line, t0: float, log: bool) -> bool:
    return any(t >= t0 and math.isfinite(v) and (v > 0 or not log)
               for t, v in zip(ln.ts, ln.vs))


def draw_plot(surface: pygame.Surface, rect: pygame.Rect, lines: list[Line], t_now: float,
              window: float, log: bool = False, hint: str = "") -> dict[str, list]:
    """Draw `lines` over the last `window` seconds before `t_now` in `rect`; return where the
    tick labels went ({"x": [rect, ...], "y": [...], "y2": [...]}: the tests check they never
    overlap). Lines in a second unit are scaled to an axis of their own, labelled on the right;
    a line with no value in view says so in the legend (a held pane's, which stopped earlier)."""
    drawn: dict[str, list] = {"x": [], "y": [], "y2": []}
    surface.fill(BACKGROUND, rect)
    pygame.draw.rect(surface, FRAME, rect, 1)
    f = font(PLOT_SIZE)
    lh = f.get_linesize()
    pad = max(4, int(6 * TEXT.scale))
    t0 = max(t_now - window, 0.0) if t_now >= window else 0.0
    t1 = max(t0 + window, t_now)
    lines = [ln if _in_view(ln, t0, log) else
             Line(f"{ln.label} (none in view)", ln.color, ln.ts, ln.vs, ln.dash, ln.scales,
                  ln.unit) for ln in lines]
    legend_rows = _legend_rows(lines, f, rect.width - 2 * pad)
    top = rect.top + pad + len(legend_rows) * lh
    first = lines[0].unit if lines else ""
    left_lines = [ln for ln in lines if ln.unit == first]
    right_lines = [ln for ln in lines if ln.unit != first]
    yr = y_range(left_lines, t0, log)
    yr2 = y_range(right_lines, t0, log) if right_lines else None
    most = max(2, min(6, int((rect.bottom - top - 2 * pad - lh) // (1.5 * lh))))  # labels

    def ticks_of(r):
        return (nice_ticks(*r, most) if not log else _decades(*r, most)) if r else []
    ticks, ticks2 = ticks_of(yr), ticks_of(yr2)                                    # apart
    two = bool(right_lines)           # two axes: each tick names its unit ('20 %', '-40 J')
    labels = [fmt_number(10 ** t if log else t) + (f" {first}" if two and first else "")
              for t in ticks]
    labels2 = [fmt_number(10 ** t if log else t) + (f" {right_lines[0].unit}"
                                                    if right_lines[0].unit else "")
               for t in ticks2] if two else []
    left = rect.left + pad + max([f.size(s)[0] for s in labels] + [f.size("0")[0]]) + pad
    right = rect.right - pad - (max([f.size(s)[0] for s in labels2]) + pad if labels2 else 0)
    plot = pygame.Rect(left, top + pad, right - left, rect.bottom - top - 2 * pad - lh)
    _draw_legend(surface, legend_rows, (rect.left + pad, rect.top + pad), f)
    if plot.width < 20 or plot.height < 10:
        return drawn
    pygame.draw.rect(surface, FRAME, plot, 1)

    def x_of(t: float) -> float:
        return plot.left + (t - t0) / (t1 - t0) * plot.width

    for t in nice_ticks(t0, t1, max(2, plot.width // max(f.size("000.0")[0] * 2, 1))):
        x = x_of(t)
        pygame.draw.line(surface, GRID, (x, plot.top + 1), (x, plot.bottom - 2))
        img = f.render(fmt_number(t), True, LABEL)
        at = (min(max(x - img.get_width() / 2, plot.left), plot.right - img.get_width()),
              plot.bottom + 2)
        surface.blit(img, at)
        drawn["x"].append(img.get_rect(topleft=at))
    unit = f.render("t (s)", True, LABEL)
    if yr is None and yr2 is None:
        img = f.render("no value yet", True, LABEL)
        surface.blit(img, img.get_rect(center=plot.center))
        return drawn

    def y_of(v: float, r) -> float | None:
        if r is None or not math.isfinite(v) or (log and v <= 0):
            return None
        w = math.log10(v) if log else v
        return plot.bottom - (w - r[0]) / (r[1] - r[0]) * plot.height

    for r, tk, texts, key in ((yr, ticks, labels, "y"), (yr2, ticks2, labels2, "y2")):
        for t, text in zip(tk, texts):
            y = plot.bottom - (t - r[0]) / (r[1] - r[0]) * plot.height
            if key == "y":
                pygame.draw.line(surface, GRID, (plot.left + 1, y), (plot.right - 2, y))
            img = f.render(text, True, LABEL)
            at = (plot.left - pad - img.get_width() if key == "y" else plot.right + pad,
                  y - img.get_height() / 2)
            surface.blit(img, at)
            drawn[key].append(img.get_rect(topleft=at))
    old = surface.get_clip()
    surface.set_clip(plot.clip(old))
    try:
        for ln in lines:
            r = yr if ln.unit == first else yr2
            run: list[tuple[float, float]] = []
            for t, v in zip(ln.ts, ln.vs):
                y = y_of(v, r) if t >= t0 else None
                if y is None:
                    _polyline(surface, ln.color, run, ln.dash)
                    run = []
                else:
                    run.append((x_of(t), y))
            _polyline(surface, ln.color, run, ln.dash)
    finally:
        surface.set_clip(old)
    # the axis's name and the hint on a backing of their own: no line runs through them
    at = (plot.right - unit.get_width() - 2, plot.top + 2)
    surface.fill(BACKGROUND, unit.get_rect(topleft=at).inflate(4, 2))
    surface.blit(unit, at)
    if hint:
        img = f.render(hint, True, LABEL)
        if img.get_width() < plot.width - unit.get_width() - 12:
            surface.fill(BACKGROUND, img.get_rect(topleft=(plot.left + 4, plot.top + 2))
                         .inflate(4, 2))
            surface.blit(img, (plot.left + 4, plot.top + 2))
    return drawn


def _polyline(surface: pygame.Surface, color, points: list[tuple[float, float]], dash: int):
    width = px(2)
    if len(points) == 1:
        pygame.draw.circle(surface, color, points[0], width)
        return
    if len(points) < 2:
        return
    pattern = [d * TEXT.scale for d in DASHES[dash % len(DASHES)]]
    if not pattern:
        pygame.draw.lines(surface, color, False, points, width)
        return
    k, left, on = 0, pattern[0], True          # walk the line, switching on and off
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        seg = math.hypot(x1 - x0, y1 - y0)
        done = 0.0
        while done < seg:
            take = min(left, seg - done)
            if on:
                a, b = done / seg, (done + take) / seg
                pygame.draw.line(surface, color, (x0 + (x1 - x0) * a, y0 + (y1 - y0) * a),
                                 (x0 + (x1 - x0) * b, y0 + (y1 - y0) * b), width)
            done += take
            left -= take
            if left <= 1e-9:
                k = (k + 1) % len(pattern)
                left, on = pattern[k], not on


def _legend_rows(lines: list[Line], f: pygame.font.Font, width: int) -> list[list[Line]]:
    rows: list[list[Line]] = [[]]
    used = 0
    for ln in lines:
        w = _entry_width(ln, f)
        if rows[-1] and used + w > width:
            rows.append([])
            used = 0
        rows[-1].append(ln)
        used += w
    return rows if rows[0] else []


def _entry_width(ln: Line, f: pygame.font.Font) -> int:
    return int(28 * TEXT.scale) + f.size(ln.label + "    ")[0]


def _draw_legend(surface: pygame.Surface, rows: list[list[Line]], pos, f) -> None:
    x0, y = pos
    chip = int(22 * TEXT.scale)
    for row in rows:
        x = x0
        for ln in row:
            mid = y + f.get_linesize() / 2
            _polyline(surface, ln.color, [(x, mid), (x + chip, mid)], ln.dash)
            surface.blit(f.render(ln.label, True, ln.color), (x + chip + 6, y))
            x += _entry_width(ln, f)
        y += f.get_linesize()


__all__ = ["Line", "draw_plot", "nice_ticks", "y_range", "PALETTE", "DASHES"]
