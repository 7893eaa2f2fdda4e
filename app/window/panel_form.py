"""The scene's own form in the panel (app/form.py): a title, text boxes (one or two a row) or a
drop-down per field, a prompt with its text box, and the one-line note under them.

Nothing typed here calls the scene: Enter in a field sends the event InputEvent("edit", field,
value), Enter at the prompt InputEvent(form.action, value=name), Esc at it the same with "" (a
cancel), through the host's `deliver`, the path of a mouse press: the runner hands it to the
scene and `--record` writes it, so `--input` replays it headless.

The widgets are built from `Form.layout_key()`; when the scene's form changes its shape (another
body selected, the prompt opened, a new note) `stale()` is True and the view builds the panel
again; a field's value alone changes in place (unless its box has the keyboard).
"""

from __future__ import annotations

from typing import Any

import pygame

from app.draw import hud
from app.scene import InputEvent

NOTES = {"ok": "#form_note", "warn": "#watch", "error": "#form_error",   # assets/theme.json
         "hint": "#form_hint"}
HINT = "Type a value and press Enter; Esc puts the old one back."
NOTE_LINES = 4          # room kept under the title for the note, so the boxes stay put when a
                        # refusal appears (a second click lands on the same box; 4 lines: the
                        # panel is 320 px at F2 in a 1024 px window, panel_size.py)


