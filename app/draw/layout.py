"""Where things go in the world area: the HUD box (top left), the metrics strip (bottom) and the
scene's content, fitted into what they leave free, so that HUD and metrics never cover what the
scene draws (its `content_bounds()`), at any text size and window size.

The HUD's room is reserved, not measured per frame: it only grows (a new line, a message) and is
forgotten when the layout is redone (another scene, F2, F3, Tab, a resize), so the picture does
not jump with every message. The content goes below the HUD or to its right, whichever shows it
larger; small scenes (a cradle, a pendulum) are zoomed to fill the space.
"""

from __future__ import annotations

from dataclasses import dataclass

import pygame

from app.draw.view import View

MARGIN = 8          # pixels between the content and the HUD, strip and edges
HUD_SHARE = 0.5     # the HUD may take this much of the height before its text shrinks (never
                    # below the normal size)


@dataclass
class Layout:
    area: pygame.Rect     # the world area (the window left of the panel)
    hud: pygame.Rect      # reserved for the HUD box (empty when hidden)
    strip: pygame.Rect    # reserved for the metrics strip (empty when none or hidden)
    free: pygame.Rect     # where the content is fitted
    view: View
    hud_text: int = 28    # the HUD's text size (as font() takes it)

    def content_rect(self, bounds: tuple[float, float, float, float]) -> pygame.Rect:
        """The screen rectangle of a world rectangle (x, y, w, h)."""
        (x0, y0), (x1, y1) = self.view.pt(bounds[:2]), self.view.pt((bounds[0] + bounds[2],
                                                                     bounds[1] + bounds[3]))
        return pygame.Rect(x0, y0, x1 - x0, y1 - y0)


def fit(area: pygame.Rect, bounds: tuple[float, float, float, float],
        hud_size: tuple[int, int], strip_h: int) -> Layout:
    """Fit the world rectangle `bounds` into `area` less a HUD box of `hud_size` at its top left
    and a strip of `strip_h` along its bottom (either may be (0, 0) / 0: hidden)."""
    hw, hh = hud_size
    hud = pygame.Rect(area.left + MARGIN, area.top + MARGIN, hw, hh) if hw and hh else \
        pygame.Rect(area.left, area.top, 0, 0)
    strip = pygame.Rect(area.left, area.bottom - strip_h, area.width, strip_h)
    bottom = (strip.top if strip_h else area.bottom) - MARGIN
    if hud.height:
        below = pygame.Rect(area.left + MARGIN, hud.bottom + MARGIN, area.width - 2 * MARGIN,
                            bottom - hud.bottom - MARGIN)
        right = pygame.Rect(hud.right + MARGIN, area.top + MARGIN,
                            area.right - hud.right - 2 * MARGIN, bottom - area.top - MARGIN)
        free = max((below, right), key=lambda r: _scale(bounds, r))
    else:
        free = pygame.Rect(area.left + MARGIN, area.top + MARGIN, area.width - 2 * MARGIN,
                           bottom - area.top - MARGIN)
    return Layout(area, hud, strip, free, View.fit_bounds(bounds, free))


def _scale(bounds, rect: pygame.Rect) -> float:
    if rect.width <= 0 or rect.height <= 0:
        return 0.0
    return min(rect.width / bounds[2], rect.height / bounds[3])


def scene_layout(area: pygame.Rect, scene, lines: list | None,
                 room: tuple[int, int] = (0, 0)) -> Layout:
    """The layout of `scene` in `area` with these HUD lines (None: HUD and metrics hidden); the
    HUD's room is at least `room` (what was reserved before)."""
    from app.draw import hud
    from app.draw.text import TEXT
    if lines is None:
        return fit(area, scene.content_bounds(), (0, 0), 0)
    size = hud.HUD_SIZE     # large text in a small window: the HUD gives back some of its growth
    w, h = hud.box_size(lines, size, max_width=hud.hud_width(area))
    while h > HUD_SHARE * area.height and size * TEXT.scale > hud.HUD_SIZE + 1:
        size = max(hud.HUD_SIZE / TEXT.scale, size * 0.9)
        w, h = hud.box_size(lines, int(round(size)), max_width=hud.hud_width(area))
    layout = fit(area, scene.content_bounds(), (max(room[0], w), max(room[1], h)),
                 hud.strip_height(scene, area, int(round(size))))
    layout.hud_text = int(round(size))
    return layout


def draw_scene(surface: pygame.Surface, layout: Layout, scene, lines: list | None) -> int:
    """Draw the scene's world (clipped to the world area), then its HUD box and metrics strip
    unless `lines` is None; return the y above the strip (for banners stacked on it)."""
    from app.draw import hud
    area = layout.area
    surface.fill(scene.background, area)
    surface.set_clip(area)                 # nothing of the world under the panel
    try:
        scene.draw(surface, layout.view)
    finally:
        surface.set_clip(None)
    if lines is None:
        return area.bottom - 6
    hud.text_box(surface, lines, layout.hud.topleft, layout.hud_text,
                 max_width=hud.hud_width(area))
    strip = hud.draw_metrics(surface, area, scene, layout.hud_text)
    return strip.top if strip.height else area.bottom - 6
