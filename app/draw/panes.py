"""Compare mode's picture: a header across the top (the scene, the shared clock, the messages)
and one `Pane` per variant below it, side by side in a wide area and stacked in a tall one (four
are two by two, unless the area is a strip). The window and the headless screenshot draw the same
picture with the same code.

Each pane's HUD box opens with its tag and what differs ("B: iterations=20") in the pane's colour
(the live plot draws that variant's lines in it), then its own physics cost and its error against
the scene's reference, then the scene's own lines (hud_lines) and the pane's messages (a blow-up
rolled back and held, with its advice).

Which arrangement: the one whose smallest pane shows the most content (scene_layout measures it
for each candidate, HUD included; three panes may also go two by two with the header in the
fourth cell instead of across the top), decided when the layout is redone (a resize, F2, F3, F4,
Tab, a message that comes or goes) and kept between frames so the picture does not jump.
"""

from __future__ import annotations

import pygame

from app.draw import hud
from app.draw.layout import MARGIN, Layout, Pane, draw_scene, scene_layout
from app.draw.live_plot import PALETTE
from app.draw.text import TEXT

PANE_COLORS = PALETTE[:4]     # pane A, B, C, D (their lines in the live plot too)
GAP = 6                       # pixels between panes
PANE_BORDER = (60, 66, 76)
CRAMPED_FREE = 0.4            # a pane's picture gets at least this share of its height, or
                              # its HUD takes its brief lines
HEADER_SHARE = 0.3            # the header's text shrinks (to the normal size) above this share
HEADER_SHARE_FOUR = 0.15      # ... with four panes, whose two rows need the height more


STRIP_ASPECT = 3.0            # four panes leave 2x2 for a row (a column) only in an area this
                              # many times wider than tall (taller than wide)


def grids(n: int, area: pygame.Rect | None = None) -> list[tuple[int, int]]:
    """The (columns, rows) arrangements tried for n panes in `area`. Four panes are two by two:
    a row of four narrow columns shows each cloth a little larger but wraps every tag and
    headline into a tall thin box a class cannot read (issue 26, defect 3), unless the area
    is a strip (STRIP_ASPECT) where 2x2 would be as thin."""
    if n == 4:
        out = [(2, 2)]
        if area is not None and area.width >= STRIP_ASPECT * area.height:
            out.append((4, 1))
        if area is not None and area.height >= STRIP_ASPECT * area.width:
            out.append((1, 4))
        return out
    out = [(n, 1), (1, n)]
    if n >= 3:
        out.append((2, 2))
    return out


