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
