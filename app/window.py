"""The interactive window: scene menu, parameter panel, HUD, help overlay, screenshots, recording.

`python -m app` opens the menu; `python -m app --scene cloth` opens one scene. The window runs every
scene the same way the headless runner does: a fixed-timestep loop (app.loop.FixedStepClock) calls
`scene.advance()` a whole number of times per frame, mouse and key events reach the scene as
`InputEvent`s in world coordinates, and parameter changes go through `scene.set()` (which validates
and rebuilds when needed). What the window adds is for people in a room:

  Space pause/resume   .  one step        - / =  slow motion x1 .. x1/8 (dt never changes)
  R reset              H or F1  help      F2  large text       F12  screenshot to screenshots/
  Tab  panel on/off    PageUp/PageDown  previous/next scene   Esc  menu (quit from the menu)

Everything else (other keys, mouse in the world area) goes to the scene. The HUD shows frames per
second, the median physics milliseconds per step over the last second (the time of
`scene.advance()` alone, drawing excluded), the scene's metrics and the cost of each effect.

If the state goes non-finite (NaN or inf) the window rolls back to the last good snapshot, pauses
and says so, instead of drawing garbage or crashing.

`--record FILE` writes the mouse and key events the scene received (and each R, as a key "r" the
headless runner also treats as a reset) in the `--input` format: positions in world coordinates,
t in simulated seconds counted as the headless runner counts them (steps x dt since the scene was
opened). So a demo done by hand replays headless, step for step:
`python -m app --headless --scene NAME --input FILE --steps N`. Panel changes are not events:
give them with --set.

The `Window` class does the work and never owns the main loop, so tests drive it directly
(handle_pygame_event, update, render); `run_window` is the loop the command line calls.
"""

from __future__ import annotations

import json
import math
import os
import statistics
import sys
import time
import traceback
from collections import deque
from dataclasses import replace
from pathlib import Path
from typing import Any, Sequence

import pygame

from app.draw import hud, save_png
from app.draw.text import TEXT, font
from app.draw.view import View
from app.loop import FixedStepClock
from app.headless import deliver
from app.scene import EVENT_SLACK, SHELL_KEYS, InputEvent, ParamError, Scene, docstring_help

ROOT = Path(__file__).resolve().parent.parent
THEME_PATH = ROOT / "assets" / "theme.json"
DEFAULT_SIZE = (1280, 800)        # world 960x720 at zoom 1 + a 320 px panel
PANEL_WIDTH = 320
LARGE_TEXT_SCALE = 1.6
FPS_CAP = 60
SNAPSHOT_EVERY = 30               # steps between last-good snapshots
STEP_BUDGET_SECONDS = 0.1         # physics time per frame after which the frame's other steps
                                  # are dropped (the window stays responsive; time runs slower)
MESSAGE_SECONDS = 4.0
NO_DISPLAY = "no display for the window: {}; use --headless, or run under xvfb-run"

NONFINITE_TEXT = ("The simulation went non-finite (NaN/inf, or past the scene's blow-up bounds) "
                  "at t={bad:.3f} s: rolled back to "
                  "t={good:.3f} s and paused. Try a smaller dt (raise hertz) or more substeps.")


