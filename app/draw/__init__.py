"""Drawing helpers: the world<->screen view, text, HUD, pymunk and cloth drawing (pygame), and
the benchmarks' charts for slides (plot.py: matplotlib, imported only when a chart is saved)."""

from __future__ import annotations

import os

import pygame


def save_png(surface: pygame.Surface, path: str | os.PathLike, what: str = "the screenshot") -> None:
    """Save a surface as a PNG, whole or not at all (app/outputs.py), creating the folder as
    needed; OutputError (one line) if it cannot."""
    from app.outputs import atomic_path
    with atomic_path(path, what) as tmp:
        try:
            pygame.image.save(surface, tmp, "png")
        except pygame.error as e:
            raise OSError(0, str(e)) from None