def split(area: pygame.Rect, cols: int, rows: int, n: int) -> list[pygame.Rect]:
    """n cells of a cols x rows grid over `area`, GAP apart, row by row."""
    w = (area.width - GAP * (cols - 1)) // cols
    h = (area.height - GAP * (rows - 1)) // rows
    return [pygame.Rect(area.left + (k % cols) * (w + GAP), area.top + (k // cols) * (h + GAP),
                        max(w, 1), max(h, 1)) for k in range(n)]


def pane_lines(scene, tag: str, label: str, color, step_ms: float | None, notes: list = (),
               details: bool = False, more: list = (), clock: str = "",
               brief: bool = False) -> list:
    """A pane's HUD lines: its tag and label, its cost and its error against the scene's
    reference, the first of the scene's own lines (its headline: a verdict, the step against
    its limit), its notes; on the second page (`details`) all the scene's lines and details and
    `more`. (The colour key is the header's: one for every pane.) `brief`: the tag, the cost and
    the notes only (a pane too small for more)."""
    cost = hud.physics_text(step_ms)
    err = scene.reference_error()
    if err is not None:
        what, metric, value = err
        cost += f" | {what} {scene.shown(metric, value)}"
    lines: list = [hud.Line(f"{tag}: {label}", color, hint=hud.DETAILS_HINT[int(details)]),
                   *([clock] if clock else []), cost]
    own = [x if isinstance(x, hud.Line) else str(x) for x in scene.hud_lines()]
    lines += [] if brief else own if details else own[:1]
    lines += list(notes)
    if details and not brief:
        lines += [x if isinstance(x, hud.Line) else hud.Line(str(x), hud.DIM_COLOR)
                  for x in scene.hud_details()]
        lines += [x if isinstance(x, hud.Line) else hud.Line(str(x), hud.DIM_COLOR) for x in more]
    return lines


def color_key_line(scene) -> list:
    """The scene's colour key as one header line (empty if it has none)."""
    key = tuple(getattr(scene, "color_key", ()))
    return [hud.Line("", hud.DIM_COLOR, keys=key)] if key else []


class PaneGrid:
    """The panes of a comparison and their arrangement in an area."""

    def __init__(self, scenes, camera=None):
        self.panes = [Pane(s, camera) for s in scenes]     # one camera: every pane alike
        self.cells: list[pygame.Rect] | None = None
        self._for: tuple | None = None        # (area, header height) the cells were chosen for
        self.header = pygame.Rect(0, 0, 0, 0)
        self.header_size = hud.HUD_SIZE
        self.corner = False                   # the header in the fourth cell (three panes)
        self.used: list = []

    def forget(self) -> None:
        for p in self.panes:
            p.forget()
        self.cells = None

    @property
    def layout(self) -> Layout | None:
        """Pane A's layout (its view maps the mouse when the pointer is over no pane)."""
        return self.panes[0].layout

    def fit(self, area: pygame.Rect, header: list | None, lines: list[list | None],
            strip: bool = False, brief: list[list] | None = None) -> list[Layout]:
        """Lay out the header box at the top of `area` (None: no header) and the panes below,
        or, for three panes two by two, the header in the fourth cell (the panes then take the
        whole height: at 1024x768 with F2 the header's ~200 px band cost each cloth a third of
        its size) if that shows the panes larger. A pane whose HUD box would run out of it (a
        small window, large text) takes its `brief` lines instead (`used` holds the lines each
        pane was laid out with)."""
        shared = shared_bounds([p.scene for p in self.panes])
        top = self._header_at_top(area, header)
        corner = self._header_in_corner(area, header) if header and len(self.panes) == 3 \
            else None
        key = (tuple(top[2]), tuple(corner[0]) if corner else None, len(self.panes))
        if self.cells is None or self._for != key:
            cells, score = self.choose(top[2], lines, strip, brief, _cap(header, top[1]), shared)
            self.corner = False
            if corner is not None:
                cells4 = split(area, 2, 2, 4)[:3]
                score4 = self.score(cells4, lines, strip, brief, _cap(header, corner[1]),
                                    shared)
                if score4[0] > score[0] or (score4[0] == score[0] and score4[1] > 1.01 * score[1]):
                    cells, self.corner = cells4, True
            self.cells = cells
            self._for = key
            for p in self.panes:
                p.forget()
        self.header, self.header_size = (corner if self.corner else top)[:2]
        cap = _cap(header, self.header_size)
        layouts, self.used = [], []
        for k, (p, cell, ln) in enumerate(zip(self.panes, self.cells, lines)):
            if cap is not None and brief is not None and ln is not None and not strip:
                ln = brief[k]               # (a crowded comparison: see _cap)
            layout = p.fit(cell, ln, strip, text_size=cap, bounds=shared)
            if brief is not None and ln is not None and _cramped(layout, cell, strip, cap):
                p.forget()
                ln = brief[k]
                layout = p.fit(cell, ln, strip, text_size=cap, bounds=shared)
            layouts.append(layout)
            self.used.append(ln)
        # brief in one pane, brief in all (on the first page): at 1024x768 with F2 cotton's
        # pane gave its headline four rows and leather's none, and the cloths sat at two heights
        if brief is not None and not strip and any(u is b for u, b in zip(self.used, brief)):
            for k, (p, cell, ln) in enumerate(zip(self.panes, self.cells, self.used)):
                if ln is not None and ln is not brief[k]:
                    p.forget()
                    self.used[k] = brief[k]
                    layouts[k] = p.fit(cell, brief[k], strip, text_size=cap,
                                           bounds=shared)
        # one text size in every pane: a pane whose text had to shrink sets it for all (three
        # panes large and one small reads as a mistake)
        shown = [lay.hud_text for lay, ln in zip(layouts, self.used) if ln is not None]
        if shown and min(shown) != max(shown):
            for k, (p, cell, ln) in enumerate(zip(self.panes, self.cells, self.used)):
                if ln is not None and layouts[k].hud_text != min(shown):
                    p.forget()
                    layouts[k] = p.fit(cell, ln, strip, text_size=min(shown),
                                       bounds=shared)
        return layouts

    def _header_at_top(self, area: pygame.Rect, header: list | None
                       ) -> tuple[pygame.Rect, float, pygame.Rect]:
        """(the header's box, its text size, the room left below it) with the header across
        the top: at most HEADER_SHARE (four panes: HEADER_SHARE_FOUR) of the height (large text gives back some of its growth,
        not below the normal size)."""
        h, size = 0, hud.HUD_SIZE
        if header:
            width = area.width - 2 * MARGIN
            h = hud.box_size(header, hud.HUD_SIZE, max_width=width)[1]
            share = HEADER_SHARE_FOUR if len(self.panes) >= 4 else HEADER_SHARE
            while h > share * area.height and size * TEXT.scale > hud.HUD_SIZE + 1:
                size = max(hud.HUD_SIZE / TEXT.scale, size * 0.9)
                h = hud.box_size(header, int(round(size)), max_width=width)[1]
        box = pygame.Rect(area.left + MARGIN, area.top + MARGIN, area.width - 2 * MARGIN, h)
        top = box.bottom + MARGIN if h else area.top
        return box, size, pygame.Rect(area.left, top, area.width, max(area.bottom - top, 1))

    def _header_in_corner(self, area: pygame.Rect, header: list
                          ) -> tuple[pygame.Rect, float] | None:
        """(the header's box, its text size) in the fourth cell of a 2x2 grid over `area`, its
        text shrunk (not below the normal size) to fit the cell; None if it does not."""
        cell = split(area, 2, 2, 4)[3]
        width, room = cell.width - 2 * MARGIN, cell.height - 2 * MARGIN
        size = hud.HUD_SIZE
        h = hud.box_size(header, hud.HUD_SIZE, max_width=width)[1]
        while h > room and size * TEXT.scale > hud.HUD_SIZE + 1:
            size = max(hud.HUD_SIZE / TEXT.scale, size * 0.9)
            h = hud.box_size(header, int(round(size)), max_width=width)[1]
        if h > room or width < 1:
            return None
        return pygame.Rect(cell.left + MARGIN, cell.top + MARGIN, width, h), size

    def choose(self, rest: pygame.Rect, lines: list, strip: bool,
               brief: list | None = None, cap: float | None = None, shared=None
               ) -> tuple[list[pygame.Rect], tuple]:
        """The arrangement whose HUD boxes fit their panes (or spill least; with the `brief`
        lines where the full ones spill) and whose smallest pane shows the most content (on a
        near tie, the first tried: side by side), and its score."""
        best, best_key = None, (-float("inf"), 0.0)
        for cols, rows in grids(len(self.panes), rest):
            cells = split(rest, cols, rows, len(self.panes))
            key = self.score(cells, lines, strip, brief, cap, shared)
            if key[0] > best_key[0] or (key[0] == best_key[0] and key[1] > 1.01 * best_key[1]):
                best, best_key = cells, key
        return best, best_key

    def score(self, cells: list[pygame.Rect], lines: list, strip: bool,
              brief: list | None = None, cap: float | None = None, shared=None
              ) -> tuple[float, float]:
        """(minus the worst spill of a HUD box out of its cell, or 0; the smallest pane's
        content area in pixels): higher is better."""
        layouts = []
        for k, (p, c, ln) in enumerate(zip(self.panes, cells, lines)):
            if cap is not None and brief is not None and ln is not None and not strip:
                ln = brief[k]
            lay = scene_layout(c, p.scene, ln, strip=strip, text_size=cap, bounds=shared)
            if brief is not None and ln is not None and _cramped(lay, c, strip, cap):
                lay = scene_layout(c, p.scene, brief[k], strip=strip, text_size=cap,
                                   bounds=shared)
            layouts.append(lay)
        spill = max(lay.hud.bottom - c.bottom for lay, c in zip(layouts, cells))
        return (min(0, -spill), min(_content_area(lay, c) for lay, c in zip(layouts, cells)))

    def draw(self, surface: pygame.Surface, area: pygame.Rect, header: list | None,
             lines: list[list | None], strip: bool = False, overlay=None,
             brief: list[list] | None = None, picked: int | None = None) -> list[Layout]:
        """Fit, then draw every pane (its scene, `overlay(surface, k, layout)` over it, its HUD;
        pane `picked`, the one the panel edits, framed in its colour) and the header; return the
        panes' layouts."""
        layouts = self.fit(area, header, lines, strip, brief)
        surface.fill((21, 24, 29), area)
        for k, (p, layout, ln) in enumerate(zip(self.panes, layouts, self.used)):
            draw_scene(surface, layout, p.scene, ln, strip,
                       overlay=(lambda s, lay, k=k: overlay(s, k, lay)) if overlay else None)
            if k == picked:
                pygame.draw.rect(surface, PANE_COLORS[k], layout.area, 3)
            else:
                pygame.draw.rect(surface, PANE_BORDER, layout.area.inflate(2, 2), 1)
        if header:
            hud.text_box(surface, header, self.header.topleft, int(round(self.header_size)),
                         max_width=self.header.width)
        return layouts

    def pane_at(self, pos) -> int | None:
        """The pane under a screen point, or None."""
        for k, cell in enumerate(self.cells or ()):
            if cell.collidepoint(pos):
                return k
        return None


def shared_bounds(scenes) -> tuple[float, float, float, float] | None:
    """The world rectangle every pane of a comparison shows: the union of the scenes'
    content_bounds(), so each is drawn at the same scale and what differs between the variants
    is what a class sees (cloth_collisions' heap card: each pane fitted to its own heap drew
    the crushed one at twice the scale, and a heap 2-3 x as tall looked ~1.6 x). None for one
    pane, or where a scene fills its pane (content_fills: it lays itself out)."""
    if len(scenes) < 2 or any(getattr(s, "content_fills", False) for s in scenes):
        return None
    boxes = [s.content_bounds() for s in scenes]
    x0, y0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
    x1, y1 = max(b[0] + b[2] for b in boxes), max(b[1] + b[3] for b in boxes)
    return (x0, y0, x1 - x0, y1 - y0)


def _cap(header: list | None, size: float) -> float | None:
    """The panes' HUD text at most the header's size where the header had to give up some of
    F2's growth, and the panes' first page their brief lines (four panes at 1024x768: the
    header at 1.17x, the panes' boxes at 1.4x took the cloths' height: now the whole comparison
    in one size, the mass-spring cloths ~15 % larger); None where the header kept its size."""
    return size if header and size < hud.HUD_SIZE else None


def _cramped(layout: Layout, cell: pygame.Rect, details: bool = False,
             cap: float | None = None) -> bool:
    """A pane's HUD box runs out of its cell, or, on the first page, had to shrink its text
    below the size every pane's text has (F2 given up in one pane only) or left the picture
    under CRAMPED_FREE of the cell's height (a held pane's advice over a 10 px cloth at
    1024x768): it takes its brief lines instead. (On the second page, F4, the details are what
    was asked for: they stay.)"""
    return layout.hud.bottom > cell.bottom or (not details and (
        layout.hud_text < int(round(cap or hud.HUD_SIZE)) or
        layout.free.height < CRAMPED_FREE * cell.height))


def _content_area(layout: Layout, cell: pygame.Rect) -> float:
    r = layout.content_rect().clip(cell)
    return float(r.width * r.height)


__all__ = ["PaneGrid", "pane_lines", "color_key_line", "grids", "split", "PANE_COLORS"]
