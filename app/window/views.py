"""What the window shows, one view at a time (arcade's View / show_view): the scene menu, a
running scene (app/window/scene_view.py), and the help overlay of a running scene.

Each view handles the pygame events routed to it, advances its state once per frame (`update`)
and draws itself (`draw`). Shell keys are looked up in the one key table (app/keys.py) and
run as the view's method named by the table's action (or the window's, for the actions every view
shares: large text, screenshot, scene switching); a view that has no such method ignores the key.

This module imports nothing of the window: a view reaches the window through the object it is
given (`WindowLike` says what it may ask for), so imports run one way (window -> scene_view ->
views).
"""

from __future__ import annotations

from typing import Any, Protocol

import pygame

from app import keys
from app.draw import hud, menu
from app.draw.text import TEXT, font
from app.scene import Scene, docstring_help


class WindowLike(Protocol):
    """What a view may ask of the window that shows it (app/window/window.py's Window)."""

    screen: pygame.Surface
    scenes: list[type[Scene]]
    menu_selected: int
    running: bool
    panel_visible: bool
    hud_details: bool
    wall: float
    last_draw_seconds: float
    recorder: Any
    PANEL_WIDTH: int
    arrows: bool                 # the arrows overlay (V), for every scene
    csv_path: str | None         # --csv: the file the open scene's metrics go to
    plot_start: list[str]        # --plot: the metrics the first scene opens plotted

    def show_view(self, view: "ShellView") -> None: ...
    def open_scene(self, scene_cls: type[Scene], overrides: dict | None = None) -> bool: ...
    def open_compare(self, scene_cls: type[Scene], shared: dict, variants: list,
                     card: Any = None) -> bool: ...
    def own_csv(self, view: Any) -> None: ...
    def open_menu(self) -> None: ...
    def flash(self, text: str, color: tuple = ..., seconds: float = ...,
              topic: str = "") -> None: ...
    def clear_messages(self, *topics: str) -> None: ...


class RunningScene(Protocol):
    """What the help overlay asks of the view of the scene it covers."""

    scene: Scene

    def update(self, frame_seconds: float) -> int: ...
    def on_layout(self) -> None: ...


class ShellView:
    """A screen of the window. Override what you use (hooks that do nothing by default)."""

    def __init__(self, window: WindowLike):
        self.window = window

    def on_show(self) -> None:
        """The view became the window's current one."""

    def on_hide(self) -> None:
        """Another view replaces this one."""

    def on_layout(self) -> None:
        """The window's size or the text size changed."""

    def handle_event(self, ev: pygame.event.Event) -> None:
        if ev.type == pygame.KEYDOWN:
            self.shell_key(ev.key)

    def update(self, frame_seconds: float) -> int:
        return 0

    def draw(self, screen: pygame.Surface) -> None:
        pass

    def shell_key(self, key: int) -> bool:
        """Run the action of a shell key (the key table); True if `key` is one."""
        action = keys.action_for(pygame.key.name(key))
        if action is None:
            return False
        method = getattr(self, action, None) or getattr(self.window, action, None)
        if method is not None:
            method(key) if action == "pick" else method()
        return True


# ----------------------------------------------------------------------------------------------
class MenuView(ShellView):
    """The scene menu: categories, scenes numbered in the order shown, click or press a digit."""

    def __init__(self, window: WindowLike, message: str = ""):
        super().__init__(window)
        self.message = message
        self.entries: list[menu.MenuEntry] = []

    @property
    def order(self) -> list[int]:
        return menu.menu_order(self.window.scenes)

    def pick(self, key: int) -> None:
        """Digit n opens the n-th scene shown."""
        name = pygame.key.name(key).strip("[]")
        n = int(name) if name.isdigit() else 0
        if 1 <= n <= len(self.order):
            self.window.open_scene(self.window.scenes[self.order[n - 1]])

    def escape(self) -> None:
        self.window.running = False

    def handle_event(self, ev: pygame.event.Event) -> None:
        order, w = self.order, self.window
        if ev.type == pygame.KEYDOWN:
            if self.shell_key(ev.key):
                return
            if ev.key in (pygame.K_DOWN, pygame.K_UP) and order:
                i = order.index(w.menu_selected) if w.menu_selected in order else 0
                i = (i + (1 if ev.key == pygame.K_DOWN else -1)) % len(order)
                w.menu_selected = order[i]
            elif ev.key in (pygame.K_RETURN, pygame.K_KP_ENTER) and order:
                w.open_scene(w.scenes[w.menu_selected])
        elif ev.type == pygame.MOUSEMOTION:
            for entry in self.entries:
                if entry.rect.collidepoint(ev.pos):
                    w.menu_selected = entry.index
        elif ev.type == pygame.MOUSEBUTTONDOWN and ev.button == 1:
            for entry in self.entries:
                if entry.rect.collidepoint(ev.pos):
                    w.open_scene(w.scenes[entry.index])
                    return

    def draw(self, screen: pygame.Surface) -> None:
        self.entries = menu.draw_menu(screen, self.window.scenes, self.window.menu_selected,
                                     self.message)


