"""Drawing the particle dance: thousands of dots coloured by species, and the rule's colour key.

Speed: each species' dot is drawn once into a small sprite and all the dots of a species go to
the screen in one `Surface.fblits` call. For 2000 dots of radius 4 on the lab's 2-core machine
(busy; the best of 7 runs) that took 0.51 ms against 0.68 ms for one `pygame.draw.circle` per
particle: either way well inside a 60 fps frame, the step is what costs.
"""

from __future__ import annotations

import numpy as np
import pygame

from app.draw.text import TEXT, font

COLORS = [(240, 90, 80), (80, 170, 250), (250, 210, 70), (110, 215, 120), (210, 120, 240),
          (240, 150, 60)]
LEGEND_SIZE = 24            # pygame's default font at 24 px (the integrator lab's table size)
PULL_COLOR = (240, 240, 240)
PUSH_COLOR = (255, 120, 110)

_sprites: dict[tuple[int, int], pygame.Surface] = {}
_legends: dict[tuple, pygame.Surface] = {}


def _sprite(species: int, radius: int) -> pygame.Surface:
    """A filled circle of the species' colour on a transparent square (cached)."""
    key = (species, radius)
    if key not in _sprites:
        size = 2 * radius + 1
        dot = pygame.Surface((size, size), pygame.SRCALPHA)
        pygame.draw.circle(dot, COLORS[species], (radius, radius), radius)
        _sprites[key] = dot
    return _sprites[key]


def draw_particles(surface: pygame.Surface, view, x: np.ndarray, species: np.ndarray,
                   count: int, radius: float) -> None:
    """Dots of `radius` world px at the positions x (n, 2), coloured by species (0..count-1).
    Far-off particles (walls off) are clipped to +-1e5 px: pygame wants coordinates it can hold."""
    r = max(1, int(round(view.len(radius))))
    pts = (np.clip(view.pts(x), -1e5, 1e5) - r).astype(np.intp)
    for s in range(count):
        # one fblits call per species replaces the loop `for p in pts: surface.blit(dot, p)`
        surface.fblits([(_sprite(s, r), p) for p in pts[species == s].tolist()])


def draw_mouse(surface: pygame.Surface, view, point, radius: float, pulling: bool) -> None:
    """The mouse's reach: a ring, white while it pulls, red while it pushes."""
    pygame.draw.circle(surface, PULL_COLOR if pulling else PUSH_COLOR,
                       view.pt(np.clip(point, -1e5, 1e5)), max(2, int(view.len(radius))), 2)


def _legend(matrix: np.ndarray) -> pygame.Surface:
    """The colour key: a colour chip per species heads each row and column, each cell the rule
    matrix's entry (green: they attract, red: they repel)."""
    key = (matrix.tobytes(), matrix.shape, TEXT.scale)
    if key in _legends:
        return _legends[key]
    if len(_legends) > 32:
        _legends.clear()
    f = font(LEGEND_SIZE)
    k = len(matrix)
    line = f.get_linesize() + 2
    chip = f.get_height() - 4
    cell_w = f.size("+0.0")[0] + 12
    title = f.render("who likes whom: + pulls, - pushes", True, (225, 225, 225))
    w = max(title.get_width(), chip + 8 + k * cell_w) + 12
    h = line * (k + 2) + 6
    box = pygame.Surface((w, h), pygame.SRCALPHA)
    box.fill((0, 0, 0, 160))
    box.blit(title, (6, 4))
    x0, y0 = 6 + chip + 8, 4 + line
    for t in range(k):                              # column heads: a colour chip per species
        pygame.draw.rect(box, COLORS[t], (x0 + t * cell_w + (cell_w - chip) // 2, y0 + 2, chip,
                                          chip - 2))
    for s in range(k):
        y = y0 + line * (s + 1)
        pygame.draw.rect(box, COLORS[s], (6, y + 2, chip, chip - 2))     # row head
        for t in range(k):
            a = float(matrix[s, t])
            colour = (150, 230, 150) if a > 0 else (250, 140, 130) if a < 0 else (200, 200, 200)
            text = f.render(f"{a:+.1f}", True, colour)
            box.blit(text, (x0 + t * cell_w + (cell_w - text.get_width()) // 2, y))
    _legends[key] = box
    return box


def draw_legend(surface: pygame.Surface, view, world_size: tuple[int, int],
                matrix: np.ndarray) -> pygame.Rect:
    """The colour key in the top-right corner of the world; returns its screen rectangle."""
    box = _legend(matrix)
    x, y = view.pt((world_size[0], 0))
    return surface.blit(box, (x - box.get_width() - 6, y + 6))


__all__ = ["COLORS", "draw_particles", "draw_mouse", "draw_legend"]