# ----------------------------------------------------------------------------------------------
# the parameter panel
# ----------------------------------------------------------------------------------------------
def _value_text(value: Any) -> str:
    """How a parameter value is written in the panel's text boxes."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return format(value, ".6g")
    return str(value)


class _NumberControl:
    """Slider + text box for an int or float Param. The slider runs 0..1000 and maps to the
    value linearly, or logarithmically when the range spans two decades or more."""

    STEPS = 1000

    def __init__(self, prm, slider):
        self.prm = prm
        self.slider = slider
        lo, hi = float(prm.lo), float(prm.hi)
        self.log = lo > 0 and hi / lo >= 100

    def value_at(self, pos: float) -> float | int:
        lo, hi = float(self.prm.lo), float(self.prm.hi)
        u = min(max(pos / self.STEPS, 0.0), 1.0)
        v = lo * (hi / lo) ** u if self.log else lo + (hi - lo) * u
        return int(round(v)) if self.prm.kind is int else float(f"{v:.4g}")

    def pos_of(self, value: float) -> int:
        lo, hi = float(self.prm.lo), float(self.prm.hi)
        if hi <= lo:
            return 0
        if self.log:
            u = math.log(max(value, lo) / lo) / math.log(hi / lo)
        else:
            u = (value - lo) / (hi - lo)
        return int(round(min(max(u, 0.0), 1.0) * self.STEPS))


class ParamPanel:
    """The right-hand panel built from scene.all_params() and scene.effects (pygame-gui)."""

    def __init__(self, window: "Window", manager, rect: pygame.Rect):
        import pygame_gui
        from pygame_gui.elements import (UIButton, UIDropDownMenu, UIHorizontalSlider, UILabel,
                                         UIScrollingContainer, UITextEntryLine)
        self.gui = pygame_gui
        self.window = window
        self.manager = manager
        self.rect = rect
        scene = window.scene
        s = TEXT.scale
        row = int(round(30 * s))
        gap = int(round(6 * s))
        pad = 10
        self.container = UIScrollingContainer(rect, manager, allow_scroll_x=False)
        inner_w = rect.width - 2 * pad - 20       # room for the vertical scroll bar
        y = pad
        self.numbers: dict[str, _NumberControl] = {}
        self.entries: dict[str, Any] = {}         # name -> UITextEntryLine (numbers, seed)
        self.dropdowns: dict[str, Any] = {}
        self.toggles: dict[str, Any] = {}         # name -> UIButton (bool params and effects)
        self._by_element: dict[Any, tuple[str, str]] = {}

        def label(text: str, width: int = inner_w, obj: str | None = None, x: int = pad):
            UILabel(pygame.Rect(x, y, width, row), text, manager, container=self.container,
                    object_id=obj)

        third = (inner_w - 2 * gap) // 3
        self.pause_button = UIButton(pygame.Rect(pad, y, third, row), "Pause", manager,
                                     container=self.container)
        self.reset_button = UIButton(pygame.Rect(pad + third + gap, y, third, row), "Reset",
                                     manager, container=self.container)
        self.help_button = UIButton(pygame.Rect(pad + 2 * (third + gap), y, third, row), "Help",
                                    manager, container=self.container)
        y += row + 2 * gap
        label("Parameters", obj="#section")
        y += row
        for prm in scene.all_params():
            value = scene.p[prm.name]
            tip = prm.help or None
            if prm.kind is bool:
                label(prm.name, width=inner_w // 2)
                b = UIButton(pygame.Rect(pad + inner_w // 2, y, inner_w - inner_w // 2, row),
                             "", manager, container=self.container, tool_tip_text=tip)
                self.toggles[prm.name] = b
                self._by_element[b] = ("toggle", prm.name)
                y += row + gap
                continue
            if prm.choices is not None:
                label(prm.name)
                y += row
                d = UIDropDownMenu(list(prm.choices), str(value),
                                   pygame.Rect(pad, y, inner_w, row), manager,
                                   container=self.container)
                self.dropdowns[prm.name] = d
                self._by_element[d] = ("choice", prm.name)
                y += row + gap
                continue
            label(f"{prm.name}   ({hud.fmt_number(prm.lo)} to {hud.fmt_number(prm.hi)})")
            y += row
            wide = prm.kind is int and (prm.hi - prm.lo) > 100_000   # e.g. seed: no slider
            entry_w = inner_w if wide else int(inner_w * 0.36)
            slider = None
            if not wide:
                slider = UIHorizontalSlider(pygame.Rect(pad, y, inner_w - entry_w - gap, row),
                                            0, (0, _NumberControl.STEPS), manager,
                                            container=self.container)
            entry = UITextEntryLine(pygame.Rect(pad + inner_w - entry_w, y, entry_w, row),
                                    manager, container=self.container)
            entry.set_text(_value_text(value))
            self.entries[prm.name] = entry
            self._by_element[entry] = ("entry", prm.name)
            if slider is not None:
                ctl = _NumberControl(prm, slider)
                slider.set_current_value(ctl.pos_of(value))
                self.numbers[prm.name] = ctl
                self._by_element[slider] = ("slider", prm.name)
            y += row + gap
        if scene.effects:
            y += gap
            label("Effects (off = not computed)", obj="#section")
            y += row
            for eff in scene.effects:
                b = UIButton(pygame.Rect(pad, y, inner_w, row), "", manager,
                             container=self.container, tool_tip_text=eff.help or None)
                self.toggles[eff.name] = b
                self._by_element[b] = ("toggle", eff.name)
                y += row + gap
        self.container.set_scrollable_area_dimensions((rect.width - 20, y + pad))
        self._toggle_state: dict[str, bool | None] = {}
        self.refresh()

    # --- reading the scene ---------------------------------------------------------------------
    def _current(self, name: str) -> Any:
        scene = self.window.scene
        return scene.p[name] if scene.param(name) is not None else (name in scene.on)

    def refresh(self) -> None:
        """Show the scene's current values (after a change, a refused value or a rebuild)."""
        for name, entry in self.entries.items():
            if not entry.is_focused:
                text = _value_text(self._current(name))
                if entry.get_text() != text:
                    entry.set_text(text)
        for name, ctl in self.numbers.items():
            if not ctl.slider.sliding_button.held:
                pos = ctl.pos_of(self._current(name))
                if int(ctl.slider.get_current_value()) != pos:
                    ctl.slider.set_current_value(pos)
        for name, b in self.toggles.items():
            on = bool(self._current(name))
            if self._toggle_state.get(name) != on:
                self._toggle_state[name] = on
                b.set_text(f"{name}: {'ON' if on else 'OFF'}" if self.window.scene.effect(name)
                           else ("ON" if on else "OFF"))
                b.change_object_id("#toggle_on" if on else "#toggle_off")
        paused = self.window.clock.paused
        want = "Resume" if paused else "Pause"
        if self.pause_button.text != want:
            self.pause_button.set_text(want)

    def is_typing(self) -> bool:
        """True while a text box of the panel has the keyboard."""
        return any(e.is_focused for e in self.entries.values())

    # --- pygame-gui events -------------------------------------------------------------------
    def handle(self, ev: pygame.event.Event) -> bool:
        """React to a pygame-gui event of this panel; return True if it was one."""
        gui = self.gui
        element = getattr(ev, "ui_element", None)
        if ev.type == gui.UI_BUTTON_PRESSED:
            if element is self.pause_button:
                self.window.toggle_pause()
                return True
            if element is self.reset_button:
                self.window.reset_scene()
                return True
            if element is self.help_button:
                self.window.show_help = not self.window.show_help
                return True
        what = self._by_element.get(element)
        if what is None:
            return False
        kind, name = what
        if kind == "toggle" and ev.type == gui.UI_BUTTON_PRESSED:
            self.window.apply_setting(name, not bool(self._current(name)))
        elif kind == "choice" and ev.type == gui.UI_DROP_DOWN_MENU_CHANGED:
            self.window.apply_setting(name, ev.text)
        elif kind == "entry" and ev.type == gui.UI_TEXT_ENTRY_FINISHED:
            self.window.apply_setting(name, ev.text)
            self.entries[name].unfocus()
        elif kind == "slider" and ev.type == gui.UI_HORIZONTAL_SLIDER_MOVED:
            value = self.numbers[name].value_at(ev.value)
            if value != self._current(name):
                self.window.apply_setting(name, value)
        else:
            return False
        self.refresh()
        return True


