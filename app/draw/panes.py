"""Compare mode's picture: a header across the top (the scene, the shared clock, the messages)
and one `Pane` per variant below it, side by side in a wide area and stacked in a tall one (with
four, two by two if that shows them larger). The window and the headless screenshot draw the same
picture with the same code.

Each pane's HUD box opens with its tag and what differs ("B: iterations=20") in the pane's colour
(the live plot draws that variant's lines in it), then its own physics cost and its error against
the scene's reference, then the scene's own lines (hud_lines) and the pane's messages (a blow-up
rolled back and held, with its advice).

Which arrangement: the one whose smallest pane shows the most content (scene_layout measures it
for each candidate, HUD included), decided when the layout is redone (a resize, F2, F3, F4,
Tab, a message that comes or goes) and kept between frames so the picture does not jump.
"""

from __future__ import annotations

import pygame

from app.draw import hud
from app.draw.layout import MARGIN, Layout, Pane, draw_scene, scene_layout
from app.draw.live_plot import PALETTE

PANE_COLORS = PALETTE[:4]     # pane A, B, C, D (their lines in the live plot too)
GAP = 6                       # pixels between panes
PANE_BORDER = (60, 66, 76)


def grids(n: int) -> list[tuple[int, int]]:
    """The (columns, rows) arrangements tried for n panes."""
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
               details: bool = False, more: list = (), clock: str = "") -> list:
    """A pane's HUD lines: its tag and label, its cost and error, the scene's own lines, its
    notes; on the second page (`details`) the scene's details and `more`."""
    cost = hud.physics_text(step_ms)
    err = scene.reference_error()
    if err is not None:
        what, metric, value = err
        cost += f" | {what} {scene.shown(metric, value)}"
    status = ([clock] if clock else []) + [cost]
    lines = hud.scene_lines(scene, status, list(notes), details, list(more))
    first = lines[0]
    lines[0] = hud.Line(f"{tag}: {label}", color, hint=first.hint)
    return lines


class PaneGrid:
    """The panes of a comparison and their arrangement in an area."""

    def __init__(self, scenes):
        self.panes = [Pane(s) for s in scenes]
        self.cells: list[pygame.Rect] | None = None
        self._for: tuple | None = None        # (area, header height) the cells were chosen for
        self.header = pygame.Rect(0, 0, 0, 0)

    def forget(self) -> None:
        for p in self.panes:
            p.forget()
        self.cells = None

    @property
    def layout(self) -> Layout | None:
        """Pane A's layout (its view maps the mouse when the pointer is over no pane)."""
        return self.panes[0].layout

    def fit(self, area: pygame.Rect, header: list | None, lines: list[list | None],
            strip: bool = False) -> list[Layout]:
        """Lay out the header box at the top of `area` (None: no header) and the panes below."""
        h = 0
        if header:
            h = hud.box_size(header, hud.HUD_SIZE, max_width=area.width - 2 * MARGIN)[1]
        self.header = pygame.Rect(area.left + MARGIN, area.top + MARGIN, area.width - 2 * MARGIN,
                                  h)
        top = self.header.bottom + MARGIN if h else area.top
        rest = pygame.Rect(area.left, top, area.width, max(area.bottom - top, 1))
        key = (tuple(rest), len(self.panes))
        if self.cells is None or self._for != key:
            self.cells = self.choose(rest, lines, strip)
            self._for = key
            for p in self.panes:
                p.forget()
        return [p.fit(cell, ln, strip) for p, cell, ln in zip(self.panes, self.cells, lines)]

    def choose(self, rest: pygame.Rect, lines: list, strip: bool) -> list[pygame.Rect]:
        """The arrangement whose smallest pane shows the most content."""
        best, best_score = None, -1.0
        for cols, rows in grids(len(self.panes)):
            cells = split(rest, cols, rows, len(self.panes))
            score = min(_content_area(scene_layout(c, p.scene, ln, strip=strip), c)
                        for p, c, ln in zip(self.panes, cells, lines))
            if score > best_score * 1.01:
                best, best_score = cells, score
        return best

    def draw(self, surface: pygame.Surface, area: pygame.Rect, header: list | None,
             lines: list[list | None], strip: bool = False, overlay=None) -> list[Layout]:
        """Fit, then draw every pane (its scene, `overlay(surface, k, layout)` over it, its HUD)
        and the header; return the panes' layouts."""
        layouts = self.fit(area, header, lines, strip)
        surface.fill((21, 24, 29), area)
        for k, (p, layout, ln) in enumerate(zip(self.panes, layouts, lines)):
            draw_scene(surface, layout, p.scene, ln, strip,
                       overlay=(lambda s, lay, k=k: overlay(s, k, lay)) if overlay else None)
            pygame.draw.rect(surface, PANE_BORDER, layout.area.inflate(2, 2), 1)
        if header:
            hud.text_box(surface, header, self.header.topleft, hud.HUD_SIZE,
                         max_width=self.header.width)
        return layouts

    def pane_at(self, pos) -> int | None:
        """The pane under a screen point, or None."""
        for k, cell in enumerate(self.cells or ()):
            if cell.collidepoint(pos):
                return k
        return None


def _content_area(layout: Layout, cell: pygame.Rect) -> float:
    r = layout.content_rect().clip(cell)
    return float(r.width * r.height)


__all__ = ["PaneGrid", "pane_lines", "grids", "split", "PANE_COLORS"]
