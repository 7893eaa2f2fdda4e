"""A scene's own form in the panel: fields to type into and a prompt, as plain data.

A scene that edits something of its own (the sandbox: the selected body's mass, friction, size,
...; the name to save under) returns a `Form` from `Scene.panel_form()`; the window's panel
(app/window/panel.py) draws it above the parameters and turns what is typed into input events,
never into a call:

    Enter in a field      InputEvent("edit", field=NAME, value=TEXT)    {"type": "edit", ...}
    Enter at the prompt   InputEvent("save", value=TEXT)                {"type": "save", ...}
                          (or "open": the prompt's `action`)
    Esc at the prompt     InputEvent("save", value="")                  (cancels)

so they go through the runner like a mouse press, `--record` writes them and `--input` replays
them headless: a scene built by hand in the panel replays as a test. The scene checks the text
(a number that is finite and in range) before anything reaches pymunk, and says in `note` (one
line) what it refused or did.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class FormField:
    """One field: `name` (what the "edit" event names), the `label` shown (with its unit), the
    current `value` as text, and `choices` (a drop-down) or None (a text box)."""

    name: str
    label: str
    value: str
    choices: tuple[str, ...] | None = None


@dataclass(frozen=True)
class Form:
    """What the panel shows of a scene's own: a `title` ("Selected: ball1"), its fields in
    `rows` (one or two a row), a `prompt` (the question of an open prompt, e.g. "Save as"; ""
    when none is open) with the text it starts with (`answer`) and the event it sends
    (`action`: "save" or "open"), and `note`, one line: what the last edit or save did."""

    title: str = ""
    rows: tuple[tuple[FormField, ...], ...] = ()
    prompt: str = ""
    answer: str = ""
    action: str = "save"
    note: str = ""
    note_kind: str = "ok"          # "ok" (done), "warn" (what the next Enter does), "error"

    @property
    def fields(self) -> tuple[FormField, ...]:
        return tuple(f for row in self.rows for f in row)

    def layout_key(self) -> tuple:
        """What the panel's widgets are built from (a change rebuilds them); the values of
        the fields are not in it: they change in place."""
        return (self.title, tuple(tuple((f.name, f.label, f.choices) for f in row)
                                  for row in self.rows),
                self.prompt, self.answer, self.action, self.note, self.note_kind)
