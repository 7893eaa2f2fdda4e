"""Drawing helpers: the world<->screen view, text, HUD, pymunk and cloth drawing (pygame), and
the benchmarks' charts for slides (plot.py: matplotlib, imported only when a chart is saved)."""

from __future__ import annotations

import os

import pygame


def save_png(surface: pygame.Surface, path: str | os.PathLike) -> None:
    """Save a surface as a PNG, creating the folder as needed (raises pygame.error, OSError)."""
    folder = os.path.dirname(os.fspath(path))
    if folder:
        os.makedirs(folder, exist_ok=True)
    pygame.image.save(surface, os.fspath(path))
