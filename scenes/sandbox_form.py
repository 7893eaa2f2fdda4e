"""The sandbox's panel and files: the selected body's fields, typed in the panel, and the name
that Ctrl+S and Ctrl+O ask there (scenes/sandbox.py is the scene; this is its mixin).

What is typed reaches the scene as an input event, never as a call (app/form.py): "edit"
(field, value) sets a field of the selected body, "save" and "open" (a name; "" cancels) write
or read NAME.toml in the current folder. So `--record` writes them and `--input` replays them
headless like a mouse press. A value is checked as the loader checks a file (a finite number in
the format's range) before pymunk sees it: a refused one changes nothing and `message` says why
in one line, which the panel shows under its title and the HUD below its lines.
"""

from __future__ import annotations

import copy
import math
import os
import re

from app.form import Form, FormField
from app.outputs import OutputError
from app.scenefile.load import SceneFileError, load_spec
from app.scenefile.parts import area_of
from app.scenefile.write import save

DENSITY = 0.01            # kg per px^2 of what is drawn: a ball of radius 20 is 12.6 kg
FILE_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_\-]{0,59}\Z")   # what Ctrl+S saves as NAME.toml
# the fields that are one component of a body's vector: field -> (key, index)
VECTOR_FIELDS = {"x": ("position", 0), "y": ("position", 1), "vx": ("velocity", 0),
                 "vy": ("velocity", 1)}
SHAPE_FIELDS = ("friction", "elasticity")         # every shape of the body gets the value


