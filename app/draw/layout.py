"""Where things go in a rectangle of the window: the HUD box (top left), the metrics strip (bottom,
on the HUD's second page) and the scene's content, fitted into what they leave free, so that HUD
and strip never cover what the scene draws (its `content_bounds()`), at any text size, window
size or pane size.

A `Pane` is one scene drawn with its HUD into a given rectangle: the window's world area today,
one of several side by side tomorrow (compare mode). It keeps the HUD's reserved room between
frames: the room only grows (a line appears) and is forgotten when the layout is redone (another
scene, F2, F3, F4, Tab, a resize, a message that comes or goes), so the picture does not jump
with every frame's text. When the room is redone the HUD's width is chosen too: a wide, short box
above content that is wider than the space (it takes room the content could not use anyway), a
narrow, tall one beside content that is taller; whichever shows the content larger.
"""

from __future__ import annotations

from dataclasses import dataclass

import pygame

from app.draw.view import Camera, View

MARGIN = 8          # pixels between the content and the HUD, strip and edges
HUD_SHARE = 0.5     # the HUD may take this much of the height before its text shrinks (never
                    # below the normal size)
HUD_SHARE_DETAILS = 0.6  # on the second page (F4), where the text is what is read, in a window
DETAILS_TALL = 700       # at least this tall: this much (in a shorter one the content is a stamp)
HUD_WIDTHS = (1.0, 0.75, 0.55)   # the HUD box's widths tried, as fractions of the widest
DETAILS_WIDTH = 0.7              # the second page's widest: this share of the area's width


@dataclass
class Layout:
    area: pygame.Rect     # the rectangle the pane draws in (the window's world area)
    hud: pygame.Rect      # reserved for the HUD box (empty when hidden)
    strip: pygame.Rect    # reserved for the metrics strip (empty when none or hidden)
    free: pygame.Rect     # where the content is fitted
    view: View
    bounds: tuple[float, float, float, float] = (0.0, 0.0, 1.0, 1.0)   # the content, world
    hud_text: int = 28    # the HUD's text size (as font() takes it)
    hud_width: int = 0    # the width the HUD's lines are wrapped to
    filled: bool = False  # the content fills the free room 1:1 (Scene.content_fills)
    fitted: View | None = None   # the view before the camera's zoom and pan (None: the same)

    def content_rect(self, bounds: tuple[float, float, float, float] | None = None
                     ) -> pygame.Rect:
        """The screen rectangle of a world rectangle (x, y, w, h); default: the content."""
        b = self.bounds if bounds is None else bounds
        (x0, y0), (x1, y1) = self.view.pt(b[:2]), self.view.pt((b[0] + b[2], b[1] + b[3]))
        return pygame.Rect(x0, y0, x1 - x0, y1 - y0)

    def content_share(self, window: tuple[int, int]) -> float:
        """The share of a window of this size that the scene's content gets on screen."""
        r = self.content_rect().clip(self.area)
        return r.width * r.height / float(window[0] * window[1])


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
    return Layout(area, hud, strip, free, View.fit_bounds(bounds, free), bounds)


def fill(area: pygame.Rect, scene, hud_size: tuple[int, int], strip_h: int) -> Layout:
    """As fit, for a scene whose content fills its room (Scene.content_fills): the larger of the
    rooms below and beside the HUD is all the content's (it lays itself out in pixels). The
    zoom is the one that shows the whole world_size in the room, so world coordinates (the
    mouse, recordings) keep their meaning; the content is the room, in world units."""
    hw, hh = hud_size
    layout = fit(area, (0.0, 0.0, 1.0, 1.0), hud_size, strip_h)
    if hw and hh:
        bottom = (layout.strip.top if strip_h else area.bottom) - MARGIN
        below = pygame.Rect(area.left + MARGIN, layout.hud.bottom + MARGIN,
                            area.width - 2 * MARGIN, bottom - layout.hud.bottom - MARGIN)
        right = pygame.Rect(layout.hud.right + MARGIN, area.top + MARGIN,
                            area.right - layout.hud.right - 2 * MARGIN, bottom - area.top - MARGIN)
        layout.free = max((below, right), key=lambda r: max(r.width, 0) * max(r.height, 0))
    free = layout.free
    zoom = max(min(free.width / scene.world_size[0], free.height / scene.world_size[1]), 1e-3)
    scene.fit_to((max(free.width, 1) / zoom, max(free.height, 1) / zoom))
    layout.bounds = scene.content_bounds()
    layout.view = View(zoom, (free.left - layout.bounds[0] * zoom,
                              free.top - layout.bounds[1] * zoom))
    layout.filled = True
    return layout


