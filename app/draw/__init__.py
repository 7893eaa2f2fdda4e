"""Drawing helpers: the world<->screen view, text, HUD, pymunk and cloth drawing, charts. Uses pygame."""

from __future__ import annotations

import os

import pygame


def save_png(surface: pygame.Surface, path: str | os.PathLike) -> None:
    """Save a surface as a PNG, creating the folder as needed (raises pygame.error, OSError)."""
    folder = os.path.dirname(os.fspath(path))
    if folder:
        os.makedirs(folder, exist_ok=True)
    pygame.image.save(surface, os.fspath(path))
