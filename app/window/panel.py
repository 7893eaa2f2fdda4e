"""The parameter panel: built from the scene's declared params and effects, with its "try this"
cards (pygame-gui).

Numbers get a slider and a text box (type a value, press Enter), choices a drop-down, bools and
effects an ON/OFF button; every change goes through the host's apply_setting (Scene.set: the one
validation), so a refused value keeps the old one and the window says why. A "try this" card
applies its settings the same way and shows, below the cards, what to watch for.

While one of the panel's text boxes has the keyboard, no key reaches the shell or the scene
(`is_typing`): typing "-5" must not switch slow motion, "r" must not reset.
"""

from __future__ import annotations

import math
from typing import Any, Protocol

import pygame

from app.draw import hud
from app.draw.text import TEXT
from app.scene import Scene, Try
from app.window import gui_ids
from app.window.panel_form import FormWidgets, _html, select as _select
from app.window.panel_size import BUTTON_PAD, TOP_ROW

gui_ids.install()           # pygame_gui's theming ids, cached (app/window/gui_ids.py)


WATCH_HINT = ("Point at a card to see what it sets; click it: the scene starts afresh from its "
              "defaults plus the card's values, and says what to watch for.")


class PanelHost(Protocol):
    """What the panel asks of the running-scene view."""

    scene: Scene

    @property
    def paused(self) -> bool: ...
    def toggle_pause(self) -> None: ...
    def reset(self) -> None: ...
    def toggle_help(self) -> None: ...
    def apply_setting(self, name: str, value: Any) -> bool: ...
    def apply_try(self, card: Try) -> bool: ...
    def deliver(self, event: Any) -> None: ...
    def toggle_plot(self) -> None: ...
    def toggle_arrows(self) -> None: ...


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

    def __init__(self, host: PanelHost, manager, rect: pygame.Rect, scale: float | None = None):
        import pygame_gui
        from pygame_gui.elements import (UIButton, UIDropDownMenu, UIHorizontalSlider, UILabel,
                                         UIScrollingContainer, UITextBox, UITextEntryLine)
        self.gui = pygame_gui
        self.host = host
        self.manager = manager
        self.rect = rect
        scene = host.scene
        self.scale = s = TEXT.scale if scale is None else scale   # the theme's (panel_size.py)
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
        self._toggle_state: dict[str, bool | None] = {}

        label_font = manager.get_theme().get_font(["label"])

        def label(text: str, width: int = inner_w, obj: str | None = None, x: int = pad,
                  short: str | None = None):
            """A label; `short` replaces the text when it would not fit (large text)."""
            if short is not None and label_font.size(text)[0] > width - 8:
                text = short
            UILabel(pygame.Rect(x, y, width, row), text, manager, container=self.container,
                    object_id=obj)

        # each button as wide as its longest label ("Resume" was cut at large text in a small
        # window), the spare width shared out equally
        button_font = manager.get_theme().get_font(["button"])
        need = [button_font.size(t)[0] + BUTTON_PAD for t in TOP_ROW]   # (Pause <-> Resume)
        spare = inner_w - 2 * gap - sum(need)
        widths = [max(1, n + spare // 3) for n in need]
        xs = [pad, pad + widths[0] + gap, pad + widths[0] + widths[1] + 2 * gap]
        self.pause_button, self.reset_button, self.help_button = (
            UIButton(pygame.Rect(x, y, w, row), text, manager, container=self.container)
            for x, w, text in zip(xs, widths, ("Pause", "Reset", "Help")))
        y += row + gap
        # the instruments: the plot's list (P) and the arrows (V), in every scene
        self.plot_button = UIButton(pygame.Rect(pad, y, inner_w, row), "Plot over time (P)",
                                    manager, container=self.container)
        y += row + gap
        text, look = self._arrows_look()
        self.arrows_button = UIButton(pygame.Rect(pad, y, inner_w, row), text, manager,
                                      container=self.container, object_id=look)
        y += row + 2 * gap
        # the scene's own form (the sandbox's selected body, its save prompt): app/form.py
        self.form = FormWidgets(self, host, manager, self.container, pad, inner_w, row, gap)
        y = self.form.build(y)
        # a comparison: whose settings the panel shows and edits (every pane, or one)
        self.target_menu = None
        targets = host.targets() if hasattr(host, "targets") else None
        self._targets = list(targets or [])
        locked = host.locked_settings() if hasattr(host, "locked_settings") else set()
        if targets:
            label("Settings of", obj="#section")
            y += row
            self.target_menu = UIDropDownMenu(targets, targets[host.target_index()],
                                              pygame.Rect(pad, y, inner_w, row), manager,
                                              container=self.container)
            y += row + 2 * gap
        self.cards: dict[Any, Try] = {}
        self.watch_box = None
        every_card = scene.tries + scene.comparisons
        if every_card:
            for section, cards in (("Try this", scene.tries),
                                   ("Compare side by side", scene.comparisons)):
                if not cards:
                    continue
                label(section, obj="#section", short=section.split()[0])
                y += row
                for card in cards:
                    # no tooltip: it covered the cards below; pointing at a card shows what it
                    # does in the box under the cards instead
                    b = UIButton(pygame.Rect(pad, y, inner_w, row), card.label, manager,
                                 container=self.container, object_id="#card")
                    if _cut(b, card.label):    # 'Explicit vs implicit at 60 Hz' at F2, 1024
                        b.kill()               # px: the same card in the theme's smaller font
                        b = UIButton(pygame.Rect(pad, y, inner_w, row), card.label, manager,
                                     container=self.container, object_id="#card_small")
                    self.cards[b] = card
                    y += row + gap
            self.watch_box = UITextBox("", pygame.Rect(pad, y, inner_w, row),
                                       manager, container=self.container, object_id="#watch")
            # as tall as the text it shows (a box that scrolls hides the end; one as tall as the
            # longest card's left a 200-300 px gap above "Parameters"): what lies below it
            # moves when a card's text is longer or shorter (_fit_watch)
            self._watch_font = manager.get_theme().get_font(self.watch_box.combined_element_ids)
            self._watch_w = inner_w
            height = self._watch_height(WATCH_HINT)
            self.watch_box.set_dimensions((inner_w, height))
            self.watch_box.set_text(_html(WATCH_HINT))
            self._watch_shown = WATCH_HINT
            self._clicked: Try | None = None
            y += height + 2 * gap
        label("Parameters", obj="#section")
        y += row
        for prm in scene.all_params():
            value = scene.p[prm.name]
            tip = prm.help or None
            if prm.name in locked:
                label(f"{prm.name}: differs by pane", short=prm.name)
                y += row + gap
                continue
            if prm.kind is bool:
                label(prm.name, width=inner_w // 2)
                text, look = self._toggle_look(prm.name)
                b = UIButton(pygame.Rect(pad + inner_w // 2, y, inner_w - inner_w // 2, row),
                             text, manager, container=self.container, tool_tip_text=tip,
                             object_id=look)
                self.toggles[prm.name] = b
                self._by_element[b] = ("toggle", prm.name)
                y += row + gap
                continue
            if prm.choices is not None:
                label(prm.name)
                y += row
                # (it opens down, or up where its list would run past the window: _aim_menus)
                d = UIDropDownMenu(list(prm.choices), str(value),
                                   pygame.Rect(pad, y, inner_w, row), manager,
                                   container=self.container)
                self.dropdowns[prm.name] = d
                self._by_element[d] = ("choice", prm.name)
                y += row + gap
                continue
            label(f"{prm.name}   ({hud.fmt_number(prm.lo)} to {hud.fmt_number(prm.hi)})",
                  short=prm.name)
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
            entry.lab_setting = (scene, prm.name)   # (for successor: the scene's, this name)
            if slider is not None:
                ctl = _NumberControl(prm, slider)
                slider.set_current_value(ctl.pos_of(value))
                self.numbers[prm.name] = ctl
                self._by_element[slider] = ("slider", prm.name)
            y += row + gap
        if scene.effects:
            y += gap
            label("Effects (off = not computed)", obj="#section", short="Effects")
            y += row
            for eff in scene.effects:
                if eff.name in locked:
                    label(f"{eff.name}: differs by pane", short=eff.name)
                    y += row + gap
                    continue
                text, look = self._toggle_look(eff.name)
                b = UIButton(pygame.Rect(pad, y, inner_w, row), text, manager,
                             container=self.container, tool_tip_text=eff.help or None,
                             object_id=look)
                self.toggles[eff.name] = b
                self._by_element[b] = ("toggle", eff.name)
                y += row + gap
        self.container.set_scrollable_area_dimensions((rect.width - 20, y + pad))
        self._height = y + pad
        self._row_step = row + gap
        self._wheel_speed()
        self.refresh()

    def _wheel_speed(self) -> None:
        """A notch of the mouse wheel scrolls three rows (pygame-gui's default: ~25 px)."""
        bar = getattr(self.container, "vert_scroll_bar", None)
        if bar is not None:
            bar.scroll_wheel_speed = 3.0 * self._row_step

    def _watch_height(self, text: str) -> int:
        lines = len(hud.wrap(text, self._watch_font, self._watch_w - 16))
        return int(lines * self._watch_font.size("Ay")[1] * 1.25) + 12

    def _fit_watch(self, text: str) -> None:
        """Make the watch box as tall as `text` and move what lies below it by the change."""
        box = self.watch_box
        old = box.relative_rect.height
        new = self._watch_height(text)
        if new == old:
            return
        top = box.relative_rect.top
        # a slider's buttons sit in a container of their own, listed here too: the slider moves
        # it, and moved again its handle stood a box's growth off the track
        moved_by_slider = {id(c.slider.button_container) for c in self.numbers.values()}
        for el in list(self.container.get_container().elements):
            r = el.relative_rect
            if el is not box and r.top > top and id(el) not in moved_by_slider:
                el.set_relative_position((r.left, r.top + new - old))
        box.set_dimensions((self._watch_w, new))
        self._height += new - old
        self.container.set_scrollable_area_dimensions((self.rect.width - 20, self._height))
        self._wheel_speed()

    # --- reading the scene ---------------------------------------------------------------------
    def _current(self, name: str) -> Any:
        scene = self.host.scene
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
        self.form.refresh()
        self._aim_menus()
        for name, d in self.dropdowns.items():      # a card or a refused value changed it
            text = str(self._current(name))
            if d.selected_option[0] != text:
                _select(d, text)
        for name, b in self.toggles.items():
            on = bool(self._current(name))
            if self._toggle_state.get(name) != on:
                text, look = self._toggle_look(name, on)
                b.set_text(text)
                b.change_object_id(look)
        paused = self.host.paused
        want = "Resume" if paused else "Pause"
        if self.pause_button.text != want:
            self.pause_button.set_text(want)
        want, look = self._arrows_look()
        if self.arrows_button.text != want:
            self.arrows_button.set_text(want)
            self.arrows_button.change_object_id(look)

    def _toggle_look(self, name: str, on: bool | None = None) -> tuple[str, str]:
        """A toggle's text and theme id, its value (read if not given) noted as shown."""
        on = bool(self._current(name)) if on is None else on
        self._toggle_state[name] = on
        text = (f"{name}: {'ON' if on else 'OFF'}" if self.host.scene.effect(name)
                else ("ON" if on else "OFF"))
        return text, "#toggle_on" if on else "#toggle_off"

    def _arrows_look(self) -> tuple[str, str]:
        arrows = bool(getattr(getattr(self.host, "inst", None), "arrows", False))
        return f"Arrows (V): {'ON' if arrows else 'OFF'}", "#toggle_on" if arrows else "#toggle_off"

    def _aim_menus(self) -> None:
        """Each closed drop-down opens where its list fits in the window: down, or up where
        there is no room below it and more above. Decided where it is now, as the panel
        scrolls (decided where it was built, the materials' list opened off the window's top
        once scrolled up, or showed only its first item near the bottom)."""
        menus = [*self.dropdowns.values(), *self.form.menus.values(), self.target_menu]
        for d in (m for m in menus if m is not None):
            if d.current_state is not d.menu_states["closed"]:
                continue
            need = (len(d.options_list) + 1) * d.rect.height
            below, above = self.rect.bottom - d.rect.bottom, d.rect.top - self.rect.top
            want = "down" if below >= need or below >= above else "up"
            if d.expand_direction != want:
                d.expand_direction = want
                for state in d.menu_states.values():
                    state.expand_direction = want
                d.rebuild()                 # (its arrow points the new way)

    def is_typing(self) -> bool:
        """True while a text box of the panel has the keyboard."""
        return any(e.is_focused for e in self.entries.values()) or self.form.typing()

    @property
    def stale(self) -> bool:
        """The scene's form changed its shape (another body, a prompt, a new note): the panel
        is built again (SceneView._refresh_panel)."""
        return self.form.stale()

    def took_escape(self, ev: pygame.event.Event) -> bool:
        """Esc while the form has the keyboard (or a prompt is open): cancel; True if it did."""
        return ev.type == pygame.KEYDOWN and ev.key == pygame.K_ESCAPE and self.form.escape()

    def refreshed(self) -> "ParamPanel":
        """This panel showing the scene's values, or, if the scene's form changed its shape,
        a new one built where it is (scrolled back to the top; an open prompt gets the
        keyboard)."""
        if not self.stale:
            self.refresh()
            return self
        self.container.kill()
        self.manager.set_focus_set(None)
        panel = ParamPanel(self.host, self.manager, self.rect, self.scale)
        panel.form.focus_prompt()
        return panel

    def show_watch(self, card: Try | None, clicked: bool = True) -> None:
        """Below the cards: what a card sets and what to watch for (the card clicked last, or
        the one the pointer is on; None: back to the card clicked last, or the hint)."""
        if self.watch_box is None:
            return
        if clicked:
            self._clicked = card
        shown = card or self._clicked
        text = _watch_text(shown) if shown is not None else WATCH_HINT
        if text != self._watch_shown:
            self._watch_shown = text
            self._fit_watch(text)
            self.watch_box.set_text(_html(text))

    def release_keyboard(self) -> None:
        """Take the keyboard from the text box through the manager: unfocusing the element alone
        leaves the manager believing it is still focused, and then a second click on the same
        box does not focus it (the keys went to the shell)."""
        self.manager.set_focus_set(None)
        for entry in list(self.entries.values()) + self.form.entries():   # one focused without
            if entry.is_focused:                                          # the manager (a test)
                entry.unfocus()

    # --- pygame-gui events -------------------------------------------------------------------
    def handle(self, ev: pygame.event.Event) -> bool:
        """React to a pygame-gui event of this panel; return True if it was one."""
        gui = self.gui
        element = getattr(ev, "ui_element", None)
        if ev.type == gui.UI_BUTTON_PRESSED:
            if element is self.pause_button:
                self.host.toggle_pause()
                return True
            if element is self.reset_button:
                self.host.reset()
                return True
            if element is self.help_button:
                self.host.toggle_help()
                return True
            if element is self.plot_button:
                self.host.toggle_plot()
                return True
            if element is self.arrows_button:
                self.host.toggle_arrows()
                self.refresh()
                return True
        if ev.type == gui.UI_DROP_DOWN_MENU_CHANGED and element is self.target_menu:
            if ev.text in self._targets:
                self.host.set_target(self._targets.index(ev.text))
            return True
        if ev.type == gui.UI_BUTTON_PRESSED and element in self.cards:
            card = self.cards[element]
            if self.host.apply_try(card):
                self.show_watch(card)
            self.refresh()
            return True
        if ev.type == gui.UI_BUTTON_ON_HOVERED and element in self.cards:
            self.show_watch(self.cards[element], clicked=False)
            return True
        if ev.type == gui.UI_BUTTON_ON_UNHOVERED and element in self.cards:
            self.show_watch(None, clicked=False)
            return True
        if self.form.handle(ev, element):
            return True
        what = self._by_element.get(element)
        if what is None and ev.type == gui.UI_TEXT_ENTRY_FINISHED:
            what = self.successor(element)
        if what is None:
            return False
        kind, name = what
        if kind == "toggle" and ev.type == gui.UI_BUTTON_PRESSED:
            self.host.apply_setting(name, not bool(self._current(name)))
        elif kind == "choice" and ev.type == gui.UI_DROP_DOWN_MENU_CHANGED:
            self.host.apply_setting(name, ev.text)
        elif kind == "entry" and ev.type == gui.UI_TEXT_ENTRY_FINISHED:
            self.host.apply_setting(name, ev.text)
            self.release_keyboard()
        elif kind == "slider" and ev.type == gui.UI_HORIZONTAL_SLIDER_MOVED:
            value = self.numbers[name].value_at(ev.value)
            if value != self._current(name):
                self.host.apply_setting(name, value)
        else:
            return False
        self.refresh()
        return True

    def successor(self, element) -> tuple[str, str] | None:
        """("entry", name) for a number box of a panel built before this one for the same scene
        (the window was resized between Enter and the event pygame-gui queued for the box: the
        panel was laid out again, and what was typed would have been lost in silence; the form's
        boxes: panel_form.FormWidgets.successor); else None."""
        scene, name = getattr(element, "lab_setting", (None, None))
        if scene is not self.host.scene or name not in self.entries:
            return None
        return "entry", name


def _cut(button, text: str) -> bool:
    """Would the button's font cut `text` (its padding and border kept)?"""
    font = button.ui_manager.get_theme().get_font(button.combined_element_ids)
    return font.size(text)[0] + 20 > button.relative_rect.width


def _watch_text(card: Try) -> str:
    """The watch box's text for a card: what it sets, then what to watch for."""
    if card.compare:
        return (f"{card.label}: side by side, {card.changes()}, the rest at the defaults. "
                f"Watch: {card.watch}")
    return f"{card.label}: sets {card.changes()}, the rest at the defaults. Watch: {card.watch}"