def _scale(bounds, rect: pygame.Rect) -> float:
    if rect.width <= 0 or rect.height <= 0:
        return 0.0
    return min(rect.width / bounds[2], rect.height / bounds[3])


def scene_layout(area: pygame.Rect, scene, lines: list | None, room: tuple[int, int] = (0, 0),
                 strip: bool = True, hud_width: int | None = None,
                 bounds: tuple[float, float, float, float] | None = None,
                 text_size: int | None = None) -> Layout:
    """The layout of `scene` in `area` with these HUD lines (None: HUD and strip hidden; `strip`
    False: no metrics strip); the HUD's room is at least `room` (what was reserved before), its
    lines wrapped to `hud_width` if given, else to whichever of HUD_WIDTHS shows the content
    largest (the widest on a tie); `bounds`: the content's world rectangle if not the scene's
    content_bounds() now (a view held still while the mouse drags the content); `text_size`:
    the HUD's text at most this size (the panes of a comparison share one size)."""
    from app.draw import hud
    from app.draw.text import TEXT, font
    place = (lambda a, b, hud_size, strip_h: fill(a, scene, hud_size, strip_h)) \
        if getattr(scene, "content_fills", False) else fit
    if bounds is None or getattr(scene, "content_fills", False):
        bounds = scene.content_bounds()
    if lines is None:
        return place(area, bounds, (0, 0), 0)
    widest = hud.hud_width(area)
    if strip:               # the second page (F4) is read as text: as wide as the area allows
        widest = max(widest, int(DETAILS_WIDTH * (area.width - 2 * MARGIN)))
    # never so narrow that the status line breaks ("physics" / "5.46 ms/step"): the first
    # lines (the title, the time and cost) fit on one line each where the widest can
    # (where even the widest breaks them, the widest: a column of half-lines is no use)
    f = font(min(hud.HUD_SIZE, text_size or hud.HUD_SIZE))
    head = max((f.size(getattr(x, "text", str(x)))[0] + 2 * 8 + 2 for x in lines[:2]
                if "\n" not in getattr(x, "text", str(x))), default=1)
    narrowest = min(head, widest) if not strip else 1   # (F4: the content comes first)
    widths = [hud_width] if hud_width else \
        sorted({max(1, narrowest, int(widest * k)) for k in HUD_WIDTHS}, reverse=True)
    tag = getattr(lines[0], "text", str(lines[0])) if lines else ""
    best: Layout | None = None
    for width in widths:
        size = min(hud.HUD_SIZE, text_size or hud.HUD_SIZE)   # large text in a small window:
        w, h = hud.box_size(lines, int(round(size)), max_width=width)   # the HUD gives back some
        share = HUD_SHARE_DETAILS if strip and area.height >= DETAILS_TALL else HUD_SHARE
        # ... as it does where the tag's longest word ("symplectic_euler") would be cut, and
        # by up to PHRASE_SHRINK where a short phrase would break ("physics" / "2.19 ms/step"
        # in one of two panes at 1024x768 with F2)
        start = size
        while (h > share * area.height or hud.longest_word(tag, int(round(size))) + 2 * 8 >
               width or (size > PHRASE_SHRINK * start and
                         longest_phrase(lines, int(round(size))) + 2 * 8 + 2 > width)) \
                and size * TEXT.scale > hud.HUD_SIZE + 1:
            size = max(hud.HUD_SIZE / TEXT.scale, size * 0.9)
            w, h = hud.box_size(lines, int(round(size)), max_width=width)
        strip_h = hud.strip_height(scene, area, int(round(size))) if strip else 0
        layout = place(area, bounds, (max(room[0], w), max(room[1], h)), strip_h)
        layout.hud_text, layout.hud_width = int(round(size)), width
        if best is None or _better(layout, best):
            best = layout
    if best.filled:                     # the room chosen is the one the scene lays out in
        scene.fit_to((best.bounds[2], best.bounds[3]))
    return best


PHRASE_WORDS = 4       # a phrase of at most this many words (a label and its value) is kept
PHRASE_SHRINK = 0.8    # on one row: the HUD's text shrinks by up to this factor for it


def longest_phrase(lines: list, size: int) -> int:
    """The width in pixels, at text `size`, of the widest short phrase of `lines` (at most
    PHRASE_WORDS words between the gaps hud.wrap breaks at: "physics 2.19 ms/step")."""
    from app.draw.text import font, text_width
    from app.draw.wrap import PHRASE_GAP
    f = font(size)
    phrases = (p for x in lines for p in PHRASE_GAP.split(getattr(x, "text", str(x)))[::2])
    return max((text_width(f, p.strip()) for p in phrases
                if 0 < len(p.split()) <= PHRASE_WORDS), default=0)