# ----------------------------------------------------------------------------------------------
# the window
# ----------------------------------------------------------------------------------------------
_THEMES: dict[float, dict] = {}


def theme(scale: float) -> dict:
    """assets/theme.json with every font size multiplied by `scale` (the large-text theme)."""
    if scale not in _THEMES:
        data = json.loads(THEME_PATH.read_text())      # a fresh dict for every scale
        for block in data.values():
            f = block.get("font") if isinstance(block, dict) else None
            if isinstance(f, dict) and "size" in f:
                f["size"] = str(int(round(float(f["size"]) * scale)))
        _THEMES[scale] = data
    return _THEMES[scale]


class Window:
    """The interactive shell around one scene at a time (or the menu when there is none).

    Drive it with handle_pygame_event(ev) for each pygame event, update(frame_seconds) once per
    frame, render() to draw on `screen`. `running` turns False when the user quits.
    """

    def __init__(self, screen: pygame.Surface, scenes: Sequence[type[Scene]] | None = None,
                 large_text: bool = False, events: list[InputEvent] | None = None,
                 screenshot_dir: str | Path = "screenshots", recording: bool = False):
        if scenes is None:
            from scenes import SCENES
            scenes = SCENES
        self.screen = screen
        self.scenes: list[type[Scene]] = list(scenes)
        self.screenshot_dir = Path(screenshot_dir)
        self.running = True
        self.scene: Scene | None = None
        self.clock = FixedStepClock()
        self.view = View()
        self.manager = None
        self.panel: ParamPanel | None = None
        self.panel_visible = True
        self.show_help = False
        self.menu_selected = 0
        self.menu_entries: list[hud.MenuEntry] = []
        self.menu_message = ""
        self.messages: list[tuple[float, str, tuple[int, int, int]]] = []   # (until, text, colour)
        self.nonfinite_banner = ""
        self.wall = 0.0                       # seconds of frames seen (update's clock)
        self.frame_times: deque[float] = deque()
        self.step_times: deque[tuple[float, float]] = deque()   # (wall, ms per advance)
        self.last_step_ms = float("nan")
        self.last_drop = -1e9                 # wall time of the last frame that dropped steps
        self.recorded: list[dict] = []        # events delivered to the scene, --input format
        self.session_steps = 0                # steps since the scene was opened (not reset by R)
        self.session_clock = 0.0
        self.recording = recording            # --record: warn that panel changes are not events
        self.recorded_changes: list[str] = []
        self.opened_with: dict[str, str] = {}
        self._dragging: set[int] = set()      # mouse buttons pressed in the world area
        self._replay = sorted(events or [], key=lambda e: e.t)
        self._replay_index = 0
        self._replay_scene: type[Scene] | None = None
        self._last_good: tuple[Any, float, int] | None = None
        self._pending_shot: Path | None = None
        self.set_large_text(large_text)

    # --- scenes and the menu ---------------------------------------------------------------
    def open_scene(self, scene_cls: type[Scene], overrides: dict[str, Any] | None = None) -> bool:
        """Build scene_cls(overrides) and show it; on a construction error stay in (or go back
        to) the menu and show the error. Return True if the scene is open."""
        try:
            scene = scene_cls(overrides or {})
        except ParamError as e:
            self._to_menu(f"{scene_cls.name}: {e}")
            return False
        except Exception as e:     # a broken scene must not take the classroom's window down
            traceback.print_exc()
            self._to_menu(f"{scene_cls.name} failed to build: {type(e).__name__}: {e}")
            return False
        self.scene = scene
        if scene_cls in self.scenes:
            self.menu_selected = self.scenes.index(scene_cls)
        if self._replay and self._replay_scene is None:
            self._replay_scene = scene_cls        # --input events belong to the first scene
        self.clock = FixedStepClock()
        self.show_help = False
        self._dragging.clear()
        self.recorded = []
        self.session_steps = 0
        self.session_clock = 0.0                  # simulated seconds since opened (sum of dt)
        self.recorded_changes = []                # panel changes while recording (not events)
        self.opened_with = {k: str(v) for k, v in (overrides or {}).items()}
        self.last_drop = -1e9
        self._after_rebuild()
        self._layout()
        if pygame.display.get_init():
            pygame.display.set_caption(f"Physics lab: {scene_cls.title or scene_cls.name}")
        return True

    def open_menu(self) -> None:
        self._to_menu("")

    def _to_menu(self, message: str) -> None:
        self.scene = None
        self.menu_message = message
        self.show_help = False
        self.nonfinite_banner = ""
        self._dragging.clear()
        self._layout()

    def switch_scene(self, delta: int) -> None:
        """PageUp/PageDown: the previous/next scene of the registry."""
        if not self.scenes:
            return
        if self.scene is None:
            i = self.menu_selected if delta > 0 else self.menu_selected - 1
        else:
            cls = type(self.scene)
            i = self.scenes.index(cls) + delta if cls in self.scenes else 0
        self.open_scene(self.scenes[i % len(self.scenes)])

    def _after_rebuild(self) -> None:
        """The scene was (re)built: forget the old state's snapshot and step times."""
        self.nonfinite_banner = ""
        self.step_times.clear()
        self._last_good = (self.scene.snapshot(), self.scene.time, self.scene.steps)

    def reset_scene(self) -> None:
        """R: rebuild the scene. The recording keeps it as a key "r" event, which the headless
        runner replays as a reset too."""
        if self.scene is not None:
            self.recorded.append(InputEvent("key_down", key="r", t=self.session_time).to_json())
            self.recorded.append(InputEvent("key_up", key="r", t=self.session_time).to_json())
            self.scene.reset()
            self._after_rebuild()
            if self.panel:
                self.panel.refresh()

    def apply_setting(self, name: str, value: Any) -> bool:
        """Change a param or effect through scene.set (validated). A refused value keeps the old
        one and shows why; return True if the value was taken."""
        scene = self.scene
        if scene is None:
            return False
        before = scene.settings().get(scene.canonical(name))
        try:
            rebuilt = scene.set(name, value)
        except ParamError as e:
            self.flash(str(e), hud.ERROR_COLOR)
            if self.panel:
                self.panel.refresh()
            return False
        except Exception as e:
            traceback.print_exc()
            self.flash(f"{name}={value!r} failed: {type(e).__name__}: {e}", hud.ERROR_COLOR)
            try:
                scene.set(name, before)
            except Exception:
                scene.reset()
            self._after_rebuild()
            return False
        after = scene.settings().get(scene.canonical(name))
        if rebuilt:
            self._after_rebuild()
        if after != before and self.recording:
            self.recorded_changes.append(f"{name}={after}")
            self.flash(f"recording: {name}={after} is a panel change, not an event; the "
                       "replay runs with the settings the scene was opened with", hud.WARN_COLOR)
        if self.panel:
            self.panel.refresh()
        return True

    # --- layout, text size -----------------------------------------------------------------
    @property
    def panel_width(self) -> int:
        if self.scene is None or not self.panel_visible:
            return 0
        return int(round(PANEL_WIDTH * TEXT.scale)) if TEXT.scale > 1 else PANEL_WIDTH

    def world_area(self) -> pygame.Rect:
        """The part of the window left of the panel, where the world is drawn."""
        w, h = self.screen.get_size()
        return pygame.Rect(0, 0, max(w - self.panel_width, 1), h)

    def _layout(self) -> None:
        """(Re)build the view and the pygame-gui manager and panel for the current size."""
        import pygame_gui
        size = self.screen.get_size()
        self.manager = None
        self.panel = None
        if self.scene is None:
            return
        area = self.world_area()
        self.view = View.fit(self.scene.world_size, tuple(area))
        self.manager = pygame_gui.UIManager(size, theme_path=theme(TEXT.scale))
        if self.panel_visible:
            rect = pygame.Rect(area.right, 0, size[0] - area.right, size[1])
            self.panel = ParamPanel(self, self.manager, rect)

    def set_large_text(self, on: bool) -> None:
        TEXT.scale = LARGE_TEXT_SCALE if on else 1.0
        self._layout()

    @property
    def large_text(self) -> bool:
        return TEXT.scale > 1.0

    def resize(self, surface: pygame.Surface | None = None) -> None:
        self.screen = surface or pygame.display.get_surface() or self.screen
        self._layout()

    # --- messages --------------------------------------------------------------------------
    def flash(self, text: str, color=hud.WARN_COLOR, seconds: float = MESSAGE_SECONDS) -> None:
        """Show a message for a few seconds."""
        self.messages.append((self.wall + seconds, text, color))

    # --- events ----------------------------------------------------------------------------
    def handle_pygame_event(self, ev: pygame.event.Event) -> None:
        if ev.type == pygame.QUIT:
            self.running = False
            return
        if ev.type == pygame.VIDEORESIZE:
            self.resize()
            return
        if self.scene is None:
            self._menu_event(ev)
            return
        consumed = False
        if self.manager is not None:
            consumed = bool(self.manager.process_events(ev))
        if self.panel is not None and ev.type >= pygame.USEREVENT and self.panel.handle(ev):
            return
        if ev.type in (pygame.KEYDOWN, pygame.KEYUP, pygame.TEXTINPUT):
            if consumed or (self.panel is not None and self.panel.is_typing()):
                return                      # the keys are typing a value into the panel
            if ev.type == pygame.KEYDOWN and self._shell_key(ev.key):
                return
            if ev.type in (pygame.KEYDOWN, pygame.KEYUP) and not _is_reserved(ev.key):
                kind = "key_down" if ev.type == pygame.KEYDOWN else "key_up"
                self.deliver(InputEvent(kind, key=pygame.key.name(ev.key)))
            return
        if ev.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP, pygame.MOUSEMOTION):
            self._mouse_event(ev, consumed)

    def _mouse_event(self, ev: pygame.event.Event, consumed: bool) -> None:
        in_world = self.world_area().collidepoint(ev.pos) and not consumed
        x, y = self.view.to_world(ev.pos)
        world = (round(x, 2), round(y, 2))     # as recorded, so a replay sees the same numbers
        if ev.type == pygame.MOUSEBUTTONDOWN and ev.button in (1, 3) and in_world:
            self._dragging.add(ev.button)
            self.deliver(InputEvent("mouse_down", pos=world, button=ev.button))
        elif ev.type == pygame.MOUSEBUTTONUP and ev.button in (1, 3) and (
                ev.button in self._dragging or in_world):
            self._dragging.discard(ev.button)
            self.deliver(InputEvent("mouse_up", pos=world, button=ev.button))
        elif ev.type == pygame.MOUSEMOTION and (in_world or self._dragging):
            self.deliver(InputEvent("mouse_move", pos=world))

    @property
    def session_time(self) -> float:
        """Simulated seconds since the scene was opened, counted as the headless runner counts
        them (steps x dt), so a recording replays with --input at the same steps. Equal to
        scene.time until the first R."""
        return self.session_clock if self.scene is not None else 0.0

    def deliver(self, event: InputEvent) -> None:
        """Hand an event to the scene now (before the next step) and record it."""
        if self.scene is None:
            return
        event.t = self.session_time
        self.scene.handle_event(event)
        self.recorded.append(event.to_json())

    def _shell_key(self, key: int) -> bool:
        """The common keys of every scene (SHELL_KEYS); return True if `key` was one of them."""
        actions = {
            "space": self.toggle_pause,
            ".": self.clock.single_step, "[.]": self.clock.single_step,
            "-": self.clock.slower, "[-]": self.clock.slower,
            "=": self.clock.faster, "+": self.clock.faster, "[+]": self.clock.faster,
            "r": self.reset_scene,
            "h": self.toggle_help, "f1": self.toggle_help,
            "f2": lambda: self.set_large_text(not self.large_text),
            "f12": self.request_screenshot,
            "escape": self.escape,
            "tab": self.toggle_panel,
            "page up": lambda: self.switch_scene(-1),
            "page down": lambda: self.switch_scene(+1),
        }
        action = actions.get(pygame.key.name(key))
        if action is None:
            return False
        action()
        return True

    def toggle_help(self) -> None:
        self.show_help = not self.show_help

    def escape(self) -> None:
        """Esc: close the help, else back to the menu."""
        if self.show_help:
            self.show_help = False
        else:
            self.open_menu()

    def toggle_panel(self) -> None:
        self.panel_visible = not self.panel_visible
        self._layout()

    def toggle_pause(self) -> None:
        self.clock.toggle_pause()
        if not self.clock.paused:
            self.nonfinite_banner = ""

    def _menu_event(self, ev: pygame.event.Event) -> None:
        n = len(self.scenes)
        if ev.type == pygame.KEYDOWN:
            if ev.key == pygame.K_ESCAPE:
                self.running = False
            elif pygame.K_1 <= ev.key <= pygame.K_9 or pygame.K_KP1 <= ev.key <= pygame.K_KP9:
                i = ev.key - (pygame.K_1 if ev.key <= pygame.K_9 else pygame.K_KP1)
                if i < n:
                    self.open_scene(self.scenes[i])
            elif ev.key in (pygame.K_DOWN, pygame.K_UP) and n:
                self.menu_selected = (self.menu_selected + (1 if ev.key == pygame.K_DOWN else -1)) % n
            elif ev.key in (pygame.K_RETURN, pygame.K_KP_ENTER) and n:
                self.open_scene(self.scenes[self.menu_selected])
            elif ev.key == pygame.K_PAGEUP:
                self.switch_scene(-1)
            elif ev.key == pygame.K_PAGEDOWN:
                self.switch_scene(+1)
            elif ev.key == pygame.K_F2:
                self.set_large_text(not self.large_text)
            elif ev.key == pygame.K_F12:
                self.request_screenshot()
        elif ev.type == pygame.MOUSEMOTION:
            for entry in self.menu_entries:
                if entry.rect.collidepoint(ev.pos):
                    self.menu_selected = entry.index
        elif ev.type == pygame.MOUSEBUTTONDOWN and ev.button == 1:
            for entry in self.menu_entries:
                if entry.rect.collidepoint(ev.pos):
                    self.open_scene(self.scenes[entry.index])
                    return

    # --- time ------------------------------------------------------------------------------
    def update(self, frame_seconds: float) -> int:
        """Advance the window by one frame of `frame_seconds` wall time; return the number of
        physics steps run."""
        self.wall += frame_seconds
        self.frame_times.append(self.wall)
        while self.frame_times and self.frame_times[0] < self.wall - 1.0:
            self.frame_times.popleft()
        self.messages = [m for m in self.messages if m[0] > self.wall]
        scene = self.scene
        if scene is None:
            return 0
        if self.manager is not None:
            self.manager.update(frame_seconds)
        if self.panel is not None:
            self.panel.refresh()
        self._deliver_replay()
        before = self.clock.dropped_steps
        n = self.clock.steps_for_frame(frame_seconds, scene.dt)
        frame_start = time.perf_counter()
        for i in range(n):
            if i and time.perf_counter() - frame_start > STEP_BUDGET_SECONDS:
                self.clock.dropped_steps += n - i    # the rest would freeze the window
                n = i
                break
            self._deliver_replay()
            t0 = time.perf_counter()
            scene.advance()
            ms = (time.perf_counter() - t0) * 1000.0
            self.session_steps += 1
            self.session_clock += scene.dt
            self.step_times.append((self.wall, ms))
            self.last_step_ms = ms
            if scene.steps % SNAPSHOT_EVERY == 0 and scene.is_finite():
                self._last_good = (scene.snapshot(), scene.time, scene.steps)
        while self.step_times and self.step_times[0][0] < self.wall - 1.0:
            self.step_times.popleft()
        if self.clock.dropped_steps > before:
            self.last_drop = self.wall
        if n and not scene.is_finite():
            self._roll_back()
        return n

    def _roll_back(self) -> None:
        """The state went NaN/inf: back to the last good snapshot, paused, with a banner."""
        scene = self.scene
        bad_t = scene.time
        snap, t, steps = self._last_good if self._last_good else (None, 0.0, 0)
        scene.restore(snap)
        if snap is not None:
            scene.time, scene.steps = t, steps
        else:
            t = scene.time
        self.clock.paused = True
        self.clock.accumulator = 0.0
        self._dragging.clear()
        self.nonfinite_banner = NONFINITE_TEXT.format(bad=bad_t, good=t)
        if not scene.is_finite():      # a snapshot that shares arrays with the state: rebuild
            scene.reset()
            self._after_rebuild()
            self.nonfinite_banner = NONFINITE_TEXT.format(bad=bad_t, good=0.0)

    def _deliver_replay(self) -> None:
        if self.scene is None or type(self.scene) is not self._replay_scene:
            return
        while (self._replay_index < len(self._replay)
               and self._replay[self._replay_index].t <= self.session_time + EVENT_SLACK):
            ev = self._replay[self._replay_index]
            self._replay_index += 1
            if deliver(self.scene, replace(ev, t=self.session_time)):   # the headless rules
                self._after_rebuild()

    # --- what the HUD reads ----------------------------------------------------------------
    @property
    def fps(self) -> float:
        if len(self.frame_times) < 2:
            return 0.0
        span = self.frame_times[-1] - self.frame_times[0]
        return (len(self.frame_times) - 1) / span if span > 0 else 0.0

    @property
    def step_ms(self) -> float:
        """Median wall milliseconds of one scene.advance() over the last second."""
        if not self.step_times:
            return self.last_step_ms
        return statistics.median(ms for _, ms in self.step_times)

    def status_lines(self) -> list:
        """The shell's lines of the HUD box: fps and step cost, time and speed, warnings."""
        L, scene = hud.Line, self.scene
        ms = self.step_ms
        ms_text = "-" if math.isnan(ms) else f"{ms:.2f}"
        lines: list = [f"{self.fps:.0f} fps  |  physics {ms_text} ms/step  |  {hud.dt_text(scene)}"]
        state = f"t = {scene.time:.2f} s  |  speed x{_slow_text(self.clock.slow_motion)}"
        if self.clock.paused:
            state += "  |  PAUSED (space resumes, . steps)"
        slow = self.clock.paused or self.clock.slow_motion != 1.0
        lines.append(L(state, hud.WARN_COLOR if slow else hud.TEXT_COLOR))
        if self.wall - self.last_drop < 1.0:
            lines.append(L("slower than real time: the steps do not fit in a frame (fewer "
                           "iterations, substeps or hertz catch up)", hud.WARN_COLOR))
        return lines

    def notes(self) -> list:
        """Passing messages shown at the end of the HUD box (errors get a banner instead)."""
        return [hud.Line(text, color) for _, text, color in self.messages
                if color != hud.ERROR_COLOR]

    def hud_lines(self) -> list:
        """Everything in the HUD box, as drawn."""
        return hud.scene_lines(self.scene, self.status_lines(), self.notes())

    # --- drawing ---------------------------------------------------------------------------
    def render(self) -> None:
        screen = self.screen
        if self.scene is None:
            self.menu_entries = hud.draw_menu(screen, self.scenes, self.menu_selected,
                                              self.menu_message)
            self._save_pending()
            return
        scene = self.scene
        area = self.world_area()
        screen.fill((10, 11, 14))
        world = pygame.Rect(self.view.world_rect(scene.world_size)).clip(area)
        screen.fill(scene.background, world)
        screen.set_clip(area)
        scene.draw(screen, self.view)
        screen.set_clip(None)
        s = TEXT.scale
        bottom = hud.draw_scene_hud(screen, area, scene, self.status_lines(), self.notes())
        if self.nonfinite_banner:
            hud.banner(screen, self.nonfinite_banner, area, hud.WARN_COLOR,
                       y=area.centery - int(60 * s))
        for _, text, color in reversed(self.messages):
            if color == hud.ERROR_COLOR:
                bottom = hud.banner(screen, text, area, color, size=hud.HUD_SIZE,
                                    bottom=bottom).top
        if self.panel is not None:
            screen.fill((21, 24, 29), self.panel.rect)
            pygame.draw.line(screen, (60, 66, 76), self.panel.rect.topleft,
                             self.panel.rect.bottomleft, 2)
        if self.manager is not None:
            self.manager.draw_ui(screen)
        if self.show_help:       # over the whole window: the room needs the space for big text
            settings = [(prm.name, prm.help) for prm in scene.all_params()]
            settings += [(eff.name, f"effect, {'on' if eff.name in scene.on else 'off'}: {eff.help}")
                         for eff in scene.effects]
            hud.help_overlay(screen, screen.get_rect(), scene.title or scene.name,
                             docstring_help(type(scene)), settings)
        self._save_pending()

    # --- screenshots and recording -----------------------------------------------------------
    def request_screenshot(self) -> Path:
        """F12: save the next rendered frame to screenshots/<scene>-<timestamp>.png."""
        name = self.scene.name if self.scene is not None else "menu"
        stamp = time.strftime("%Y%m%d-%H%M%S")
        path = self.screenshot_dir / f"{name}-{stamp}.png"
        k = 2
        while path.exists():
            path = self.screenshot_dir / f"{name}-{stamp}-{k}.png"
            k += 1
        self._pending_shot = path
        return path

    def _save_pending(self) -> None:
        if self._pending_shot is None:
            return
        path, self._pending_shot = self._pending_shot, None
        try:
            self.save_screenshot(path)
        except (pygame.error, OSError) as e:
            self.flash(f"screenshot failed: {e}", hud.ERROR_COLOR)
            return
        self.flash(f"screenshot saved: {path}", (140, 230, 140))

    def save_screenshot(self, path: str | Path) -> None:
        save_png(self.screen, path)

    def replay_command(self, path: str | Path) -> str:
        """The headless command that replays the recording written to `path`."""
        if self.scene is None:
            return ""
        sets = "".join(f" --set {k}={v}" for k, v in self.opened_with.items())
        return (f"python -m app --headless --scene {self.scene.name}{sets} --input {path} "
                f"--steps {max(self.session_steps, 1)}")

    def write_recording(self, path: str | Path) -> int:
        """Write the events delivered to the scene since it was opened, and the R resets, in the
        --input format (one event per line); return how many. Panel changes are not events: a
        demo that changes parameters replays with the values given by --set."""
        body = ",\n".join(" " + json.dumps(e) for e in self.recorded)
        Path(path).write_text("[\n" + body + ("\n" if body else "") + "]\n")
        return len(self.recorded)


