"""Drawing helpers of the window's overlays: the HUD box, the metrics strip, banners and the help
overlay (the scene menu: app/draw/menu.py).

Everything here draws plain text on dark boxes, readable from the back of a classroom; the layout
(app/draw/layout.py) keeps the HUD and the metrics strip off the scene's content. Sizes are at text
scale 1; `app.draw.text.TEXT.scale` (the F2 large-text switch) enlarges them all. Text is wrapped
between phrases, never cut with "...": the help overlay scrolls. No state lives here.
"""

from __future__ import annotations

from dataclasses import dataclass

import pygame

from app.draw.text import TEXT, font, rendered, text_width
from app.draw.wrap import PHRASE_GAP, UNITS, longest_word, pack, wrap  # noqa: F401 (importers)
from app.units import fmt_number  # noqa: F401  (the HUD's number format; importers use it)

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


@dataclass
class Line:
    """One line of overlay text and its colour; `swatch`: a colour square drawn before it (a
    colour key: what a colour on screen means); `hint`: dim text after it, on the line's last
    row if it fits there, else left out (never a row of its own)."""
    text: str
    color: tuple[int, int, int] = TEXT_COLOR
    swatch: tuple[int, int, int] | None = None
    keys: tuple = ()      # a colour key packed into rows: (colour or None, text) items
    hint: str = ""
    tex: str = ""         # a formula (mathtext "$...$"): drawn as a picture at the text's size
    image: pygame.Surface | None = None   # the formula drawn (made by _box_lines)


def _as_line(item) -> Line:
    return item if isinstance(item, Line) else Line(str(item))


def _key_width(f: pygame.font.Font, key: tuple) -> int:
    color, text = key
    return (_swatch_w(f) if color is not None else 0) + text_width(f, text + "  ")


def _line_width(f: pygame.font.Font, it: Line) -> int:
    if it.image is not None:
        return it.image.get_width()
    if it.keys:
        return sum(_key_width(f, k) for k in it.keys)
    hint = text_width(f, "   " + it.hint) if it.hint else 0
    return text_width(f, it.text) + (_swatch_w(f) if it.swatch else 0) + hint


def _box_lines(lines: list, f: pygame.font.Font, max_width: int | None, pad: int) -> list[Line]:
    items = [_as_line(x) for x in lines]
    if max_width is None:
        return items if not any(it.tex and it.image is None for it in items) else \
            _box_lines(items, f, 10 ** 6, pad)
    wrapped: list[Line] = []
    for item in items:
        if item.tex:              # a formula: as wide as it is at this text size, or shrunk
            from app.draw.formula import fitted
            image = fitted(item.tex, max(6, f.get_height()), item.color, max_width - 2 * pad)
            if image is not None:
                wrapped.append(Line("", item.color, tex=item.tex, image=image))
            else:                 # still being drawn (the window's worker): its TeX meanwhile
                wrapped += _box_lines([Line(item.tex.strip("$"), DIM_COLOR)], f, max_width, pad)
            continue
        if item.keys and max(_key_width(f, k) for k in item.keys) > max_width - 2 * pad:
            # a key wider than the box: one wrapped line per key instead
            items_ = [Line(text, item.color, swatch=color) for color, text in item.keys]
            wrapped += _box_lines(items_, f, max_width, pad)
            continue
        if item.keys:             # the fewest rows that hold the key, evenly filled
            rows = _key_rows(item.keys, f, max_width - 2 * pad)
            wrapped += [Line("", item.color, keys=tuple(r)) for r in rows]
            continue
        room = max_width - 2 * pad - (_swatch_w(f) if item.swatch else 0)
        rows = wrap(item.text, f, room)
        hint = item.hint
        if hint and text_width(f, rows[-1] + "   " + hint) > room:
            hint = ""                       # no row of its own for a hint (the help has it)
        for i, t in enumerate(rows):
            wrapped.append(Line(t, item.color, item.swatch if i == 0 else None,
                                hint=hint if i == len(rows) - 1 else ""))
    return wrapped