def _better(a: Layout, b: Layout) -> bool:
    """Is layout `a` better than `b`: its HUD text not shrunk where b's is, else its content
    more than 1 % larger (on a tie the first tried, the widest HUD, stays)."""
    if a.hud_text != b.hud_text:
        return a.hud_text > b.hud_text
    if a.filled:                        # rooms the content fills: the larger room on screen
        return a.free.width * a.free.height > 1.01 * b.free.width * b.free.height
    return _scale(a.bounds, a.free) > 1.01 * _scale(b.bounds, b.free)


class Pane:
    """One scene drawn with its HUD (and, on the second page, its metrics strip) into a
    rectangle of a surface. `forget()` redoes the HUD's room on the next frame. `camera`: the
    zoom and pan applied on top of the fitted view (app/draw/view.py; shared by the panes of a
    comparison). `hold(True)` keeps the content's bounds as they are (while the mouse drags the
    content, the view must not re-fit under the pointer); `hold(False)` lets them follow the
    scene again."""

    def __init__(self, scene, camera: Camera | None = None):
        self.scene = scene
        self.camera = camera if camera is not None else Camera()
        self.room = (0, 0)                 # the HUD box reserved so far
        self.hud_width: int | None = None  # chosen when the room is redone
        self.layout: Layout | None = None
        self.held: tuple[float, float, float, float] | None = None

    def hold(self, on: bool) -> None:
        self.held = (self.layout.bounds if on and self.layout is not None and
                     not self.layout.filled else None)

    def forget(self) -> None:
        """Redo the HUD's room and width on the next fit (a new size, text size, page, ...)."""
        self.room, self.hud_width = (0, 0), None

    def fit(self, rect: pygame.Rect, lines: list | None, strip: bool = False,
            text_size: int | None = None,
            bounds: tuple[float, float, float, float] | None = None) -> Layout:
        """The layout in `rect` with these HUD lines (None: HUD and strip hidden). Lines that
        no longer fit the room reserved redo it (its width chosen again): the picture moves
        then, and only then. `bounds`: the world rectangle to show, if not the scene's own
        content_bounds() (a comparison's panes share one); a pane held still keeps its own."""
        bounds = self.held or bounds
        layout = scene_layout(rect, self.scene, lines, self.room, strip, self.hud_width, bounds,
                              text_size)
        if lines is not None and self.hud_width is not None and \
                layout.hud.size != tuple(self.room):
            layout = scene_layout(rect, self.scene, lines, (0, 0), strip, None, bounds,
                                  text_size)
        if lines is not None:
            self.room, self.hud_width = layout.hud.size, layout.hud_width
        layout.fitted = layout.view
        layout.view = self.camera.apply(layout.view, layout.free)
        self.layout = layout
        return layout

    def draw(self, surface: pygame.Surface, rect: pygame.Rect, lines: list | None,
             strip: bool = False, overlay=None) -> Layout:
        """Fit, then draw the scene, its HUD box and (with `strip`) its metrics strip in
        `rect`; return the layout used."""
        layout = self.fit(rect, lines, strip)
        draw_scene(surface, layout, self.scene, lines, strip, overlay)
        return layout


def draw_scene(surface: pygame.Surface, layout: Layout, scene, lines: list | None,
               strip: bool = False, overlay=None) -> None:
    """Draw the scene's world (clipped to the layout's area; a scene that lays itself out in its
    room, to that room: in a room too small for its charts it is cut, never drawn over the HUD),
    `overlay(surface, layout)` over it (the arrows), then its HUD box and, with `strip`, its
    metrics strip, unless `lines` is None."""
    from app.draw import hud
    area = layout.area
    surface.fill(scene.background, area)
    old_clip = surface.get_clip()
    room = layout.free.inflate(2 * MARGIN, 2 * MARGIN).clip(area) if layout.filled else area
    surface.set_clip(room.clip(old_clip))          # nothing of the world outside its rectangle
    try:
        scene.draw(surface, layout.view)
        if overlay is not None:
            overlay(surface, layout)
    finally:
        surface.set_clip(old_clip)
    if lines is None:
        return
    box = hud.text_box(surface, lines, layout.hud.topleft, layout.hud_text,
                       max_width=layout.hud_width)
    if strip:
        top = hud.draw_metrics(surface, area, scene, layout.hud_text).top
        from app.draw.formula_box import formula_box
        formula_box(surface, area, box, min(top, area.bottom) - 6, scene, layout.hud_text)
