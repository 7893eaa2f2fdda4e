"""Drawing the Verlet cloth: its structural rods as a strain heat map, locked particles marked.

Colour = how stretched a rod is, |length/rest - 1|, in a few buckets (blue: < 0.2 %, red: > 20 %).
Speed matters (a 64 x 64 cloth has 8000 rods and must draw in a couple of milliseconds), so no rod
is drawn on its own: each row (and each column) of rods is cut into *runs* of neighbouring rods
that fall in the same colour bucket, and every run is ONE `pygame.draw.lines` call. A hanging cloth
has smooth strain, so a row is one or a few runs; torn rods end a run and are not drawn.
"""

from __future__ import annotations

import numpy as np
import pygame

from app.draw.text import TEXT, font
from app.physics.cloth import Cloth

STRAIN_EDGES = (0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2)
STRAIN_COLORS = [(70, 110, 210), (60, 155, 225), (70, 200, 200), (120, 210, 120),
                 (225, 220, 80), (250, 170, 50), (245, 105, 45), (235, 45, 45)]
PIN_COLOR = (240, 240, 240)
GRAB_COLOR = (255, 120, 200)
HOVER_COLOR = (200, 200, 200)


def strain_buckets(stretch: np.ndarray, alive: np.ndarray) -> np.ndarray:
    """Colour bucket 0..7 of every rod (np.digitize against STRAIN_EDGES); -1 where torn."""
    b = np.digitize(stretch, STRAIN_EDGES)
    b[alive <= 0] = -1
    return b


def draw_runs(surface: pygame.Surface, lines: list, buckets: np.ndarray, width: int) -> int:
    """Draw rods given as polylines: lines[i] holds the screen points of line i, buckets[i, j] the
    colour of its rod j (between points j and j+1). One draw call per run of equal colour,
    hottest runs last (on top). Returns the number of draw calls."""
    n_lines, n_rods = buckets.shape
    if n_rods == 0:
        return 0
    starts_run = np.ones(buckets.shape, bool)
    starts_run[:, 1:] = buckets[:, 1:] != buckets[:, :-1]   # a run starts where the colour changes
    starts = np.flatnonzero(starts_run)                      # ...or at the start of a line
    ends = np.append(starts[1:], buckets.size)
    colours = buckets.ravel()[starts]
    order = np.argsort(colours, kind="stable")
    calls = 0
    draw_lines = pygame.draw.lines
    for s, e, b in zip(starts[order].tolist(), ends[order].tolist(), colours[order].tolist()):
        if b < 0:
            continue
        line, j0 = divmod(s, n_rods)
        j1 = e - line * n_rods                               # rods j0..j1-1 -> points j0..j1
        draw_lines(surface, STRAIN_COLORS[b], False, lines[line][j0:j1 + 1], width)
        calls += 1
    return calls


def draw_cloth(surface: pygame.Surface, view, cloth: Cloth,
               hover: tuple[int, int] | None = None) -> int:
    """Draw the cloth's structural rods coloured by strain, its locked particles as dots, the
    grabbed particle as a ring (and `hover`, the particle the mouse would grab, as a thin ring).
    Returns the number of line draw calls (for the benchmark)."""
    pts = view.pts(np.moveaxis(cloth.x, 0, -1))              # (rows, cols, 2) screen points
    width = 2 if view.len(cloth.spacing) >= 10 else 1
    calls = 0
    horizontal, vertical = cloth.sets["structural"].families
    rows_pts = pts.tolist()
    calls += draw_runs(surface, rows_pts, strain_buckets(cloth.stretch(horizontal),
                                                        horizontal.alive), width)
    cols_pts = pts.transpose(1, 0, 2).tolist()
    calls += draw_runs(surface, cols_pts, strain_buckets(cloth.stretch(vertical),
                                                        vertical.alive).T, width)
    r_pin = max(2, int(round(view.len(cloth.spacing) * 0.16)))
    for r, c in zip(*np.nonzero(cloth.locked)):
        pygame.draw.circle(surface, PIN_COLOR, rows_pts[r][c], r_pin)
    ring = max(5, r_pin * 2 + 2)
    if cloth.grabbed is not None:
        r, c = cloth.grabbed
        pygame.draw.circle(surface, GRAB_COLOR, rows_pts[r][c], ring, 2)
    elif hover is not None:
        r, c = hover
        pygame.draw.circle(surface, HOVER_COLOR, rows_pts[r][c], ring, 1)
    return calls


_legend_cache: dict[float, pygame.Surface] = {}


def _legend() -> pygame.Surface:
    """The colour key (cached per text scale)."""
    key = TEXT.scale
    if key not in _legend_cache:
        f = font(15)
        labels = ([f"<{STRAIN_EDGES[0] * 100:g}%"]
                  + [f"{a * 100:g}-{b * 100:g}%" for a, b in zip(STRAIN_EDGES, STRAIN_EDGES[1:])]
                  + [f">{STRAIN_EDGES[-1] * 100:g}%"])
        title = f.render("stretch |l/rest - 1|", True, (220, 220, 220))
        texts = [f.render(t, True, (220, 220, 220)) for t in labels]
        chip = f.get_height()
        w = max(title.get_width(), max(t.get_width() for t in texts) + chip + 6) + 8
        h = (chip + 2) * (len(texts) + 1) + 8
        surf = pygame.Surface((w, h), pygame.SRCALPHA)
        surf.fill((0, 0, 0, 120))
        surf.blit(title, (4, 4))
        for i, (t, col) in enumerate(zip(texts, STRAIN_COLORS)):
            y = 4 + (chip + 2) * (i + 1)
            pygame.draw.rect(surf, col, (4, y + 2, chip, chip - 4))
            surf.blit(t, (chip + 10, y))
        _legend_cache[key] = surf
    return _legend_cache[key]


def draw_legend(surface: pygame.Surface, view, world_size: tuple[int, int]) -> None:
    """The strain colour key in the bottom-right corner of the world."""
    legend = _legend()
    x, y = view.pt((world_size[0], world_size[1]))
    surface.blit(legend, (x - legend.get_width() - 6, y - legend.get_height() - 6))