def _is_reserved(key: int) -> bool:
    """Shell keys (and the menu's digits) never reach a scene, not even their key_up."""
    return pygame.key.name(key) in SHELL_KEYS


def _slow_text(factor: float) -> str:
    return "1" if factor == 1.0 else f"1/{int(round(1 / factor))}"


# ----------------------------------------------------------------------------------------------
# the main loop (python -m app without --headless)
# ----------------------------------------------------------------------------------------------
class _quiet_stderr:
    """Silence file descriptor 2 (C libraries' messages) inside a `with` block."""

    def __enter__(self):
        sys.stderr.flush()
        self.saved = os.dup(2)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 2)
        os.close(devnull)

    def __exit__(self, *exc):
        os.dup2(self.saved, 2)
        os.close(self.saved)
        return False


def _open_display(size: tuple[int, int]) -> pygame.Surface:
    """Open the window; raise pygame.error if there is no usable display."""
    if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY")
                                                 or os.environ.get("WAYLAND_DISPLAY")):
        with _quiet_stderr():     # SDL's own probing prints "XDG_RUNTIME_DIR is invalid" lines
            pygame.display.init()
    else:
        pygame.display.init()
    driver = pygame.display.get_driver()
    # SDL quietly falls back to an invisible 'offscreen' window when there is no display; that
    # is no window for a person, unless someone asked for it (tests, SDL_VIDEODRIVER=dummy).
    if driver in ("offscreen", "dummy") and os.environ.get("SDL_VIDEODRIVER", "") != driver:
        raise pygame.error(f"SDL found no display (it fell back to the '{driver}' driver; "
                           "is DISPLAY set?)")
    return pygame.display.set_mode(size, pygame.RESIZABLE)


