"""Drawing helpers of the window's overlays: the HUD box, banners, the help overlay and the scene menu.

Everything here draws plain text on dark, half-transparent boxes so it stays readable from the back
of a classroom over any scene. Sizes are at text scale 1; `app.draw.text.TEXT.scale` (the F2
large-text switch) enlarges them all. No state lives here: the window decides what to show.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pygame

from app.draw.text import TEXT, font

HUD_SIZE = 28            # pygame's default font at 28: glyphs ~20 px high, 21 px lines
HELP_SIZE = 28
TITLE_SIZE = 44
MENU_SIZE = 32
BOX_COLOR = (8, 10, 14, 160)     # see-through enough to show the world behind the HUD
TEXT_COLOR = (235, 235, 235)
DIM_COLOR = (170, 178, 190)
WARN_COLOR = (255, 200, 90)
ERROR_COLOR = (255, 120, 110)
ACCENT_COLOR = (120, 190, 255)


def fmt_number(x) -> str:
    """A compact form of a metric: integers as they are, floats with 4 significant digits, "-"
    for a value that does not exist yet (None; null in JSON)."""
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(v):
        return str(v)
    if v.is_integer() and abs(v) < 1e9:
        return str(int(v))
    if abs(v) >= 1e5 or abs(v) < 1e-3:
        return f"{v:.3g}"
    return f"{v:.4g}"


def wrap(text: str, f: pygame.font.Font, width: int) -> list[str]:
    """Split `text` into lines no wider than `width` pixels (paragraph breaks kept)."""
    lines: list[str] = []
    for para in text.split("\n"):
        indent = para[: len(para) - len(para.lstrip())]
        words = para.split()
        if not words:
            lines.append("")
            continue
        line = indent + words[0]
        for w in words[1:]:
            candidate = line + " " + w
            if f.size(candidate)[0] <= width:
                line = candidate
            else:
                lines.append(line)
                line = indent + "  " + w if indent else w
        lines.append(line)
    return lines


def pack(items: list[str], f: pygame.font.Font, width: int, sep: str = "  |  ") -> list[str]:
    """Join items with `sep` into lines no wider than `width`, never splitting an item."""
    lines: list[str] = []
    for item in items:
        if lines and f.size(lines[-1] + sep + item)[0] <= width:
            lines[-1] += sep + item
        else:
            lines.append(item)
    return lines


@dataclass
class Line:
    """One line of overlay text and its colour."""
    text: str
    color: tuple[int, int, int] = TEXT_COLOR


def _as_line(item) -> Line:
    return item if isinstance(item, Line) else Line(str(item))


def text_box(surface: pygame.Surface, lines: list, pos: tuple[int, int], size: int = HUD_SIZE,
             pad: int = 8, max_width: int | None = None, from_bottom: bool = False) -> pygame.Rect:
    """Draw lines on a dark backing box whose top-left is `pos` (bottom-left if `from_bottom`);
    return the box's rectangle. Lines wider than `max_width` are wrapped."""
    f = font(size)
    items = [_as_line(x) for x in lines]
    if max_width is not None:
        wrapped: list[Line] = []
        for item in items:
            wrapped += [Line(t, item.color) for t in wrap(item.text, f, max_width - 2 * pad)]
        items = wrapped
    if not items:
        return pygame.Rect(pos, (0, 0))
    rendered = [(f.render(it.text, True, it.color), f.render(it.text, True, (0, 0, 0)))
                for it in items]
    w = max(img.get_width() for img, _ in rendered) + 2 * pad
    h = len(rendered) * f.get_linesize() + 2 * pad
    box = pygame.Surface((w, h), pygame.SRCALPHA)
    box.fill(BOX_COLOR)
    if from_bottom:
        pos = (pos[0], pos[1] - h)
    surface.blit(box, pos)
    y = pos[1] + pad
    for img, shadow in rendered:
        surface.blit(shadow, (pos[0] + pad + 1, y + 1))
        surface.blit(img, (pos[0] + pad, y))
        y += f.get_linesize()
    return pygame.Rect(pos, (w, h))


