"""P: the list of what can be plotted over time, over a running scene (which runs on underneath,
its plot changing as you pick).

    Up/Down        choose a row          Enter, Space or a click   plot it or not
    Left/Right     the rolling window (5, 10, 30, 60, 120 s)      L   linear or log y axis
    P or Esc       close the list (the plot stays; unpick everything to remove it)

Every number the scene reports is listed with its value now (in the HUD's unit); several can be
plotted at once (a legend names them); in compare mode each is drawn once per pane.
"""

from __future__ import annotations

from typing import Any

import pygame

from app import keys
from app.draw import hud
from app.draw.text import TEXT, font
from app.instruments import WINDOWS
from app.window.views import ShellView, WindowLike

PICKER_SIZE = 24
BOX = (12, 14, 19)
ROW_ON = (120, 210, 120)
SELECTED = (40, 48, 62)
HINT = ("Up/Down + Enter or a click: plot it or not  |  Left/Right: window  |  L: log y  |  "
        "P or Esc: close")


class PlotPicker(ShellView):
    """The list over the running view `under` (an InstrumentHost)."""

    def __init__(self, window: WindowLike, under: Any):
        super().__init__(window)
        self.under = under
        self.selected = 0
        self.rows: list[tuple[pygame.Rect, str]] = []     # (screen rect, what the row is)
        self.box = pygame.Rect(0, 0, 0, 0)

    @property
    def scene(self):
        return self.under.scene

    @property
    def inst(self):
        return self.under.inst

    def items(self) -> list[str]:
        """The rows: each metric, then the window and the y axis."""
        return self.inst.choices() + ["@window", "@log"]

    def on_layout(self) -> None:
        self.under.on_layout()

    # --- keys and mouse -----------------------------------------------------------------------
    def close(self) -> None:
        self.window.show_view(self.under)

    def toggle_plot(self) -> None:
        self.close()

    escape = close

    def shell_key(self, key: int) -> bool:
        action = keys.action_for(pygame.key.name(key))
        if action in ("toggle_plot", "escape", "toggle_large_text", "screenshot",
                      "toggle_arrows"):
            if action == "toggle_arrows":
                self.under.toggle_arrows()
                return True
            return super().shell_key(key)
        return False

    def handle_event(self, ev: pygame.event.Event) -> None:
        items = self.items()
        if ev.type == pygame.KEYDOWN:
            if ev.key in (pygame.K_DOWN, pygame.K_UP):
                self.selected = (self.selected + (1 if ev.key == pygame.K_DOWN else -1)) % \
                    len(items)
            elif ev.key in (pygame.K_RETURN, pygame.K_KP_ENTER, pygame.K_SPACE):
                self.choose(items[min(self.selected, len(items) - 1)])
            elif ev.key in (pygame.K_LEFT, pygame.K_RIGHT):
                self.change_window(+1 if ev.key == pygame.K_RIGHT else -1)
            elif ev.key == pygame.K_l:
                self.choose("@log")
            else:
                self.shell_key(ev.key)
        elif ev.type == pygame.MOUSEBUTTONDOWN and ev.button == 1:
            for rect, item in self.rows:
                if rect.collidepoint(ev.pos):
                    self.selected = items.index(item) if item in items else 0
                    self.choose(item)
                    return
        elif ev.type == pygame.MOUSEMOTION:
            for rect, item in self.rows:
                if rect.collidepoint(ev.pos) and item in items:
                    self.selected = items.index(item)

    def choose(self, item: str) -> None:
        if item == "@window":
            self.change_window(+1, wrap=True)
        elif item == "@log":
            self.inst.log = not self.inst.log
        else:
            had = bool(self.inst.plot)
            self.inst.toggle_metric(item)
            if bool(self.inst.plot) != had:
                self.under.plot_changed()      # the plot strip came or went: a new room

    def change_window(self, step: int, wrap: bool = False) -> None:
        i = WINDOWS.index(self.inst.window) if self.inst.window in WINDOWS else 1
        i = (i + step) % len(WINDOWS) if wrap else min(max(i + step, 0), len(WINDOWS) - 1)
        self.inst.window = WINDOWS[i]

    # --- time and drawing ---------------------------------------------------------------------
    def update(self, frame_seconds: float) -> int:
        return self.under.update(frame_seconds)

    def row_text(self, item: str, metrics: dict) -> tuple[str, tuple]:
        inst = self.inst
        if item == "@window":
            return f"window: the last {inst.window:g} s  (Left/Right)", hud.ACCENT_COLOR
        if item == "@log":
            return f"y axis: {'log' if inst.log else 'linear'}  (L)", hud.ACCENT_COLOR
        on = item in inst.plot
        value = self.scene.shown(item, metrics.get(item))
        return f"[{'x' if on else ' '}] {item}   {value}", ROW_ON if on else hud.TEXT_COLOR

    def draw(self, screen: pygame.Surface) -> None:
        """The list at the window's top right, over the panel (its hint wrapped to the panel's
        width, its text shrunk to fit there first); over the scene or a pane of a comparison
        only when even the smallest text is wider than the panel (or the panel is hidden), in
        as many columns as its height needs. `box`: where it was drawn."""
        self.under.draw(screen)
        metrics = self.scene.metrics()
        items = self.items()
        texts = [self.row_text(item, metrics) for item in items]
        world = self.under.world_area()
        area = pygame.Rect(world.left, world.top, screen.get_width() - world.left, world.height)
        panel = pygame.Rect(world.right, world.top, screen.get_width() - world.right,
                            world.height)
        room = panel if panel.width > 0 else area
        pad = int(12 * TEXT.scale)
        title = "Plot over time: pick what to plot"
        size = PICKER_SIZE          # large text in a small window: the list gives back some
        while True:                 # of its growth (never below the normal size)
            f = font(size)
            lh = f.get_linesize()
            hint = hud.wrap(HINT, f, max(room.width - 16 - 2 * pad, 120))
            free = area.height - 16 - 2 * pad - int(lh * 1.5) - (len(hint) + 1) * lh
            per_col = max(1, free // lh)
            cols = -(-len(texts) // per_col)
            per_col = -(-len(texts) // cols)
            col_w = max(f.size(t)[0] for t, _ in texts) + pad
            width = max(cols * col_w, f.size(title)[0], max(f.size(h)[0] for h in hint)) + \
                2 * pad
            if width <= room.width - 16 or size * TEXT.scale <= PICKER_SIZE * 0.75:
                break
            size = max(size * 0.9, PICKER_SIZE * 0.75 / TEXT.scale)
        width = min(width, area.width - 16)
        height = 2 * pad + int(lh * 1.5) + (per_col + 1 + len(hint)) * lh
        box = pygame.Rect(area.right - width - 8, area.top + 8, width,
                          min(height, area.height - 16))
        self.box = box
        screen.fill(BOX, box)
        pygame.draw.rect(screen, hud.ACCENT_COLOR, box, 2)
        old_clip = screen.get_clip()
        screen.set_clip(box.clip(old_clip))
        top = box.top + pad // 2
        screen.blit(f.render(title, True, hud.ACCENT_COLOR), (box.left + pad, top))
        top += int(lh * 1.5)
        self.rows = []
        self.selected = min(self.selected, len(items) - 1)
        for k, (item, (text, color)) in enumerate(zip(items, texts)):
            x = box.left + pad + (k // per_col) * col_w
            y = top + (k % per_col) * lh
            rect = pygame.Rect(x - 4, y, col_w, lh)
            if k == self.selected:
                screen.fill(SELECTED, rect)
            screen.blit(f.render(text, True, color), (x, y))
            self.rows.append((rect, item))
        y = top + (per_col + 0.5) * lh
        for h in hint:
            screen.blit(f.render(h, True, hud.DIM_COLOR), (box.left + pad, y))
            y += lh
        screen.set_clip(old_clip)


__all__ = ["PlotPicker"]
