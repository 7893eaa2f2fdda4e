"""How wide the parameter panel is and how large its text, for a window's width and the text
scale (F2), so that large text leaves the scene its room in a small window.

At F2 the panel's width grew with its text (320 px x 1.6) up to 36 % of the window: 368 of a
1024-wide window's px, a third of what a class should be looking at. Now, at F2, it takes at most
LARGE_SHARE of the window (never less than its normal width), and its text grows as far as that
width lets the panel's top row ("Resume", "Reset", "Help", whole words) fit: at 1024x768 the panel
is 320 px wide, its text 1.5x instead of 1.6x; at 1920 it keeps 512 px and 1.6x. What does not
fit at that size has its own way out: a card's label takes the theme's smaller font, a slider's
label drops its range (app/window/panel.py)."""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

PANEL_WIDTH = 320        # the panel's width at normal text
NORMAL_SHARE = 0.36      # the panel takes at most this share of the window's width
LARGE_SHARE = 0.30       # ... and at F2 at most this share (never less than PANEL_WIDTH)
PAD, SCROLL_BAR = 10, 20  # the panel's inner padding and its scroll bar (panel.py)
TOP_ROW = ("Resume", "Reset", "Help")   # the top row's widest labels (Pause <-> Resume)
BUTTON_PAD = 12           # a button's width beyond its label (panel.py lays them out so)
THEME_PATH = Path(__file__).resolve().parents[2] / "assets" / "theme.json"
_THEMES: dict[float, dict] = {}


def theme(scale: float) -> dict:
    """assets/theme.json with every font size (and the sizes that hold text) multiplied by
    `scale` (the large-text theme)."""
    if scale not in _THEMES:
        data = json.loads(THEME_PATH.read_text())      # a fresh dict for every scale
        for block in data.values():
            f = block.get("font") if isinstance(block, dict) else None
            if isinstance(f, dict) and "size" in f:
                f["size"] = str(int(round(float(f["size"]) * scale)))
            misc = block.get("misc") if isinstance(block, dict) else None
            # the drop-down's rows, and a tooltip's width (a fixed width put one word a line
            # in F2's font)
            for key in ("list_item_height", "rect_width"):
                if isinstance(misc, dict) and key in misc:
                    misc[key] = str(int(round(float(misc[key]) * scale)))
        _THEMES[scale] = data
    return _THEMES[scale]


def panel_width(window_width: int, scale: float) -> int:
    """The panel's width in a window `window_width` px wide at text `scale`."""
    most = int(window_width * NORMAL_SHARE)
    if scale <= 1.0:
        return min(PANEL_WIDTH, most)
    return min(int(round(PANEL_WIDTH * scale)), max(PANEL_WIDTH, int(window_width * LARGE_SHARE)),
               most)


def panel_scale(width: int, scale: float) -> float:
    """The panel's text scale in a panel `width` px wide: `scale` (F2's) where the top row
    fits, else the largest of scale - 0.1, scale - 0.2, ... (not below 1) where it does."""
    inner = width - 2 * PAD - SCROLL_BAR
    s = round(scale, 2)
    while s > 1.0 and top_row_need(s) > inner:
        s = round(max(1.0, s - 0.1), 2)
    return s


@lru_cache(maxsize=16)
def top_row_need(scale: float) -> int:
    """The pixels the top row's three buttons need at text `scale` (their labels, padding and
    the gaps between them), measured with the theme's font at that scale."""
    import pygame_gui
    manager = pygame_gui.UIManager((64, 64), theme_path=theme(scale))
    font = manager.get_theme().get_font(["button"])
    gap = int(round(6 * scale))
    return sum(font.size(t)[0] + BUTTON_PAD for t in TOP_ROW) + 2 * gap


__all__ = ["panel_width", "panel_scale", "top_row_need", "theme", "PANEL_WIDTH", "LARGE_SHARE",
           "TOP_ROW", "BUTTON_PAD"]