def banner(surface: pygame.Surface, text: str, area: pygame.Rect, color=WARN_COLOR,
           size: int = HUD_SIZE, y: int | None = None, bottom: int | None = None) -> pygame.Rect:
    """A wrapped message centred horizontally in `area`: its top at `y` if given, else ending
    20 px above `bottom` (default: the bottom of `area`). Return its rectangle."""
    f = font(size)
    width = min(area.width - 40, int(900 * max(1.0, f.get_linesize() / 20)))
    lines = wrap(text, f, width - 24)
    h = len(lines) * f.get_linesize() + 24
    w = max(f.size(t)[0] for t in lines) + 24
    top = (area.bottom if bottom is None else bottom) - h - 20 if y is None else y
    rect = pygame.Rect(area.centerx - w // 2, top, w, h)
    box = pygame.Surface(rect.size, pygame.SRCALPHA)
    box.fill((40, 10, 10, 225) if color == ERROR_COLOR or color == WARN_COLOR else BOX_COLOR)
    surface.blit(box, rect.topleft)
    pygame.draw.rect(surface, color, rect, 2)
    yy = rect.top + 12
    for t in lines:
        surface.blit(f.render(t, True, color), (rect.left + 12, yy))
        yy += f.get_linesize()
    return rect


COMMON_KEYS = [
    ("Space", "pause / resume"),
    (".", "single step (one fixed step of dt)"),
    ("- / =", "slow motion x1 -> x1/2 -> x1/4 -> x1/8, and back"),
    ("R", "reset the scene"),
    ("H or F1", "this help"),
    ("F2", "large text on / off"),
    ("F12", "screenshot to screenshots/"),
    ("Tab", "hide / show the parameter panel"),
    ("PageUp / PageDown", "previous / next scene"),
    ("Esc", "back to the menu (quit from the menu)"),
]


MAX_METRIC_LINES = 2     # lines of metrics at the bottom of the world (--json has them all)


def dt_text(scene) -> str:
    """'dt = 1/60 s in 4 substeps': the step the scene runs at."""
    sub = scene.p["substeps"]
    return f"dt = 1/{scene.p['hertz']} s" + (f" in {sub} substeps" if sub > 1 else "")


def scene_lines(scene, status: list, notes: list = ()) -> list:
    """The HUD box of a scene: its title, the shell's `status` lines (fps, time, pause...), the
    scene's own hud_lines(), the cost of each effect where the scene measures it, and passing
    `notes`. The window and headless screenshots draw the same box."""
    lines: list = [Line(scene.title or scene.name, ACCENT_COLOR), *status]
    lines += [str(x) for x in scene.hud_lines()]
    costs = scene.effect_costs()
    if costs:
        lines.append("cost: " + ", ".join(f"{k} {v:.2f} ms" for k, v in costs.items()))
    return lines + list(notes)


def metric_lines(metrics: dict, width: int) -> list[str]:
    """`metrics` packed into at most MAX_METRIC_LINES lines of `width` pixels; what does not fit
    is counted as "+N more (--json)"."""
    items = [f"{k} {fmt_number(v)}" for k, v in metrics.items()]
    f = font(HUD_SIZE)
    lines = pack(items, f, width - 16)
    if len(lines) > MAX_METRIC_LINES:
        lines = pack(items, f, width - 16 - f.size("  |  +99 more (--json)")[0])[:MAX_METRIC_LINES]
        more = len(items) - sum(line.count("  |  ") + 1 for line in lines)
        lines[-1] += f"  |  +{more} more (--json)"
    return lines


def draw_scene_hud(surface: pygame.Surface, area: pygame.Rect, scene, status: list,
                   notes: list = ()) -> int:
    """Draw the HUD box at the top left of `area` and the metrics strip along its bottom (if the
    scene wants one); return the y above the strip (for banners stacked on it)."""
    hud_width = min(area.width - 16, int(640 * TEXT.scale))
    text_box(surface, scene_lines(scene, status, notes), (area.left + 8, area.top + 8),
             max_width=hud_width)
    lines = metric_lines(scene.metrics(), area.width - 16) if scene.metrics_box else []
    if not lines:
        return area.bottom - 6
    return text_box(surface, lines, (area.left + 8, area.bottom - 6), max_width=area.width - 16,
                    from_bottom=True).top


def reflow(doc: str) -> str:
    """Join a docstring's hard-wrapped lines into paragraphs (so the overlay can wrap them to its
    own width); list items, indented lines and blank lines keep their line breaks."""
    out: list[str] = []
    for line in doc.split("\n"):
        stripped = line.strip()
        starts_item = stripped[:1] in ("-", "*", "+") or stripped[:2].rstrip(".").isdigit()
        joinable = (out and out[-1].strip() and stripped and not starts_item
                    and not line.startswith((" ", "\t")) and not out[-1].rstrip().endswith(":"))
        if joinable:
            out[-1] = out[-1].rstrip() + " " + stripped
        else:
            out.append(line.rstrip())
    return "\n".join(out)


def help_overlay(surface: pygame.Surface, area: pygame.Rect, title: str, doc: str,
                 settings: list[tuple[str, str]] | None = None) -> None:
    """The help overlay: the scene's docstring, the common keys and, beside them, the scene's
    settings (name and one-line help of every param and effect), over `area`."""
    shade = pygame.Surface(area.size, pygame.SRCALPHA)
    shade.fill((5, 6, 9, 235))
    surface.blit(shade, area.topleft)
    x, y = area.left + 24, area.top + 18
    width = area.width - 48
    f_title, f = font(TITLE_SIZE), font(HELP_SIZE)
    surface.blit(f_title.render(title, True, ACCENT_COLOR), (x, y))
    y += f_title.get_linesize() + 6
    key_w = max(f.size(k)[0] for k, _ in COMMON_KEYS) + 24
    key_rows = [(k, wrap(what, f, width - key_w)) for k, what in COMMON_KEYS]
    keys_height = (sum(len(r) for _, r in key_rows) + 2) * f.get_linesize()
    doc_lines = wrap(reflow(doc), f, width)
    room = (area.bottom - 10 - keys_height - y) // f.get_linesize()
    if len(doc_lines) > room:
        doc_lines = doc_lines[: max(room - 1, 0)] + ["... (F2 turns large text off; more in the scene's module docstring)"]
    for t in doc_lines:
        surface.blit(f.render(t, True, TEXT_COLOR), (x, y))
        y += f.get_linesize()
    y += f.get_linesize() // 2
    if settings:      # to the right of the common keys
        left = x + key_w + max(f.size(w)[0] for _, r in key_rows for w in r) + 40
        _settings_column(surface, settings,
                         pygame.Rect(left, y, area.right - 24 - left, area.bottom - 10 - y))
    surface.blit(f.render("Common keys", True, ACCENT_COLOR), (x, y))
    y += f.get_linesize()
    for k, rows in key_rows:
        surface.blit(f.render(k, True, WARN_COLOR), (x, y))
        for what in rows:
            surface.blit(f.render(what, True, TEXT_COLOR), (x + key_w, y))
            y += f.get_linesize()


def _settings_column(surface: pygame.Surface, settings: list[tuple[str, str]],
                     rect: pygame.Rect) -> None:
    """'Settings': one line per param or effect (name in yellow, its help), as many as fit."""
    f_head, f = font(HELP_SIZE), font(int(HELP_SIZE * 0.8))
    head = "Settings (panel, or --set NAME=VALUE)"
    if f_head.size(head)[0] > rect.width:
        head = "Settings"
    widest = max(f.size(name)[0] for name, _ in settings)
    if rect.width < max(f_head.size(head)[0], widest + f.size("help text here")[0]):
        return            # no room beside the keys (large text, small window): the panel has them
    surface.blit(f_head.render(head, True, ACCENT_COLOR), rect.topleft)
    y = rect.top + f_head.get_linesize()
    for name, what in settings:
        if y + f.get_linesize() > rect.bottom:
            surface.blit(f.render("...", True, DIM_COLOR), (rect.left, y - 4))
            break
        label = f.render(name, True, WARN_COLOR)
        surface.blit(label, (rect.left, y))
        rest = _one_line(what, f, rect.width - label.get_width() - 12)
        surface.blit(f.render(rest, True, TEXT_COLOR), (rect.left + label.get_width() + 12, y))
        y += f.get_linesize()


def _one_line(text: str, f: pygame.font.Font, width: int) -> str:
    """`text` cut at a word so that it fits `width` pixels, with "..." if cut."""
    lines = wrap(text, f, width - f.size(" ...")[0])
    return lines[0] + (" ..." if len(lines) > 1 else "") if lines else ""


@dataclass
class MenuEntry:
    """One scene in the menu: its index in the registry and the rectangle that opens it."""
    index: int
    rect: pygame.Rect


def draw_menu(surface: pygame.Surface, scenes: list, selected: int, message: str = "",
              message_color=ERROR_COLOR) -> list[MenuEntry]:
    """Draw the scene menu (grouped by category, in registry order of first appearance) and
    return the clickable entries."""
    surface.fill((18, 20, 26))
    W, H = surface.get_size()
    f_title, f, f_small = font(TITLE_SIZE), font(MENU_SIZE), font(HUD_SIZE)
    x, y = 40, 28
    surface.blit(f_title.render("Physics for animation and games: choose a scene", True,
                                ACCENT_COLOR), (x, y))
    y += f_title.get_linesize() + 4
    hint = "click a scene or press its number;  PageUp/PageDown, arrows + Enter;  Esc quits"
    surface.blit(f_small.render(hint, True, DIM_COLOR), (x, y))
    y += f_small.get_linesize() + 14
    entries: list[MenuEntry] = []
    if not scenes:
        surface.blit(f.render("No scenes registered yet (scenes/__init__.py SCENES is empty).",
                              True, WARN_COLOR), (x, y))
    categories: list[str] = []
    for cls in scenes:
        cat = getattr(cls, "category", "") or "Other"
        if cat not in categories:
            categories.append(cat)
    row_full = f.get_linesize() + f_small.get_linesize() + 14
    needed = len(categories) * (f_small.get_linesize() + 12) + len(scenes) * row_full
    compact = y + needed > H - 10        # too many for the window: drop the docstring lines
    for cat in categories:
        surface.blit(f_small.render(cat.upper(), True, DIM_COLOR), (x, y))
        y += f_small.get_linesize() + 2
        for i, cls in enumerate(scenes):
            if (getattr(cls, "category", "") or "Other") != cat:
                continue
            number = f"{i + 1}" if i < 9 else " "
            title = cls.title or cls.name
            first = " ".join((cls.__doc__ or "").strip().split("\n\n")[0].split())
            row_h = f.get_linesize() + (0 if compact else f_small.get_linesize()) + 8
            rect = pygame.Rect(x - 10, y - 4, W - 2 * x + 20, row_h)
            if i == selected:
                pygame.draw.rect(surface, (40, 60, 90), rect, border_radius=6)
            surface.blit(f.render(number, True, WARN_COLOR), (x, y))
            surface.blit(f.render(title, True, TEXT_COLOR), (x + 40, y))
            name_x = x + 60 + f.size(title)[0]
            surface.blit(f_small.render(f"--scene {cls.name}", True, DIM_COLOR),
                         (name_x, y + (f.get_linesize() - f_small.get_linesize()) // 2))
            if first and not compact:
                sub = _one_line(first, f_small, W - 2 * x - 40)
                surface.blit(f_small.render(sub, True, DIM_COLOR), (x + 40, y + f.get_linesize()))
            entries.append(MenuEntry(i, rect))
            y += row_h + 6
        y += 10
    if message:
        banner(surface, message, surface.get_rect(), color=message_color, size=HUD_SIZE)
    return entries