def _key_rows(keys: tuple, f: pygame.font.Font, width: int) -> list[list]:
    """Key items in rows no wider than `width`: as few rows as fit, then as even as can be
    (never '>20%' alone on a second row under eight items)."""
    widths = [_key_width(f, k) for k in keys]

    def pack(limit: float) -> list[list]:
        rows: list[list] = [[]]
        used = 0                          # the width of the row so far
        for k, w in zip(keys, widths):
            if rows[-1] and used + w > limit:
                rows.append([])
                used = 0
            rows[-1].append(k)
            used += w
        return rows
    rows = pack(width)
    if len(rows) > 1:
        total = sum(widths)
        limit = total / len(rows)
        while limit < width:              # the narrowest limit that needs no more rows
            even = pack(limit)
            if len(even) == len(rows):
                return even
            limit += max(1.0, 0.02 * width)
    return rows


def _swatch_w(f: pygame.font.Font) -> int:
    return f.get_height() + f.get_height() // 3


def box_size(lines: list, size: int = HUD_SIZE, pad: int = 8,
             max_width: int | None = None) -> tuple[int, int]:
    """The (w, h) that text_box would take for these lines (the layout reserves it)."""
    f = font(size)
    items = _box_lines(lines, f, max_width, pad)
    if not items:
        return (0, 0)
    w = max(_line_width(f, it) for it in items)
    return (w + 2 * pad, sum(_line_height(f, it) for it in items) + 2 * pad)


def _line_height(f: pygame.font.Font, it: Line) -> int:
    """A text row's height, or a formula's with a little air below it."""
    return f.get_linesize() if it.image is None else it.image.get_height() + f.get_linesize() // 4


