"""--record: the mouse and key events a scene received, and the command that replays them.

Events are written in the `--input` format with positions in world coordinates and `t` in the
runner's session time (simulated seconds since the scene was opened, R included), so
`python -m app --headless --scene NAME --input FILE --steps N` replays the demo step for step.

Panel changes are not events. While recording, a change made before the first recorded press
(mouse button or key; the pointer merely passing over the world changes nothing in a scene, and
it always does on the way to the panel) restarts the recording: the scene is rebuilt with the new
settings and the replay command gives them as `--set` (the replay starts from that fresh scene). A
change made after the first press cannot be replayed: the window says so at once, and the command
printed on exit names it.
The file holds the last scene opened; it is written on every way out of the window.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from app.scene import InputEvent, Scene


@dataclass
class Session:
    """What was recorded of one scene, from opening it (or the last restart) on."""

    scene: str
    settings: dict[str, str] = field(default_factory=dict)   # --set values of the replay
    events: list[dict] = field(default_factory=list)           # --input format
    steps: int = 0
    not_replayed: list[str] = field(default_factory=list)     # panel changes after an event
    compare: list[str] = field(default_factory=list)          # --compare variants, if any

    def command(self, path: str | Path) -> str:
        sets = "".join(f" --set {k}={v}" for k, v in self.settings.items())
        sets += "".join(f" --compare {' '.join(self.compare)}" if self.compare else "")
        return (f"python -m app --headless --scene {self.scene}{sets} --input {path} "
                f"--steps {max(self.steps, 1)}")


class Recorder:
    """Collects the events of the scene that is open (the window always does, so tests and
    --record read the same thing); `path` is where --record writes them (None: not recording)."""

    def __init__(self, path: str | Path | None = None):
        self.path = Path(path) if path is not None else None
        self.session: Session | None = None

    @property
    def active(self) -> bool:
        return self.path is not None

    def start(self, scene: str, settings: dict[str, Any], compare: list[str] | None = None) -> None:
        """A new session of `scene` with these --set values (and --compare variants)."""
        self.session = Session(scene, {k: _text(v) for k, v in settings.items()},
                               compare=list(compare or []))

    def add(self, event: InputEvent) -> None:
        if self.session is not None:
            self.session.events.append(event.to_json())

    def steps_run(self, steps: int) -> None:
        if self.session is not None:
            self.session.steps = steps

    def panel_change(self, name: str, value: Any) -> str:
        """Note a panel change; return what the window should do: "restart" (before the first
        press: rebuild, record it as --set) or "note" (after it: not replayable)."""
        s = self.session
        if s is None or not self.active:
            return ""
        if all(e["type"] == "mouse_move" for e in s.events):   # only hovering so far
            return "restart"      # the caller rebuilds the scene and start()s a new session
        s.not_replayed.append(f"{name}={_text(value)}")
        return "note"

    def write(self) -> str | None:
        """Write the last session's events to `path`; return the line to print (None if not
        recording)."""
        if self.path is None:
            return None
        s = self.session
        events = s.events if s is not None else []
        body = ",\n".join(" " + json.dumps(e) for e in events)
        from app.outputs import write_text          # whole or not at all: OutputError
        replaced = write_text(self.path, "[\n" + body + ("\n" if body else "") + "]\n",
                              what="--record")
        if s is None:
            return f"recorded nothing (no scene was opened) to {self.path}"
        line = (f"recorded {len(events)} events of {s.scene} over {s.steps} steps"
                f"{' (replaced the file that was there)' if replaced else ''}; replay: "
                f"{s.command(self.path)}")
        if s.not_replayed:
            line += (f"\n  (panel changes made after the first press are not in it: "
                     f"{', '.join(s.not_replayed)})")
        return line


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return "on" if value else "off"
    return str(value)


def changed_settings(scene: Scene) -> dict[str, Any]:
    """The scene's settings that differ from their defaults (the --set of a replay)."""
    defaults, on = type(scene).resolve({})
    now = scene.settings()
    base = {**defaults, **{e.name: e.name in on for e in scene.effects}}
    return {k: v for k, v in now.items() if base.get(k) != v}