def run_window(scene_name: str | None, overrides: dict[str, str], record: str | None = None,
               screenshot: str | None = None, seconds: float | None = None,
               large_text: bool = False, events: list | None = None) -> int:
    """Open the window (the menu, or `scene_name` with `overrides`) and run it until the user
    quits, or for `seconds` of wall time. Return the exit code (2 when there is no display)."""
    try:
        screen = _open_display(DEFAULT_SIZE)
    except pygame.error as e:
        print(NO_DISPLAY.format(str(e).strip() or "unknown SDL error"), file=sys.stderr)
        pygame.display.quit()
        return 2
    pygame.font.init()
    pygame.display.set_caption("Physics lab")
    pygame.key.set_repeat()
    from scenes import SCENES, get_scene
    window = Window(screen, SCENES, large_text=large_text, events=events,
                    recording=record is not None)
    scene_cls = get_scene(scene_name) if scene_name else None
    if scene_cls is not None:
        window.open_scene(scene_cls, overrides)
    else:
        window.open_menu()
    if screenshot and seconds is None:
        seconds = 2.0
    fps_clock = pygame.time.Clock()
    start = time.perf_counter()
    try:
        while window.running:
            frame_seconds = min(fps_clock.tick(FPS_CAP) / 1000.0, 0.25)
            for ev in pygame.event.get():
                window.handle_pygame_event(ev)
            window.update(frame_seconds)
            window.render()
            pygame.display.flip()
            if seconds is not None and time.perf_counter() - start >= seconds:
                break
        if screenshot:
            window.render()
            window.save_screenshot(screenshot)
    except KeyboardInterrupt:
        pass
    finally:
        if record:
            n = window.write_recording(record)
            if window.scene is not None:
                changed = (f" (panel changes not in it: {', '.join(window.recorded_changes)})"
                           if window.recorded_changes else "")
                print(f"recorded {n} events of {window.scene.name} over {window.session_steps} "
                      f"steps{changed}; replay: {window.replay_command(record)}")
        pygame.display.quit()      # not pygame.quit(): app.draw.text caches fonts
    return 0