def text_box(surface: pygame.Surface, lines: list, pos: tuple[int, int], size: int = HUD_SIZE,
             pad: int = 8, max_width: int | None = None, from_bottom: bool = False,
             color: tuple = BOX_COLOR) -> pygame.Rect:
    """Draw lines on a dark backing box whose top-left is `pos` (bottom-left if `from_bottom`);
    return the box's rectangle. Lines wider than `max_width` are wrapped."""
    f = font(size)
    items = _box_lines(lines, f, max_width, pad)
    if not items:
        return pygame.Rect(pos, (0, 0))
    w, h = box_size(items, size, pad)
    box = pygame.Surface((w, h), pygame.SRCALPHA)
    box.fill(color)
    if from_bottom:
        pos = (pos[0], pos[1] - h)
    surface.blit(box, pos)
    y = pos[1] + pad
    for it in items:
        x = pos[0] + pad
        if it.image is not None:
            surface.blit(it.image, (x, y))
            y += _line_height(f, it)
            continue
        for color, text in it.keys:
            if color is not None:
                side = f.get_height() * 3 // 4
                pygame.draw.rect(surface, color, (x, y + (f.get_height() - side) // 2, side, side))
                x += _swatch_w(f)
            surface.blit(rendered(f, text, it.color), (x, y))
            x += text_width(f, text + "  ")
        if it.swatch:
            side = f.get_height() * 3 // 4
            pygame.draw.rect(surface, it.swatch, (x, y + (f.get_height() - side) // 2, side, side))
            x += _swatch_w(f)
        surface.blit(rendered(f, it.text, (0, 0, 0)), (x + 1, y + 1))
        surface.blit(rendered(f, it.text, it.color), (x, y))
        if it.hint:
            x += text_width(f, it.text + "   ") if it.text else 0
            surface.blit(rendered(f, it.hint, DIM_COLOR), (x, y))
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
    w = max(text_width(f, t) for t in lines) + 24
    top = (area.bottom if bottom is None else bottom) - h - 20 if y is None else y
    rect = pygame.Rect(area.centerx - w // 2, top, w, h)
    box = pygame.Surface(rect.size, pygame.SRCALPHA)
    box.fill((40, 10, 10, 225) if color == ERROR_COLOR or color == WARN_COLOR else BOX_COLOR)
    surface.blit(box, rect.topleft)
    pygame.draw.rect(surface, color, rect, 2)
    yy = rect.top + 12
    for t in lines:
        surface.blit(rendered(f, t, color), (rect.left + 12, yy))
        yy += f.get_linesize()
    return rect


MAX_METRIC_LINES = 2     # lines of metrics at the bottom of the world (--json has them all)
HUD_WIDTH = 640          # widest HUD box at text scale 1


def dt_text(scene) -> str:
    """'dt = 1/60 s in 4 substeps': the step the scene runs at."""
    sub = scene.p["substeps"]
    return f"dt = 1/{scene.p['hertz']} s" + (f" in {sub} substeps" if sub > 1 else "")


DETAILS_HINT = ("F4: more", "F4: less")


def scene_lines(scene, status: list, notes: list = (), details: bool = False,
                more: list = ()) -> list:
    """The HUD box of a scene: its title, the shell's `status` lines (time, cost, pause...),
    the scene's hud_lines() (what a class reads every frame), its colour key, the passing
    `notes` (messages), and on the second page (`details`) the scene's hud_details() and the
    shell's `more` lines after them. The window, headless screenshots and any pane draw the
    same box."""
    lines: list = [Line(scene.title or scene.name, ACCENT_COLOR,
                        hint=DETAILS_HINT[1 if details else 0]), *status]
    lines += [x if isinstance(x, Line) else str(x) for x in scene.hud_lines()]
    key = tuple(getattr(scene, "color_key", ()))
    late = getattr(scene, "color_key_details", False)
    if key and not late:      # packed into as many rows as it takes
        lines.append(Line("", DIM_COLOR, keys=key))
    lines += list(notes)
    if details:
        lines += [x if isinstance(x, Line) else Line(str(x), DIM_COLOR)
                  for x in scene.hud_details()]
        if late:              # a long key: a line per colour
            lines += [Line(text, DIM_COLOR, swatch=color) for color, text in key]
        lines += [x if isinstance(x, Line) else Line(str(x), DIM_COLOR) for x in more]
    return lines


def ms_text(ms: float | None) -> str:
    """Milliseconds to three figures at most: '0.35', '4.21', '29.6', '312'."""
    if ms is None:
        return fmt_number(None)
    return f"{ms:.0f}" if ms >= 100 else f"{ms:.1f}" if ms >= 10 else f"{ms:.2f}"


def physics_text(step_ms: float | None) -> str:
    """'physics 1.59 ms/step': the one physics figure of the HUD."""
    return f"physics {ms_text(step_ms)} ms/step"


def physics_line(step_ms: float | None, costs: dict[str, float]) -> str:
    """'physics 1.59 ms/step (structural 0.80, shear 0.31, ...)': the one physics figure of the
    HUD with the scene's breakdown by effect (the HUD's second page)."""
    text = physics_text(step_ms)
    if costs:
        text += " (" + ", ".join(f"{k} {v:.2f}" for k, v in costs.items()) + ")"
    return text


def hud_width(area: pygame.Rect) -> int:
    """How wide the HUD box may grow in `area` (it wraps its lines to this)."""
    return max(1, min(area.width - 16, int(HUD_WIDTH * TEXT.scale)))


def metric_lines(scene, metrics: dict, width: int, size: int = HUD_SIZE) -> list[str]:
    """`metrics` packed into at most MAX_METRIC_LINES lines of `width` pixels, each value in the
    unit the HUD uses for it (scene.shown); what does not fit is counted as "+N more (--json)"."""
    items = [f"{k} {scene.shown(k, v)}" for k, v in metrics.items()]
    f = font(size)
    lines = pack(items, f, width - 16)
    if len(lines) > MAX_METRIC_LINES:
        lines = pack(items, f, width - 16 - f.size("  |  +99 more (--json)")[0])[:MAX_METRIC_LINES]
        more = len(items) - sum(line.count("  |  ") + 1 for line in lines)
        lines[-1] += f"  |  +{more} more (--json)"
    return lines


def strip_height(scene, area: pygame.Rect, size: int = HUD_SIZE) -> int:
    """Height of the metrics strip along the bottom of `area` (0 if the scene has none): the
    room for MAX_METRIC_LINES lines, so the layout does not jump when a value gets longer."""
    if not scene.metrics_box or not scene.metrics():
        return 0
    return MAX_METRIC_LINES * font(size).get_linesize() + 16 + 6


def draw_metrics(surface: pygame.Surface, area: pygame.Rect, scene,
                 size: int = HUD_SIZE) -> pygame.Rect:
    """The metrics strip along the bottom of `area` (text of `size`); return its rectangle."""
    lines = metric_lines(scene, scene.metrics(), area.width - 16, size) if scene.metrics_box \
        else []
    if not lines:
        return pygame.Rect(area.left, area.bottom, 0, 0)
    return text_box(surface, lines, (area.left + 8, area.bottom - 6), size,
                    max_width=area.width - 16, from_bottom=True)


def reflow(doc: str) -> str:
    """Join a docstring's hard-wrapped lines into paragraphs (so the overlay can wrap them to its
    own width); list items, indented lines and blank lines keep their line breaks."""
    out: list[str] = []
    for line in doc.split("\n"):
        stripped = line.strip()
        starts_item = stripped[:1] in ("-", "*", "+") or stripped[:2].rstrip(".").isdigit()
        joinable = (out and out[-1].strip() and stripped and not starts_item
                    and not line.startswith((" ", "\t")))
        if joinable:
            out[-1] = out[-1].rstrip() + " " + stripped
        else:
            out.append(line.rstrip())
    return "\n".join(out)


class HelpPage:
    """The help overlay's content laid out for a width: the scene's description (paragraphs
    reflowed, lists kept), the shell's keys and the scene's settings, all wrapped, nothing cut.
    Taller than the screen, it scrolls (the help view's arrows and wheel)."""

    def __init__(self, width: int, title: str, doc: str, keys: list[tuple[str, str]],
                 settings: list[tuple[str, str]]):
        f_title, f, f_head = font(TITLE_SIZE), font(HELP_SIZE), font(HELP_SIZE)
        self.items: list[tuple[int, int, pygame.Surface]] = []    # (x, y, rendered text)
        gap = f.get_linesize() // 2
        two = width >= int(1100 * TEXT.scale)      # description left, keys and settings right
        col_w = (width - 40) // 2 if two else width
        self._put(0, 0, f_title.render(title, True, ACCENT_COLOR))
        top = f_title.get_linesize() + gap
        y = self._para(0, top, reflow(doc), f, col_w)
        x2, y2 = (col_w + 40, top) if two else (0, y + gap)
        y2 = self._table(x2, y2, "Keys of every scene", keys, f, f_head, col_w)
        if settings:
            y2 = self._table(x2, y2 + gap, "Settings (the panel, or --set NAME=VALUE)", settings,
                             f, f_head, col_w)
        self.height = max(y, y2)

    def _put(self, x: int, y: int, img: pygame.Surface) -> None:
        self.items.append((x, y, img))

    def _para(self, x: int, y: int, text: str, f: pygame.font.Font, width: int) -> int:
        for t in wrap(text, f, width):
            if t:
                self._put(x, y, f.render(t, True, TEXT_COLOR))
            y += f.get_linesize()
        return y

    def _table(self, x: int, y: int, head: str, rows: list[tuple[str, str]], f, f_head,
               width: int) -> int:
        for t in wrap(head, f_head, width):
            self._put(x, y, f_head.render(t, True, ACCENT_COLOR))
            y += f_head.get_linesize()
        name_w = min(max(f.size(k)[0] for k, _ in rows) + 16, width // 3)
        for name, what in rows:
            names = wrap(name, f, name_w - 8)
            whats = wrap(what, f, width - name_w)
            for i, t in enumerate(names):
                self._put(x, y + i * f.get_linesize(), f.render(t, True, WARN_COLOR))
            for i, t in enumerate(whats):
                self._put(x + name_w, y + i * f.get_linesize(), f.render(t, True, TEXT_COLOR))
            y += max(len(names), len(whats)) * f.get_linesize()
        return y

    def draw(self, surface: pygame.Surface, rect: pygame.Rect, scroll: int) -> None:
        """Draw the page in `rect`, scrolled down by `scroll` pixels."""
        surface.set_clip(rect)
        for x, y, img in self.items:
            yy = rect.top + y - scroll
            if yy + img.get_height() >= rect.top and yy <= rect.bottom:
                surface.blit(img, (rect.left + x, yy))
        surface.set_clip(None)


HELP_BACKGROUND = (12, 14, 19)      # opaque: the room reads the text, not the scene behind it
