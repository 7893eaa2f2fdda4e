"""Sandbox: build a scene with the mouse, play it, and save it as a scene file.

What it shows. The scene-file format (docs/experiments.md) from the other side: every circle,
box or line drawn here is a [[body]] of a file, and Ctrl+S writes that file, which the lab then
runs like any other (`python -m app --scene sandbox-1.toml`). While you draw, nothing moves;
Enter plays the world from what was drawn, Enter again (or R) goes back to the drawing.

Every action is a mouse or key event of the kind `--record` writes, so a scene drawn by hand
replays headless (`--input`) into the same world and the same file.

Controls (keys the lab's shell does not use):
  C circle: drag from the centre out to the radius (a dynamic ball)
  X box: drag from one corner to the other (a dynamic box)
  G polygon: click its corners, right-click (or click the first corner again) to close it; it
    must be convex, or the loader refuses it and says why
  L line: drag from one end to the other (a static line, the ground)
  M move: drag a body to move it; click one to select it; Q and W turn it by 15 degrees
  J pin joint, S spring, O pivot, D slide joint (a rope: any distance up to the one drawn): drag
    from a point on one body to a point on another (or to empty space: a fixed point of the
    world); a pivot joins them at the point you pressed
  Delete or Backspace: delete the selected body (and its joints)
  Enter: play / back to the drawing      Ctrl+Z undo, Ctrl+Y redo
  Ctrl+S: save; the panel asks the name (Enter saves NAME.toml in the current folder, Esc
    cancels; a file that is there is replaced only after a second Enter, and the line says so)
  Ctrl+O: open a scene file; the panel asks its name (the newest sandbox-N.toml is offered;
    Ctrl+Z goes back)
(B and E are the shell's blow-up watch and energy bars, so the box is X and the turns Q and W.)
While playing, the left button drags bodies as in every pymunk scene.

The panel edits the selected body (the one just drawn, or clicked with M): its type, mass or
density, friction, elasticity, size, position, angle and velocity; type a value and press
Enter. Each value is checked as the loader checks a file (finite, in the format's range) before
it reaches pymunk: a refused one changes nothing, and the panel says why in one line. What is
typed there reaches the scene as an "edit" event (and the names asked as "save" and "open"
events), which `--record` writes and `--input` replays like a mouse press.
"""

from __future__ import annotations

import copy
import math
from typing import Any

import pygame
import pymunk

from app.physics.bounds import clamp_point
from app.scene import InputEvent
from app.scenefile.load import check_spec, SceneFileError
from app.scenefile.scene import FileScene
from app.scenefile.write import to_data
from scenes.sandbox_form import DENSITY, SandboxForm

TOOLS = {"c": "circle", "x": "box", "g": "polygon", "l": "line", "m": "move", "j": "pin",
         "s": "spring", "o": "pivot", "d": "slide"}
JOINT_TOOLS = {"pin": "pin", "spring": "damped_spring", "pivot": "pivot", "slide": "slide"}
TURN_KEYS = {"q": -1.0, "w": 1.0}
SPRING_STIFFNESS, SPRING_DAMPING = 50.0, 1.0     # a soft spring: it visibly swings
TURN = 15.0               # degrees Q and W turn the selected body
CTRL = ("left ctrl", "right ctrl")
MIN_SIZE = 4.0            # px: a click without a drag draws nothing smaller than this
PREVIEW = (255, 255, 255)
SELECTED = (255, 120, 200)


def empty_spec(world_size: tuple[int, int]) -> dict[str, Any]:
    """A drawing's data: a floor line, and nothing else (every other key at its default)."""
    w, h = world_size
    data = {"scene": {"title": "My sandbox scene", "about": "Drawn in the sandbox."},
            "body": [{"name": "floor", "type": "static", "shape": [
                {"kind": "segment", "a": [40.0, h - 40.0], "b": [w - 40.0, h - 40.0],
                 "radius": 4.0}]}]}
    return check_spec(data, "", "sandbox")