# ----------------------------------------------------------------------------------------------
class HelpView(ShellView):
    """The help overlay of a running scene: opaque, wrapped, scrollable; the scene runs on
    underneath. Esc, H or F1 close it."""

    def __init__(self, window: WindowLike, under: RunningScene):
        super().__init__(window)
        self.under = under
        self.scroll = 0
        self.page: hud.HelpPage | None = None
        self.page_rect = pygame.Rect(0, 0, 0, 0)

    @property
    def scene(self) -> Scene:
        return self.under.scene

    def on_layout(self) -> None:
        self.page = None
        self.under.on_layout()

    def toggle_help(self) -> None:
        self.window.show_view(self.under)

    escape = toggle_help

    def shell_key(self, key: int) -> bool:
        action = keys.action_for(pygame.key.name(key))
        if action in ("toggle_help", "escape", "toggle_large_text", "screenshot",
                      "toggle_fullscreen"):
            return super().shell_key(key)
        return action is not None           # the other shell keys wait until the help closes

    def handle_event(self, ev: pygame.event.Event) -> None:
        step = font(hud.HELP_SIZE).get_linesize()
        if ev.type == pygame.KEYDOWN:
            if self.shell_key(ev.key):
                return
            if ev.key in (pygame.K_DOWN, pygame.K_UP):
                self.scroll_by(step * (3 if ev.key == pygame.K_DOWN else -3))
            elif ev.key in (pygame.K_END, pygame.K_HOME):
                self.scroll_by(10**6 if ev.key == pygame.K_END else -10**6)
        elif ev.type == pygame.MOUSEWHEEL:
            self.scroll_by(-ev.y * 3 * step)

    def scroll_by(self, dy: int) -> None:
        room = self.page.height - self.page_rect.height if self.page else 0
        self.scroll = int(min(max(self.scroll + dy, 0), max(room, 0)))

    def update(self, frame_seconds: float) -> int:
        return self.under.update(frame_seconds)

    def build_page(self, screen: pygame.Surface) -> hud.HelpPage:
        scene = self.scene
        settings = [(prm.name, prm.help or prm.accepted()) for prm in scene.all_params()]
        settings += [(eff.name, f"effect, now {'on' if eff.name in scene.on else 'off'}: "
                      f"{eff.help}") for eff in scene.effects]
        pad = int(24 * TEXT.scale)
        self.page_rect = screen.get_rect().inflate(-2 * pad, -2 * pad)
        self.page_rect.height -= font(hud.HUD_SIZE).get_linesize()
        return hud.HelpPage(self.page_rect.width, scene.title or scene.name,
                            docstring_help(type(scene)), keys.help_rows(), settings)

    def draw(self, screen: pygame.Surface) -> None:
        if self.page is None or self.page_rect.width != screen.get_width() - 2 * int(
                24 * TEXT.scale):
            self.page = self.build_page(screen)
            self.scroll_by(0)
        screen.fill(hud.HELP_BACKGROUND)
        self.page.draw(screen, self.page_rect, self.scroll)
        more = self.page.height - self.page_rect.height
        hint = "Esc, H or F1 close the help"
        if more > 0:
            hint = (f"Up/Down, Home/End or the mouse wheel scroll ({100 * self.scroll // more}%)"
                    f";  {hint}")
        f = font(hud.HUD_SIZE)
        img = f.render(hint, True, hud.DIM_COLOR)
        screen.blit(img, (screen.get_width() - img.get_width() - 16,
                          screen.get_height() - f.get_linesize() - 6))


def safe(fn, default):
    """fn(), or `default` if the scene raised SceneError (its message is shown elsewhere)."""
    from app.scene import SceneError
    try:
        return fn()
    except SceneError:
        return default


def slow_text(factor: float) -> str:
    """A slow-motion factor as the HUD writes it: '1', '1/2', '1/8'."""
    return "1" if factor == 1.0 else f"1/{int(round(1 / factor))}"


__all__ = ["ShellView", "MenuView", "HelpView", "safe", "slow_text"]
