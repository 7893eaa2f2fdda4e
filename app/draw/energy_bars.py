"""Energy bars (E): one bar per part of a scene's energy, then what was lost since the start, then
the total beside a mark at the starting total, as PhET's energy charts draw them.

Bars grow up from a zero line for a positive value and down for a negative one (a potential
whose zero is the start pose goes negative as the cloth falls). One scale serves every bar, the
largest of them and of the starting total, so bars compare by eye. The zero of each part is
written under the bars, in the scene's words. Sizes grow with the large-text switch (F2).
"""

from __future__ import annotations

import pygame

from app.draw.hud import BOX_COLOR, DIM_COLOR, TEXT_COLOR, wrap
from app.draw.text import font, px
from app.energy import Energies
from app.units import fmt_number

PART_COLORS = {"kinetic": (255, 170, 60), "potential": (90, 160, 255), "gravity": (90, 160, 255),
               "elastic": (110, 210, 120), "springs": (110, 210, 120), "pairs": (200, 130, 255),
               "KE": (255, 170, 60), "PE": (90, 160, 255)}    # short labels: "KE ball", "PE band"
LOST_COLOR = (200, 90, 90)
TOTAL_COLOR = (235, 235, 235)
START_COLOR = (255, 220, 90)


def _color(name: str) -> tuple[int, int, int]:
    return next((c for key, c in PART_COLORS.items() if name.startswith(key)), (160, 200, 200))


def bars(e: Energies) -> list[tuple[str, float, tuple[int, int, int]]]:
    """(label, value in the shown unit, colour) of every bar, in order: the parts, lost (or
    the named `removed` parts and the other rest), total."""
    rows = [(name, e.shown(v), _color(name)) for name, v in e.parts]
    if e.removed:                          # lost, split into what was measured and the rest
        rows += [(name, e.shown(v), LOST_COLOR) for name, v in e.removed]
        rows.append(("other", e.shown(e.other), LOST_COLOR))
    else:
        rows.append(("lost", e.shown(e.lost), LOST_COLOR))
    return rows + [("total", e.shown(e.total), TOTAL_COLOR)]


def draw_energy_bars(surface: pygame.Surface, area: pygame.Rect, e: Energies,
                     size: int = 24, avoid: pygame.Rect | None = None) -> pygame.Rect:
    """The bars in a box at the top right of `area`, below the HUD box `avoid` where the two
    would overlap; return the box."""
    f, small = font(size), font(max(8, size * 4 // 5))
    rows = bars(e)
    width = min(area.width - 16, max(area.width // 2, px(300)))
    col = (width - px(16)) // len(rows)
    if max(f.size(name)[0] for name, _, _ in rows) > col - px(4):
        f = small                                  # a narrow pane: the labels in the small size
    neg = any(v < 0 for _, v, _ in rows) or e.start < 0
    # at most ~45 % of the pane's height for the bars (both halves when values go negative)
    room = int(0.45 * area.height) - 3 * f.get_linesize() - 3 * small.get_linesize()
    bar_h = max(24, min(px(150), room // (2 if neg else 1)))
    title = f"energy ({e.unit})"
    notes = wrap(f"yellow line: the total at the start. Zero: {e.zero}. Lost: {e.losses}.",
                 small, width - px(16))
    line = f.get_linesize()
    top = max([abs(v) for _, v, _ in rows] + [abs(e.shown(e.start)), 1e-12])
    deepest = max([-v for _, v, _ in rows] + [-e.shown(e.start), 0.0]) / top
    below = int(round(bar_h * deepest)) + small.get_linesize() if neg else 0   # negative bars
    top_y = area.top + 8
    if avoid is not None and avoid.width and avoid.right > area.right - width - 8:
        top_y = max(top_y, avoid.bottom + 8)           # under the HUD, not over its text
    zero_y = top_y + px(4) + 2 * line + bar_h          # the title, the values' row, the bars
    height = (zero_y - top_y) + below + line + line // 2 + len(notes) * small.get_linesize() \
        + px(10)
    box = pygame.Rect(area.right - width - 8, top_y, width, height)
    back = pygame.Surface(box.size, pygame.SRCALPHA)
    back.fill(BOX_COLOR)
    surface.blit(back, box.topleft)
    surface.blit(f.render(title, True, TEXT_COLOR), (box.left + px(8), box.top + px(4)))
    scale = bar_h / top
    for i, (name, v, color) in enumerate(rows):
        x = box.left + px(8) + i * col
        w = max(4, col - px(10))
        h = int(round(abs(v) * scale))
        rect = pygame.Rect(x, zero_y - h, w, h) if v >= 0 else pygame.Rect(x, zero_y, w, h)
        pygame.draw.rect(surface, color, rect)
        value = small.render(fmt_number(v), True, color)
        vy = rect.top - value.get_height() - 2 if v >= 0 else rect.bottom + 2
        surface.blit(value, (x, vy))
        surface.blit(f.render(name, True, color), (x, zero_y + below + line // 4))
    sy = zero_y - int(round(e.shown(e.start) * scale))       # the starting total, on its bar
    x_total = box.left + px(8) + (len(rows) - 1) * col
    pygame.draw.line(surface, START_COLOR, (x_total - px(3), sy), (x_total + col - px(7), sy),
                     px(3))
    pygame.draw.line(surface, DIM_COLOR, (box.left + px(4), zero_y), (box.right - px(4), zero_y), 1)
    y = zero_y + below + line + line // 2
    for t in notes:
        surface.blit(small.render(t, True, DIM_COLOR), (box.left + px(8), y))
        y += small.get_linesize()
    return box


def draw_energy(screen: pygame.Surface, scene, layout, size: int = 24) -> None:
    """E's energy bars at the top right of a scene's area, clear of its HUD box (nothing for a
    scene without them, or one whose energies() raised a SceneError: its message is shown
    elsewhere)."""
    from app.scene import SceneError
    try:
        energies = scene.energies()
    except SceneError:
        return
    if energies is not None:
        draw_energy_bars(screen, layout.area, energies, size, avoid=layout.hud)


__all__ = ["draw_energy", "draw_energy_bars", "bars"]
