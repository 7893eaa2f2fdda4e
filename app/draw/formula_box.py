"""The F4 page's box of formulas: each scene's (app/equations.py) with its caption, drawn by
app/draw/formula.py, at the bottom right of the scene beside the HUD (or where the scene says:
the integrator lab's, over its phase portrait)."""

from __future__ import annotations

import pygame

from app.draw import hud

FORMULA_BOX_COLOR = (8, 10, 14, 235)   # nearly opaque: nothing shows through the formulas


def formula_lines(scene) -> list:
    """The scene's governing formulas (app/equations.py), each a caption and its picture."""
    from app.equations import equations_for
    lines: list = []
    for eq in equations_for(scene):
        if eq.caption:
            lines.append(hud.Line(eq.caption, hud.DIM_COLOR))
        lines.append(hud.Line("", hud.TEXT_COLOR, tex=eq.tex))
    return lines


def formula_box(surface: pygame.Surface, area: pygame.Rect, avoid: pygame.Rect, bottom: int,
                scene, size: int = 28) -> pygame.Rect:
    """The second page's formulas (app/equations.py) in a box at the bottom right of `area`,
    ending at `bottom`, beside the HUD box `avoid` where there is room for them (else across the
    area's width, over the HUD's foot); nothing for a scene without formulas."""
    lines = formula_lines(scene)
    if not lines:
        return pygame.Rect(area.right, bottom, 0, 0)
    room = scene.formula_room() if hasattr(scene, "formula_room") else None
    if room is not None and room.width > 80 and room.height > 40:   # the scene's own place
        surface.fill(FORMULA_BOX_COLOR[:3], room)
        clip = surface.get_clip()
        surface.set_clip(room.clip(clip))       # one size (no size is tried and thrown away)
        try:
            return hud.text_box(surface, lines, room.topleft, int(size * 0.8),
                                max_width=room.width, color=FORMULA_BOX_COLOR).clip(room)
        finally:
            surface.set_clip(clip)
    beside = area.right - max(avoid.right, area.left) - 24
    width = beside if beside >= 0.45 * area.width else area.width - 16
    tall = bottom - area.top - 8                    # the height it may take
    w, h = hud.box_size(lines, size, max_width=width)
    if h > tall and width < area.width - 16:        # too tall beside the HUD: across the area
        width = area.width - 16
        w, h = hud.box_size(lines, size, max_width=width)
    while h > tall and size > 12:                   # still too tall: a smaller size
        size = int(size * 0.85)
        w, h = hud.box_size(lines, size, max_width=width)
    return hud.text_box(surface, lines, (area.right - 8 - w, bottom), size, max_width=width,
                        from_bottom=True, color=FORMULA_BOX_COLOR)
