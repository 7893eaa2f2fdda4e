"""Formulas as pictures: TeX (matplotlib's mathtext, no TeX install) rendered into a pygame
Surface in the HUD's colours and at the HUD's text size, so F2 enlarges them like the text.

matplotlib takes about half a second to import and some 40 ms a formula to draw. Headless (a
screenshot, a test) a formula is drawn when it is asked for. In the window (`BACKGROUND = True`,
set by the window) it is drawn on a worker thread: until it is ready the HUD shows its caption
and "(drawing the formula...)", and the frame never waits. Every picture is cached by (formula,
size, colour), so a HUD drawn every frame draws nothing after the first time.
"""

from __future__ import annotations

import io
import threading
from functools import lru_cache

import pygame

FONTSET = "dejavusans"    # the same sans as the HUD text reads; "cm" would look like a textbook
BACKGROUND = False        # the window sets True: draw formulas on a worker thread

_png: dict[tuple, bytes] = {}          # (tex, em, colour) -> the PNG, once drawn
_asked: set[tuple] = set()             # keys handed to the worker and not drawn yet
_lock = threading.Lock()


def _draw_png(tex: str, em_px: int, color: tuple[int, int, int]) -> bytes:
    """The PNG of `tex` with an em of `em_px` pixels (ValueError if mathtext cannot parse it)."""
    from matplotlib.figure import Figure
    points = 12.0
    dpi = 72.0 * max(6, em_px) / points
    fig = Figure(dpi=dpi)
    fig.patch.set_alpha(0.0)
    fig.text(0.0, 0.0, tex, fontsize=points, color="#%02x%02x%02x" % tuple(color),
             math_fontfamily=FONTSET)
    buf = io.BytesIO()
    fig.savefig(buf, dpi=dpi, format="png", transparent=True, bbox_inches="tight",
                pad_inches=0.02)
    return buf.getvalue()


def _worker(key: tuple) -> None:
    try:
        data = _draw_png(*key)
    except Exception:            # a formula that cannot be drawn: shown as its TeX text instead
        data = b""
    with _lock:
        _png[key] = data
        _asked.discard(key)


@lru_cache(maxsize=256)
def _surface(key: tuple) -> pygame.Surface | None:
    data = _png[key]
    if not data:
        return None
    image = pygame.image.load(io.BytesIO(data), "formula.png")
    return image.convert_alpha() if pygame.display.get_surface() is not None else image


def formula_surface(tex: str, em_px: int, color: tuple[int, int, int],
                    wait: bool = True) -> pygame.Surface | None:
    """`tex` ("$...$", mathtext) drawn with an em of `em_px` pixels in `color` on a transparent
    background. With wait=False, None until a worker thread has drawn it. A formula mathtext
    cannot parse raises ValueError when waited for (a test draws them all)."""
    key = (tex, int(em_px), tuple(int(c) for c in color))
    with _lock:
        done = key in _png
        start = not done and not wait and key not in _asked
        if start:
            _asked.add(key)
    if not done:
        if not wait:
            if start:
                threading.Thread(target=_worker, args=(key,), daemon=True).start()
            return None
        data = _draw_png(*key)
        with _lock:
            _png[key] = data
    return _surface(key)


def fitted(tex: str, em_px: int, color: tuple[int, int, int], width: int
           ) -> pygame.Surface | None:
    """The formula at `em_px`, scaled down (never up) to at most `width` pixels wide; None while
    a worker is still drawing it (in the window)."""
    image = formula_surface(tex, em_px, tuple(color), wait=not BACKGROUND)
    if image is not None and width > 0 and image.get_width() > width:
        scale = width / image.get_width()
        image = pygame.transform.smoothscale(
            image, (width, max(1, int(round(image.get_height() * scale)))))
    return image
