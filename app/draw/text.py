"""Text for the HUD, panels and charts: one cached font per size, and a large-text switch so the
back row of a classroom can read it (the window toggles `TEXT.scale`)."""

from __future__ import annotations

import pygame


class _TextSettings:
    scale: float = 1.0


TEXT = _TextSettings()
_cache: dict[int, pygame.font.Font] = {}


def font(size: int) -> pygame.font.Font:
    """pygame's default font at `size` pixels (times the large-text scale), cached."""
    size = max(6, int(round(size * TEXT.scale)))
    if size not in _cache:
        if not pygame.font.get_init():
            pygame.font.init()
        _cache[size] = pygame.font.Font(None, size)
    return _cache[size]



def px(width: float) -> int:
    """A line width (or marker size) in screen pixels for drawing `width` at text scale 1: lines,
    trails and legend chips grow with the large-text switch like the text beside them."""
    return max(1, int(round(width * TEXT.scale)))


def fit_size(texts: list[str], size: int, width: int, smallest: int = 8) -> int:
    """The largest size <= `size` (a size as font() takes it) at which every text is at most
    `width` pixels wide, but not below `smallest`: titles and table cells shrink to fit their
    panel instead of running into the next one."""
    while size > smallest and max(font(size).size(t)[0] for t in texts) > width:
        size = max(smallest, int(size * 0.9))
    return size
