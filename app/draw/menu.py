"""The scene menu: categories, scenes numbered in the order shown, descriptions wrapped, in as many
columns as it takes (the window's first screen; app/window/views.py's MenuView shows it).
"""

from __future__ import annotations

from dataclasses import dataclass

import pygame

from app.draw.hud import (ACCENT_COLOR, DIM_COLOR, ERROR_COLOR, HUD_SIZE, MENU_SIZE, TEXT_COLOR,
                          TITLE_SIZE, WARN_COLOR, banner, wrap)
from app.draw.text import font


@dataclass
class MenuEntry:
    """One scene in the menu: its index in the registry, its number on screen (display order)
    and the rectangle that opens it."""
    index: int
    rect: pygame.Rect
    number: int = 0


def menu_order(scenes: list) -> list[int]:
    """Registry indices in the order the menu shows them: grouped by category, categories in
    the order they first appear, scenes in registry order within one. The menu numbers the
    scenes 1, 2, 3 ... in this order, and the digit keys follow it."""
    categories: list[str] = []
    for cls in scenes:
        cat = getattr(cls, "category", "") or "Other"
        if cat not in categories:
            categories.append(cat)
    return [i for cat in categories for i, cls in enumerate(scenes)
            if (getattr(cls, "category", "") or "Other") == cat]


def _first_paragraph(cls) -> str:
    return " ".join((cls.__doc__ or "").strip().split("\n\n")[0].split())


def _menu_blocks(scenes: list, order: list[int], f, f_small, text_w: int,
                 described: bool) -> list[tuple[tuple, int]]:
    """The menu's blocks in display order, each (what, height): ("category", name) headers and
    ("scene", number, registry index, title lines, description lines) rows."""
    blocks: list[tuple[tuple, int]] = []
    category = None
    for number, i in enumerate(order, start=1):
        cat = getattr(scenes[i], "category", "") or "Other"
        if cat != category:
            category = cat
            blocks.append((("category", cat), f_small.get_linesize() + 12))
        first = _first_paragraph(scenes[i]) if described else ""
        sub = wrap(first, f_small, text_w) if first else []
        titles = wrap(scenes[i].title or scenes[i].name, f, text_w)
        blocks.append((("scene", number, i, titles, sub),
                       len(titles) * f.get_linesize() + len(sub) * f_small.get_linesize() + 14))
    return blocks


def _flow(blocks: list[tuple[tuple, int]], columns: int, top: int,
          bottom: int) -> list[tuple[int, int]] | None:
    """(column, y) of every block flowed into `columns` columns between `top` and `bottom`
    (a category header never ends a column), or None if they do not fit."""
    placed: list[tuple[int, int]] = []
    col, y = 0, top
    for k, (kind, h) in enumerate(blocks):
        need = h + (blocks[k + 1][1] if kind[0] == "category" and k + 1 < len(blocks) else 0)
        if y + need > bottom and y > top:
            col, y = col + 1, top
        if col >= columns or y + need > bottom:
            return None
        placed.append((col, y))
        y += h
    return placed


MENU_HINT = "click a scene or press its number;  PageUp/PageDown, arrows + Enter;  Esc quits"


def _menu_layout(surface: pygame.Surface, scenes: list, f_title, f, f_small) -> tuple:
    """Where the menu's blocks go with these fonts: (x, column width, number width, blocks,
    their places, the top of the list, whether it all fits)."""
    W, H = surface.get_size()
    x, y = 40, 28
    y += f_title.get_linesize() * len(wrap("Physics for animation and games: choose a scene",
                                           f_title, W - 2 * x)) + 4
    y += f_small.get_linesize() * len(wrap(MENU_HINT, f_small, W - 2 * x)) + 14
    order = menu_order(scenes)
    num_w = f.size("9")[0] + 24
    top, bottom = y, H - 10
    # the first of these that fits: one column with descriptions, two columns with them, then
    # the same without descriptions (never a description cut short)
    for columns, described in ((1, True), (2, True), (1, False), (2, False), (3, False)):
        col_w = (W - 2 * x - 40 * (columns - 1)) // columns
        blocks = _menu_blocks(scenes, order, f, f_small, col_w - num_w, described)
        placed = _flow(blocks, columns, top, bottom)
        if placed is not None:
            return x, col_w, num_w, blocks, placed, y, True
    col_w = W - 2 * x                       # nothing fits: one column, what fits is shown
    blocks = _menu_blocks(scenes, order, f, f_small, col_w - num_w, False)
    placed = [(0, top + sum(h for _, h in blocks[:k])) for k in range(len(blocks))]
    return x, col_w, num_w, blocks, placed, y, False


def draw_menu(surface: pygame.Surface, scenes: list, selected: int, message: str = "",
              message_color=ERROR_COLOR) -> list[MenuEntry]:
    """Draw the scene menu (grouped by category, numbered in display order, descriptions
    wrapped, in as many columns as it takes) and return the clickable entries. When the
    descriptions do not fit, they are left out (each scene's help overlay has them)."""
    W, H = surface.get_size()
    # the first text size at which the menu fits (large text in a small window shrinks it
    # towards the normal size before anything is cut)
    for k in (1.0, 0.85, 0.72, 0.62):
        fonts = font(int(TITLE_SIZE * k)), font(int(MENU_SIZE * k)), font(int(HUD_SIZE * k))
        laid = _menu_layout(surface, scenes, *fonts)
        if laid[-1]:
            break
    f_title, f, f_small = fonts
    x, col_w, num_w, blocks, placed, y, _ = laid
    surface.fill((18, 20, 26))
    y0 = 28
    for t in wrap("Physics for animation and games: choose a scene", f_title, W - 2 * x):
        surface.blit(f_title.render(t, True, ACCENT_COLOR), (x, y0))
        y0 += f_title.get_linesize()
    y0 += 4
    for t in wrap(MENU_HINT, f_small, W - 2 * x):
        surface.blit(f_small.render(t, True, DIM_COLOR), (x, y0))
        y0 += f_small.get_linesize()
    entries: list[MenuEntry] = []
    if not scenes:
        surface.blit(f.render("No scenes registered yet (scenes/__init__.py SCENES is empty).",
                              True, WARN_COLOR), (x, y))
    for (kind, h), (col, yy) in zip(blocks, placed):
        left = x + col * (col_w + 40)
        if kind[0] == "category":
            surface.blit(f_small.render(kind[1].upper(), True, DIM_COLOR), (left, yy + 6))
            continue
        _, number, i, titles, sub = kind
        cls = scenes[i]
        rect = pygame.Rect(left - 10, yy - 4, col_w + 20, h - 6)
        if i == selected:
            pygame.draw.rect(surface, (40, 60, 90), rect, border_radius=6)
        if number <= 9:
            surface.blit(f.render(str(number), True, WARN_COLOR), (left, yy))
        ty = yy
        for t in titles:
            surface.blit(f.render(t, True, TEXT_COLOR), (left + num_w, ty))
            ty += f.get_linesize()
        name_x = left + num_w + f.size(titles[-1])[0] + 20
        tag = f_small.render(f"--scene {cls.name}", True, DIM_COLOR)
        if name_x + tag.get_width() <= left + col_w:
            surface.blit(tag, (name_x, ty - f.get_linesize()
                               + (f.get_linesize() - f_small.get_linesize()) // 2))
        for t in sub:
            surface.blit(f_small.render(t, True, DIM_COLOR), (left + num_w, ty))
            ty += f_small.get_linesize()
        entries.append(MenuEntry(i, rect, number))
    if message:
        banner(surface, message, surface.get_rect(), color=message_color, size=HUD_SIZE)
    return entries