class FormWidgets:
    """The form's part of a ParamPanel (`panel`), in its scrolling `container`."""

    def __init__(self, panel, host, manager, container, pad: int, width: int, row: int,
                 gap: int):
        self.panel, self.host, self.manager, self.container = panel, host, manager, container
        self.pad, self.width, self.row, self.gap = pad, width, row, gap
        self.form = None
        self.key: tuple | None = None
        self.boxes: dict[str, Any] = {}        # field -> UITextEntryLine
        self.menus: dict[str, Any] = {}        # field -> UIDropDownMenu
        self.prompt = None                     # the prompt's UITextEntryLine

    def _scene_form(self):
        if getattr(self.host, "targets", None) is not None and self.host.targets():
            return None                        # a comparison: the panes' scenes, no form
        try:
            return self.host.scene.panel_form()
        except Exception:                      # a broken scene must not take the panel down
            return None

    # --- building ------------------------------------------------------------------------------
    def build(self, y: int) -> int:
        """Lay the form out from `y` down; return the y below it (unchanged without a form)."""
        from pygame_gui.elements import UIDropDownMenu, UILabel, UITextBox, UITextEntryLine
        form = self.form = self._scene_form()
        if form is None:
            return y
        self.key = form.layout_key()
        pad, w, row, gap, c, m = self.pad, self.width, self.row, self.gap, self.container, \
            self.manager
        font = m.get_theme().get_font(["label"])

        def label(text: str, x: int, width: int, obj: str | None = None) -> None:
            UILabel(pygame.Rect(x, y, width, row), _fit(text, font, width - 8), m,
                    container=c, object_id=obj)

        label(form.title, pad, w, "#section")
        y += row
        note, kind = form.note, form.note_kind
        if not note and form.rows:
            note, kind = HINT, "hint"
        if note:                        # first, under the title: always in sight (F2, 768 px)
            style = NOTES.get(kind, NOTES["ok"])
            box_font = m.get_theme().get_font([style])
            lines = len(hud.wrap(note, box_font, w - 16))
            if form.rows:
                lines = max(lines, NOTE_LINES)
            height = int(lines * box_font.size("Ay")[1] * 1.25) + 12
            UITextBox(_html(note), pygame.Rect(pad, y, w, height), m, container=c,
                      object_id=style)
            y += height + gap
        # two fields a row where both labels and a number such as -1234.56 fit, else one
        box_min = font.size("-1234.567")[0] + 16
        single = max((font.size(f.label)[0] + 10 for f in form.fields), default=0)
        for fields in form.rows:
            cell = (w - gap * (len(fields) - 1)) // len(fields)
            if any(font.size(f.label)[0] + 10 + box_min > cell for f in fields):
                fields_in_rows = [(f,) for f in fields]
            else:
                fields_in_rows = [fields]
            for line in fields_in_rows:
                cell = (w - gap * (len(line) - 1)) // len(line)
                for i, f in enumerate(line):
                    x = pad + i * (cell + gap)
                    # a lone field's label as wide as the widest (the boxes line up)
                    need = min(single if len(line) == 1 else font.size(f.label)[0] + 10,
                               cell // 2)
                    label(f.label, x, need)
                    if f.choices is not None:
                        self.menus[f.name] = UIDropDownMenu(
                            list(f.choices), f.value, pygame.Rect(x + need, y, cell - need, row),
                            m, container=c)
                        continue
                    box = UITextEntryLine(pygame.Rect(x + need, y, cell - need, row), m,
                                          container=c)
                    box.set_text(f.value)
                    box.lab_form = (self.key, f.name)
                    self.boxes[f.name] = box
                y += row + gap
        if form.prompt:
            label(form.prompt, pad, w)
            y += row
            self.prompt = UITextEntryLine(pygame.Rect(pad, y, w, row), m, container=c)
            self.prompt.set_text(form.answer)
            self.prompt.lab_form = (self.key, None)
            y += row + gap
            label("Enter: " + ("save" if form.action == "save" else "open") + "   Esc: cancel",
                  pad, w)
            y += row
        return y + gap

    def focus_prompt(self) -> None:
        """Give the prompt's text box the keyboard (the name can be typed at once)."""
        if self.prompt is not None:
            self.manager.set_focus_set(self.prompt)
            self.prompt.focus()
            end = len(self.prompt.get_text())
            self.prompt.select_range = [0, end]     # typing replaces the name offered
            self.prompt.edit_position = end

    # --- reading the scene -----------------------------------------------------------------------
    def stale(self) -> bool:
        form = self._scene_form()
        return (None if form is None else form.layout_key()) != self.key

    def refresh(self) -> None:
        """The fields' values as the scene has them now (boxes being typed in are left)."""
        form = self._scene_form()
        if form is None or form.layout_key() != self.key:
            return
        for f in form.fields:
            box = self.boxes.get(f.name)
            if box is not None and not box.is_focused and box.get_text() != f.value:
                box.set_text(f.value)
            menu = self.menus.get(f.name)
            if menu is not None and menu.selected_option[0] != f.value:
                select(menu, f.value)

    def entries(self) -> list:
        return list(self.boxes.values()) + ([self.prompt] if self.prompt is not None else [])

    def typing(self) -> bool:
        return any(e.is_focused for e in self.entries())

    # --- what is typed: events ------------------------------------------------------------------
    def handle(self, ev: pygame.event.Event, element) -> bool:
        gui = self.panel.gui
        if element is None:
            return False
        if ev.type == gui.UI_TEXT_ENTRY_FINISHED and element not in self.entries():
            element = self.successor(element)
        if ev.type == gui.UI_TEXT_ENTRY_FINISHED and element is self.prompt:
            self.panel.release_keyboard()
            self.host.deliver(InputEvent(self.form.action, value=ev.text))
            return True
        for name, box in self.boxes.items():
            if element is box and ev.type == gui.UI_TEXT_ENTRY_FINISHED:
                self.panel.release_keyboard()
                self.host.deliver(InputEvent("edit", field=name, value=ev.text))
                self.refresh()
                return True
        for name, menu in self.menus.items():
            if element is menu and ev.type == gui.UI_DROP_DOWN_MENU_CHANGED:
                self.host.deliver(InputEvent("edit", field=name, value=ev.text))
                return True
        return False

    def successor(self, element):
        """The box of this panel that took over from `element`, a box of a panel built before
        it from the same form (the window was resized between Enter and the event pygame-gui
        queued for it: the panel was laid out again, and what was typed would have been lost in
        silence); else `element`."""
        key, name = getattr(element, "lab_form", (None, None))
        if key is None or key != self.key:
            return element
        return self.prompt if name is None else self.boxes.get(name, element)

    def escape(self) -> bool:
        """Esc: an open prompt is cancelled (an event, as Enter is); a field being typed in
        gets its value back. True if Esc was the form's."""
        if self.form is not None and self.form.prompt:
            self.panel.release_keyboard()
            self.host.deliver(InputEvent(self.form.action, value=""))
            return True
        if any(b.is_focused for b in self.boxes.values()):
            self.panel.release_keyboard()
            self.refresh()                     # the boxes show the scene's values again
            return True
        return False


def select(dropdown, text: str) -> None:
    """Show `text` as a drop-down's choice (pygame-gui has no setter: its menu and its closed
    state each keep the selection; the closed state's button shows it)."""
    option = (text, text)
    dropdown.selected_option = option
    closed = dropdown.menu_states["closed"]
    closed.selected_option = dropdown.menu_states["expanded"].selected_option = option
    if dropdown.current_state is closed and closed.selected_option_button is not None:
        closed.selected_option_button.set_text(text)


def _fit(text: str, font, width: int) -> str:
    """`text`, cut with an ellipsis to what `font` draws in `width` px."""
    if font.size(text)[0] <= width:
        return text
    while text and font.size(text + "...")[0] > width:
        text = text[:-1]
    return text + "..."


def _html(text: str) -> str:
    """Text for a pygame-gui text box (which reads a little HTML)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
