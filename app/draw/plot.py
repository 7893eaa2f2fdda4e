"""Charts drawn with pygame (no plotting library needed): line charts with linear or log axes,
used by the benchmarks to write PNG reports.

    chart = LineChart("ms per step vs iterations", "iterations", "ms", logy=True)
    chart.add("64x64", xs, ys)
    chart.save("bench-results/cloth.png")
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import pygame

from app.draw import save_png
from app.draw.text import font

PALETTE = [(230, 97, 76), (86, 180, 233), (240, 200, 70), (120, 200, 120), (200, 130, 230),
           (250, 150, 60), (180, 180, 180), (70, 220, 200)]


@dataclass
class Series:
    label: str
    xs: list[float]
    ys: list[float]
    color: tuple[int, int, int]
    markers: bool = True


@dataclass
class LineChart:
    title: str
    xlabel: str
    ylabel: str
    logx: bool = False
    logy: bool = False
    series: list[Series] = field(default_factory=list)

    def add(self, label: str, xs, ys, color=None, markers: bool = True) -> None:
        color = color or PALETTE[len(self.series) % len(PALETTE)]
        self.series.append(Series(label, [float(x) for x in xs], [float(y) for y in ys], color,
                                  markers))

    def _tx(self, v: float, log: bool) -> float | None:
        if not math.isfinite(v) or (log and v <= 0):
            return None
        return math.log10(v) if log else v

    def draw(self, surface: pygame.Surface, rect: pygame.Rect | None = None) -> None:
        """Draw the chart into `rect` of `surface` (the whole surface by default)."""
        rect = pygame.Rect(rect or surface.get_rect())
        pygame.draw.rect(surface, (250, 250, 250), rect)
        f_title, f_small = font(max(14, rect.h // 28)), font(max(11, rect.h // 40))
        plot = pygame.Rect(rect.x + rect.w * 0.11, rect.y + rect.h * 0.1,
                           rect.w * 0.62, rect.h * 0.76)
        surface.blit(f_title.render(self.title, True, (20, 20, 20)), (rect.x + 10, rect.y + 6))
        pts = [(self._tx(x, self.logx), self._tx(y, self.logy))
               for s in self.series for x, y in zip(s.xs, s.ys)]
        pts = [(x, y) for x, y in pts if x is not None and y is not None]
        if not pts:
            return
        x0, x1 = min(p[0] for p in pts), max(p[0] for p in pts)
        y0, y1 = min(p[1] for p in pts), max(p[1] for p in pts)
        if x1 - x0 < 1e-12:
            x0, x1 = x0 - 1, x1 + 1
        if y1 - y0 < 1e-12:
            y0, y1 = y0 - 1, y1 + 1
        pad = (y1 - y0) * 0.05
        y0, y1 = y0 - pad, y1 + pad

        def to_px(x: float, y: float) -> tuple[float, float]:
            return (plot.x + (x - x0) / (x1 - x0) * plot.w,
                    plot.bottom - (y - y0) / (y1 - y0) * plot.h)

        pygame.draw.rect(surface, (120, 120, 120), plot, 1)
        for log, lo, hi, axis in ((self.logx, x0, x1, "x"), (self.logy, y0, y1, "y")):
            for t in _ticks(lo, hi, log):
                v = math.log10(t) if log else t
                label = f_small.render(f"{t:g}", True, (60, 60, 60))
                if axis == "x":
                    px, _ = to_px(v, y0)
                    pygame.draw.line(surface, (225, 225, 225), (px, plot.y), (px, plot.bottom))
                    surface.blit(label, (px - label.get_width() / 2, plot.bottom + 4))
                else:
                    _, py = to_px(x0, v)
                    pygame.draw.line(surface, (225, 225, 225), (plot.x, py), (plot.right, py))
                    surface.blit(label, (plot.x - label.get_width() - 4, py - label.get_height() / 2))
        xl = f_small.render(self.xlabel + (" (log)" if self.logx else ""), True, (20, 20, 20))
        surface.blit(xl, (plot.centerx - xl.get_width() / 2, plot.bottom + 22))
        yl = pygame.transform.rotate(
            f_small.render(self.ylabel + (" (log)" if self.logy else ""), True, (20, 20, 20)), 90)
        surface.blit(yl, (rect.x + 4, plot.centery - yl.get_height() / 2))
        for i, s in enumerate(self.series):
            line = [to_px(tx, ty) for tx, ty in
                    ((self._tx(x, self.logx), self._tx(y, self.logy)) for x, y in zip(s.xs, s.ys))
                    if tx is not None and ty is not None]
            if len(line) > 1:
                pygame.draw.aalines(surface, s.color, False, line)
                pygame.draw.lines(surface, s.color, False, line, 2)
            if s.markers:
                for p in line:
                    pygame.draw.circle(surface, s.color, p, 4)
            ly = plot.y + i * (f_small.get_height() + 6)
            pygame.draw.line(surface, s.color, (plot.right + 14, ly + 8), (plot.right + 38, ly + 8), 3)
            surface.blit(f_small.render(s.label, True, (20, 20, 20)), (plot.right + 44, ly))

    def save(self, path: str, size: tuple[int, int] = (1000, 620)) -> str:
        """Render to a PNG file (folders created as needed); return the path."""
        surface = pygame.Surface(size)
        self.draw(surface)
        save_png(surface, path)
        return path


def save_grid(charts: list[LineChart], path: str, cols: int = 2,
              cell: tuple[int, int] = (900, 560)) -> str:
    """Several charts in one PNG, `cols` per row."""
    rows = (len(charts) + cols - 1) // cols
    surface = pygame.Surface((cell[0] * cols, cell[1] * rows))
    surface.fill((255, 255, 255))
    for i, c in enumerate(charts):
        c.draw(surface, pygame.Rect((i % cols) * cell[0], (i // cols) * cell[1], *cell).inflate(-8, -8))
    save_png(surface, path)
    return path


def _ticks(lo: float, hi: float, log: bool) -> list[float]:
    """Round tick values between lo and hi (in transformed units when log)."""
    if log:
        return [10.0 ** k for k in range(math.ceil(lo), math.floor(hi) + 1)] or [10 ** lo]
    span = hi - lo
    step = 10 ** math.floor(math.log10(span / 5))
    for m in (1, 2, 5, 10):
        if span / (step * m) <= 6:
            step *= m
            break
    first = math.ceil(lo / step) * step
    return [first + k * step for k in range(int((hi - first) / step) + 1)]