class SandboxForm:
    """The sandbox's panel form and its save and open prompts (a mixin of SandboxScene: it
    reads `drawing`, `selected`, `playing`, `named` and calls `edit`)."""

    def say(self, text: str, error: bool = False, warn: bool = False) -> None:
        """The one line the HUD and the panel show: what the last action did or refused (or,
        `warn`, what the next Enter would do)."""
        self.message, self.message_error, self.message_warn = text, error, warn

    # ----- saving and opening: the name asked in the panel --------------------------------------
    def ask(self, action: str) -> None:
        """Ctrl+S / Ctrl+O: open the panel's prompt, offering a name (save: the first free
        sandbox-N; open: the file saved or opened last, else the newest sandbox-N there is)."""
        numbers = [int(f[8:-5]) for f in os.listdir(".")
                   if f.startswith("sandbox-") and f.endswith(".toml") and f[8:-5].isdigit()]
        if action == "save":
            n = 1
            while os.path.exists(f"sandbox-{n}.toml"):
                n += 1
            offer = f"sandbox-{n}"
        elif self.last_name and os.path.isfile(self.last_name + ".toml"):
            offer = self.last_name          # the file saved or opened last
        else:
            offer = f"sandbox-{max(numbers)}" if numbers else ""
        self.asking, self.confirm = (action, offer), None
        self.say("")                    # the HUD says what to do while the prompt is open

    def answered(self, action: str, text: str) -> None:
        """The name typed at the prompt ("save"/"open" event); "" cancels."""
        name = text.strip()
        if not name:
            self.asking, self.confirm = None, None
            self.say("not saved: cancelled" if action == "save" else "not opened: cancelled")
            return
        if name.endswith(".toml"):
            name = name[:-5]
        folder = os.path.abspath(".")
        if not FILE_NAME.match(name):
            self.asking = (action, text)
            self.say(f"not {'saved' if action == 'save' else 'opened'}: {text!r} is not a name; "
                     "accepted: letters, digits, _ and - (no spaces, at most 60)", error=True)
            return
        path = name + ".toml"
        if action == "open":
            self.open_file(path)
            return
        there = os.path.lexists(path)
        if there and self.confirm != path:
            self.asking, self.confirm = (action, text), path
            self.say(f"{path} is already in {folder}: Enter again replaces it, Esc cancels",
                     warn=True)
            return
        try:
            save(self.drawing, path)
        except OSError as e:        # (OutputError: one line, what and why, the old file kept)
            self.asking = (action, text)
            self.say(f"not saved: {e}" if isinstance(e, OutputError)
                     else f"not saved: {path}: {e.strerror or e}", error=True)
            return
        self.asking, self.confirm, self.last_name = None, None, name
        self.say(f"saved to {os.path.abspath(path)}"
                 + (" (replaced the file that was there)" if there else ""))

    def open_file(self, path: str) -> None:
        """Open a scene file as the drawing (one undo step); a file the loader refuses changes
        nothing and says why."""
        try:
            spec = load_spec(path)
        except SceneFileError as e:
            self.asking = ("open", path[:-5])
            self.say(f"not opened: {e}", error=True)
            return
        if self.edit(lambda d: (d.clear(), d.update(copy.deepcopy(spec)))):
            self.selected, self.corners, self.asking = None, [], None
            self.last_name = path[:-5]
            self.say(f"opened {os.path.abspath(path)}")

    # ----- the panel's fields of the selected body -----------------------------------------------
    def selected_body(self) -> dict | None:
        return next((b for b in self.drawing["body"] if b["name"] == self.selected), None)

    def panel_form(self) -> Form:
        note, bad = self.message, ("error" if self.message_error else
                                   "warn" if self.message_warn else "ok")
        if self.asking is not None:
            action, text = self.asking
            return Form("Save the drawing" if action == "save" else "Open a scene file",
                        prompt=("Save as NAME.toml" if action == "save" else "Open NAME.toml"),
                        answer=text, action=action, note=note, note_kind=bad)
        body = self.selected_body()
        if self.playing or body is None:
            title = "Playing" if self.playing else "Nothing selected"
            if not note:             # the title is one short line; what to do goes below it
                note, bad = ("Enter goes back to the drawing, where the panel edits a body."
                             if self.playing else "Draw a body, or click one with M, to edit "
                             "its fields here."), "hint"
            return Form(title, note=note, note_kind=bad)
        return Form(f"Selected: {body['name']} ({body['shape'][0]['kind']})",
                    rows=self.fields_of(body), note=note, note_kind=bad)

    def fields_of(self, b: dict) -> tuple[tuple[FormField, ...], ...]:
        """The fields of body `b`, one or two a row, each value as its text box shows it."""
        def f(name: str, label: str, value: float) -> FormField:
            return FormField(name, label, format(value, ".6g"))
        shape = b["shape"][0]
        rows: list[tuple[FormField, ...]] = [(FormField(
            "type", "type", b["type"], choices=("dynamic", "static", "kinematic")),)]
        if b["type"] == "dynamic":
            area = area_of(b["shape"])
            mass = b["mass"] if b["mass"] is not None else b["density"] * area
            rows.append((f("mass", "mass kg", mass),
                         f("density", "density", mass / area)))
        rows.append((f("friction", "friction", shape["friction"]),
                     f("elasticity", "elasticity", shape["elasticity"])))
        if shape["kind"] == "circle":
            rows.append((f("radius", "radius px", shape["radius"]),))
        elif shape["kind"] == "box":
            rows.append((f("width", "width px", shape["size"][0]),
                         f("height", "height px", shape["size"][1])))
        rows.append((f("x", "x px", b["position"][0]),
                     f("y", "y px", b["position"][1])))
        rows.append((f("angle", "angle deg", b["angle"]),))
        if b["type"] != "static":
            rows.append((f("vx", "vx px/s", b["velocity"][0]),
                         f("vy", "vy px/s", b["velocity"][1])))
        return tuple(rows)

    def edit_field(self, field: str, text: str) -> None:
        """An "edit" event: set `field` of the selected body to the number (or type) typed.
        The text must be a finite number, and the drawing with it must pass the loader's
        checks (edit()); otherwise nothing changes and the line says why."""
        b = self.selected_body()
        if self.playing or b is None:
            self.say(f"not changed: {field}: "
                     + ("Enter goes back to the drawing first" if self.playing
                        else "no body is selected (M, then click one)"), error=True)
            return
        fields = {x.name for row in self.fields_of(b) for x in row}
        if field not in fields:
            self.say(f"not changed: a {b['type']} {b['shape'][0]['kind']} has no field "
                     f"{field!r}; accepted: {', '.join(sorted(fields))}", error=True)
            return
        name = b["name"]
        if field == "type":
            if text not in ("dynamic", "static", "kinematic"):
                self.say(f"not changed: type {text!r}; accepted: dynamic, static, kinematic",
                         error=True)
                return

            def change(d: dict) -> None:
                body = next(x for x in d["body"] if x["name"] == name)
                body["type"] = text
                if text == "dynamic":
                    if body["mass"] is None and body["density"] is None:
                        body["density"] = DENSITY
                else:
                    body["mass"] = body["density"] = body["moment"] = None
                if text == "static":
                    body["velocity"], body["angular_velocity"] = [0.0, 0.0], 0.0
            if self.edit(change):
                self.say(f"{name}: type = {text}")
            return
        try:
            value = float(text.strip().replace(",", "."))
        except ValueError:
            value = None
        if value is None or not math.isfinite(value):
            self.say(f"not changed: {field} = {text!r} is not a finite number", error=True)
            return

        def change(d: dict) -> None:
            body = next(x for x in d["body"] if x["name"] == name)
            if field in ("mass", "density"):
                body[field] = value
                body["density" if field == "mass" else "mass"] = None
            elif field in SHAPE_FIELDS:
                for sh in body["shape"]:
                    sh[field] = value
            elif field == "radius":
                body["shape"][0]["radius"] = value
            elif field in ("width", "height"):
                size = list(body["shape"][0]["size"])
                size[field == "height"] = value
                body["shape"][0]["size"] = size
            elif field == "angle":
                body["angle"] = value
            else:
                key, i = VECTOR_FIELDS[field]
                vec = list(body[key])
                vec[i] = value
                body[key] = vec
        if self.edit(change):
            self.say(f"{name}: {field} = {value:g}")
        else:                        # edit() said what the loader refused (which body: the
            why = self.message.replace("not drawn: ", "", 1)          # panel's title says it)
            if why.startswith("body "):
                why = why.split(": ", 1)[-1]
            self.say(f"not changed: {why}", error=True)