class SandboxScene(SandboxForm, FileScene):
    """Sandbox: draw circles, boxes, polygons and lines with the mouse, play them, save them as
    a scene file (Ctrl+S) that the lab runs like its own, open the last one saved (Ctrl+O).

    C circle, X box, G polygon (click corners, right-click closes), L line (static), M
    move/select (Q, W turn it); J pin, S spring, O pivot, D slide joints (drag from one body to
    another or to the world); Delete removes the selected body; Enter plays / goes back to the
    drawing; Ctrl+Z / Ctrl+Y undo / redo. The panel edits the selected body (type, mass or
    density, friction, elasticity, size, position, angle, velocity: type, Enter). Ctrl+S asks
    the file's name in the panel and saves NAME.toml in the current folder; Ctrl+O asks the
    name of one to open.
    """

    name = "sandbox"
    title = "Sandbox: draw a scene, play it, save it"
    category = "Scene files"
    path = ""                 # no file behind it (Ctrl+S makes one)
    world_keys = FileScene.world_keys + ("playing",)

    def __init__(self, overrides=None):
        self.drawing = empty_spec(self.world_size)
        self.undo: list[dict] = []
        self.redo: list[dict] = []
        self.tool = "circle"
        self.ctrl = False
        self.press: tuple[float, float] | None = None    # where the drag started
        self.mouse = (0.0, 0.0)
        self.selected: str | None = None
        self.corners: list[tuple[float, float]] = []    # the polygon's corners so far
        self.moving: tuple[float, float] | None = None   # grab offset of the body moved
        self._moving_undo = False
        self.message = ""
        self.message_error = self.message_warn = False
        self.asking: tuple[str, str] | None = None    # an open prompt: ("save"|"open", text)
        self.confirm: str | None = None               # the file a second Enter replaces
        self.last_name = ""                           # saved or opened last (Ctrl+O offers it)
        self.counter = 0
        super().__init__(overrides)

    @property
    def spec(self) -> dict:          # the file's data is what was drawn
        return self.drawing

    @classmethod
    def check_combination(cls, values) -> None:
        """No slider points into the drawing: nothing to check beyond each value's range."""

    def build_space(self, space: pymunk.Space) -> None:
        self.playing = False
        super().build_space(space)

    # ----- stepping: only while playing ---------------------------------------------------------
    def step(self, h: float) -> None:
        if self.playing:
            super().step(h)

    def after_step(self) -> None:
        if self.playing:
            super().after_step()

    # ----- editing ------------------------------------------------------------------------------
    def edit(self, change) -> bool:
        """Apply `change` to a copy of the drawing; keep it only if the loader accepts the
        result (every value checked before it reaches pymunk), then rebuild the world. True if
        it was kept."""
        new = copy.deepcopy(self.drawing)
        change(new)
        try:
            new = check_spec(to_data(new), "", "sandbox")
        except SceneFileError as e:
            self.say(f"not drawn: {e.message}", error=True)
            return False
        self.undo.append(self.drawing)
        self.redo.clear()
        self.drawing = new
        self.reset()
        return True

    def new_name(self, kind: str) -> str:
        taken = {b["name"] for b in self.drawing["body"]}
        while True:
            self.counter += 1
            if f"{kind}{self.counter}" not in taken:
                return f"{kind}{self.counter}"

    def add(self, a: tuple[float, float], b: tuple[float, float]) -> None:
        """A body (or a joint) from the drag a -> b with the tool in hand."""
        (ax, ay), (bx, by) = a, b
        if self.tool in JOINT_TOOLS:
            self.join(a, b)
            return
        if self.tool == "circle":
            r = math.hypot(bx - ax, by - ay)
            if r < MIN_SIZE:
                return
            body = {"name": self.new_name("ball"), "position": [ax, ay], "density": DENSITY,
                    "shape": [{"kind": "circle", "radius": r}]}
        elif self.tool == "box":
            w, h = abs(bx - ax), abs(by - ay)
            if min(w, h) < MIN_SIZE:
                return
            body = {"name": self.new_name("box"), "position": [(ax + bx) / 2, (ay + by) / 2],
                    "density": DENSITY, "shape": [{"kind": "box", "size": [w, h]}]}
        else:
            if math.hypot(bx - ax, by - ay) < MIN_SIZE:
                return
            body = {"name": self.new_name("line"), "type": "static",
                    "shape": [{"kind": "segment", "a": [ax, ay], "b": [bx, by], "radius": 4.0}]}
        self.edit(lambda d: d["body"].append(body))
        self.selected = body["name"]

    def corner(self, p: tuple[float, float]) -> None:
        """One more corner of the polygon; a click on the first corner closes it."""
        if len(self.corners) >= 3 and math.dist(p, self.corners[0]) < MIN_SIZE * 2:
            self.close_polygon()
        elif not self.corners or math.dist(p, self.corners[-1]) >= MIN_SIZE:
            self.corners.append((float(p[0]), float(p[1])))

    def close_polygon(self) -> None:
        """A dynamic polygon from the corners clicked, its origin at their centroid; the
        loader checks it (at least 3 corners, convex, an area) before pymunk sees it."""
        pts, self.corners = self.corners, []
        if len(pts) < 3:
            self.say("not drawn: a polygon needs at least 3 corners", error=True)
            return
        n = len(pts)
        cross = [pts[i][0] * pts[(i + 1) % n][1] - pts[(i + 1) % n][0] * pts[i][1]
                 for i in range(n)]
        area = sum(cross) / 2
        if abs(area) < 1e-6:
            self.say("not drawn: the polygon's corners are on one line (no area)", error=True)
            return
        cx = sum((pts[i][0] + pts[(i + 1) % n][0]) * cross[i] for i in range(n)) / (6 * area)
        cy = sum((pts[i][1] + pts[(i + 1) % n][1]) * cross[i] for i in range(n)) / (6 * area)
        body = {"name": self.new_name("polygon"), "position": [cx, cy], "density": DENSITY,
                "shape": [{"kind": "polygon",
                           "points": [[x - cx, y - cy] for x, y in pts]}]}
        if self.edit(lambda d: d["body"].append(body)):
            self.selected = body["name"]

    def join(self, a: tuple[float, float], b: tuple[float, float]) -> None:
        """A joint from the body under a (or the world) to the body under b (or the world),
        anchored where the drag started and ended (a pivot: at a)."""
        name_a, name_b = self.body_at(a) or "world", self.body_at(b) or "world"
        kind = JOINT_TOOLS[self.tool]
        if kind == "pivot" and name_b == name_a:
            name_b = "world"          # a click on a body: it turns about that point

        def local(name: str, p: tuple[float, float]) -> list[float]:
            if name == "world":
                return [float(p[0]), float(p[1])]
            q = self.named[name].world_to_local(p)
            return [float(q.x), float(q.y)]
        taken, number = {j["name"] for j in self.drawing["joint"]}, 1
        while f"{self.tool}{number}" in taken:     # names stay unique after a deletion
            number += 1
        joint: dict[str, Any] = {"kind": kind, "name": f"{self.tool}{number}", "a": name_a,
                                 "b": name_b}
        if kind == "pivot":
            joint["pivot"] = [float(a[0]), float(a[1])]
            joint["collide"] = False
        else:
            joint["anchor_a"], joint["anchor_b"] = local(name_a, a), local(name_b, b)
        if kind == "damped_spring":
            joint["stiffness"], joint["damping"] = SPRING_STIFFNESS, SPRING_DAMPING
        if kind == "slide":           # a rope: slack up to the length drawn, taut beyond
            joint["min"], joint["max"] = 0.0, round(math.hypot(b[0] - a[0], b[1] - a[1]), 3)
        self.edit(lambda d: d["joint"].append(joint))

    def turn(self, degrees: float) -> None:
        name = self.selected
        if name is None or name not in self.named:
            return

        def change(d: dict) -> None:
            b = next(b for b in d["body"] if b["name"] == name)
            b["angle"] = (b["angle"] + degrees + 180.0) % 360.0 - 180.0
        self.edit(change)

    def body_at(self, pos: tuple[float, float]) -> str | None:
        hit = self.space.point_query_nearest(pos, 5.0, pymunk.ShapeFilter())
        if hit is None or hit.shape is None:
            return None
        return next((n for n, b in self.named.items() if b is hit.shape.body), None)

    def move_to(self, name: str, pos: tuple[float, float]) -> None:
        """Move a drawn body so that its grab point follows the mouse (a static line's ends
        move with it)."""
        ox, oy = self.moving
        body = next(b for b in self.drawing["body"] if b["name"] == name)
        dx, dy = pos[0] - ox - body["position"][0], pos[1] - oy - body["position"][1]

        def change(d: dict) -> None:
            b = next(b for b in d["body"] if b["name"] == name)
            b["position"] = [b["position"][0] + dx, b["position"][1] + dy]
        if self.edit(change):
            if self._moving_undo:
                self.undo.pop()        # one undo step per drag, not one per mouse move
            self._moving_undo = True

    def delete(self) -> None:
        name = self.selected
        if name is None:
            return
        self.edit(lambda d: d.update(body=[b for b in d["body"] if b["name"] != name],
                                     joint=[j for j in d["joint"] if name not in (j["a"],
                                                                                  j["b"])]))
        self.selected = None

    # ----- events -------------------------------------------------------------------------------
    def handle_event(self, event: InputEvent) -> None:
        if event.kind.startswith("mouse"):
            event = InputEvent(event.kind, clamp_point(event.pos, self.world_size),
                               event.button, event.key, event.t)
            self.mouse = event.pos
        if event.kind == "edit":
            self.edit_field(event.field, event.value)
        elif event.kind in ("save", "open"):
            self.answered(event.kind, event.value)
        elif event.kind == "key_up" and event.key in CTRL:
            self.ctrl = False
        elif event.kind == "key_down":
            self.key(event.key)
        elif self.playing:
            super().handle_event(event)         # play: drag bodies as in every pymunk scene
        elif event.kind == "mouse_down" and event.button == 3 and self.tool == "polygon":
            self.close_polygon()
        elif event.kind == "mouse_down" and event.button == 1:
            self.press = event.pos
            if self.tool == "move":
                self.selected = self.body_at(event.pos)
                if self.selected is not None:
                    body = next(b for b in self.drawing["body"] if b["name"] == self.selected)
                    self.moving = (event.pos[0] - body["position"][0],
                                   event.pos[1] - body["position"][1])
                    self._moving_undo = False
        elif event.kind == "mouse_move" and self.moving is not None:
            self.move_to(self.selected, event.pos)
        elif event.kind == "mouse_up" and event.button == 1 and self.press is not None:
            if self.tool == "polygon":
                self.corner(event.pos)
            elif self.tool != "move":
                self.add(self.press, event.pos)
            self.press, self.moving = None, None

    def key(self, key: str) -> None:
        if key in CTRL:
            self.ctrl = True
        elif self.ctrl and key == "s":
            self.ask("save")
        elif self.ctrl and key == "z" and self.undo:
            self.redo.append(self.drawing)
            self.drawing = self.undo.pop()
            self.reset()
        elif self.ctrl and key == "y" and self.redo:
            self.undo.append(self.drawing)
            self.drawing = self.redo.pop()
            self.reset()
        elif key in ("return", "enter", "[enter]"):
            playing = not self.playing
            self.reset()                        # from what was drawn, either way
            self.playing = playing
        elif key in ("delete", "backspace") and not self.playing:
            self.delete()
        elif self.ctrl and key == "o":
            self.ask("open")
        elif key in TURN_KEYS and not self.playing and not self.ctrl:
            self.turn(TURN_KEYS[key] * TURN)
        elif key in TOOLS and not self.ctrl:
            self.tool = TOOLS[key]
            self.press, self.corners = None, []

    # ----- reporting ----------------------------------------------------------------------------
    def metrics(self) -> dict[str, Any]:
        bodies = [b for b in self.drawing["body"]]
        return {"bodies": len(bodies),
                "dynamic_bodies": sum(b["type"] == "dynamic" for b in bodies),
                "joints": len(self.drawing["joint"]),
                "playing": self.playing}

    def hud_details(self) -> list[str]:
        return ["drawing: nothing moves; Enter plays from the drawing, R goes back to it",
                "the panel edits the selected body; Ctrl+S asks the name there",
                "a saved file runs as: python -m app --scene NAME.toml"]

    def hud_lines(self) -> list[str]:
        mode = ("PLAYING (Enter: back to the drawing)" if self.playing else
                f"DRAWING with the {self.tool} tool (Enter: play)")
        lines = [mode, "C circle, X box, G polygon, L line, M move (Q/W turn), J pin, S spring, "
                       "O pivot, D slide; Del delete; Ctrl+Z/Y undo/redo; Ctrl+S save, Ctrl+O open"]
        if self.asking is not None:
            lines.append(f"{'Save as' if self.asking[0] == 'save' else 'Open'}: the name in "
                         f"the panel, Enter {'saves' if self.asking[0] == 'save' else 'opens'}, "
                         "Esc cancels")
        if self.message:
            lines.append(self.message)
        return lines

    def draw(self, surface: pygame.Surface, view) -> None:
        super().draw(surface, view)
        if self.selected in self.named and not self.playing:
            body = self.named[self.selected]
            for shape in body.shapes:
                bb = shape.cache_bb()
                a, b = view.pt((bb.left - 4, bb.top - 4)), view.pt((bb.right + 4, bb.bottom + 4))
                pygame.draw.rect(surface, SELECTED, pygame.Rect(a, (b[0] - a[0], b[1] - a[1])), 1)
        if self.corners and not self.playing:       # the polygon so far, closed to the mouse
            pts = [view.pt(p) for p in self.corners + [self.mouse]]
            pygame.draw.lines(surface, PREVIEW, False, pts, 1)
            for p in pts[:-1]:
                pygame.draw.circle(surface, SELECTED, p, 3)
        if self.press is not None and self.tool not in ("move", "polygon") and not self.playing:
            (ax, ay), (bx, by) = self.press, self.mouse
            if self.tool in JOINT_TOOLS:
                pygame.draw.line(surface, SELECTED, view.pt((ax, ay)), view.pt((bx, by)), 2)
            elif self.tool == "circle":
                pygame.draw.circle(surface, PREVIEW, view.pt((ax, ay)),
                                   max(1.0, view.len(math.hypot(bx - ax, by - ay))), 1)
            elif self.tool == "box":
                a, b = view.pt((min(ax, bx), min(ay, by))), view.pt((max(ax, bx), max(ay, by)))
                pygame.draw.rect(surface, PREVIEW, pygame.Rect(a, (b[0] - a[0], b[1] - a[1])), 1)
            else:
                pygame.draw.line(surface, PREVIEW, view.pt((ax, ay)), view.pt((bx, by)), 2)
