"""Text for the HUD, panels and charts: one cached font per size, and a large-text switch so the
back row of a classroom can read it (the window toggles `TEXT.scale`)."""

from __future__ import annotations

from functools import lru_cache

import pygame


class _TextSettings:
    scale: float = 1.0


TEXT = _TextSettings()


def printable(text: str) -> str:
    """`text` with what UTF-8 cannot hold written as escapes: a file name that is not UTF-8
    (bad\\xff.json) reaches Python as a lone surrogate, which pygame's fonts refuse."""
    return text.encode("utf-8", "backslashreplace").decode("utf-8")


class _Font(pygame.font.Font):
    """pygame's Font, but a text it cannot encode is measured and drawn with escapes instead of
    raising (a --record, --screenshot or scene file name shown on screen may hold one)."""

    def size(self, text):
        try:
            return super().size(text)
        except UnicodeError:
            return super().size(printable(text))

    def render(self, text, *args, **kwargs):
        try:
            return super().render(text, *args, **kwargs)
        except UnicodeError:
            return super().render(printable(text), *args, **kwargs)


_cache: dict[int, pygame.font.Font] = {}


def font(size: int) -> pygame.font.Font:
    """pygame's default font at `size` pixels (times the large-text scale), cached."""
    size = max(6, int(round(size * TEXT.scale)))
    if size not in _cache:
        if not pygame.font.get_init():
            pygame.font.init()
        _cache[size] = _Font(None, size)
    return _cache[size]


@lru_cache(maxsize=8192)
def text_width(f: pygame.font.Font, text: str) -> int:
    """f.size(text)[0], remembered: a HUD measures the same words frame after frame (a 1-pane
    mass-spring cloth frame measured ~500 strings, 4 ms of its 16.7 ms; bench frames)."""
    return f.size(text)[0]


def rendered(f: pygame.font.Font, text: str, color) -> pygame.Surface:
    """f.render(text, True, color), remembered for the last 512 (text, colour): most HUD lines
    are the same from one frame to the next. The surface is shared: blit it, never draw on it."""
    try:
        return _rendered(f, text, tuple(color))
    except TypeError:             # (a colour that is no sequence of numbers: pygame decides)
        return f.render(text, True, color)


@lru_cache(maxsize=512)
def _rendered(f: pygame.font.Font, text: str, color: tuple) -> pygame.Surface:
    return f.render(text, True, color)


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
