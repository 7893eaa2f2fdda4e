"""The shell's keys: ONE table (key, action, help) that everything else is produced from.

The window's key handling looks a pressed key up here and calls the view's method named by
`action`; the help overlay lists `KEYS`; `app.scene.SHELL_KEYS` (the keys that never reach a scene,
live or replayed) is the set of their pygame names; and the README's Controls table is
`controls_table()` (a test checks that the README holds exactly it). Print the table with

    python -m app.keys

This module is plain data (no pygame, no imports from the lab): it sits below the Scene contract
(app.scene reads the key names from it) and the window (app/window) reads the table from it.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ShellKey:
    """names: pygame key names that do it; label: how the help and the README write the key;
    action: the method of the window's views that does it; help: what it does, in one line."""

    names: tuple[str, ...]
    label: str
    action: str
    help: str


DIGITS = tuple("123456789") + tuple(f"[{d}]" for d in "123456789")

KEYS: tuple[ShellKey, ...] = (
    ShellKey(DIGITS, "1-9, mouse, arrows + Enter", "pick",
             "in the menu: open a scene (its number, a click, or Up/Down then Enter)"),
    ShellKey(("page up",), "PageUp", "previous_scene", "previous scene"),
    ShellKey(("page down",), "PageDown", "next_scene", "next scene"),
    ShellKey(("space",), "Space", "toggle_pause", "pause / resume"),
    ShellKey((".", "[.]"), "`.`", "single_step", "single step: one fixed step of dt (pauses)"),
    ShellKey(("-", "[-]"), "`-`", "slower",
             "slow motion x1 -> x1/2 -> x1/4 -> x1/8 (less simulated time per frame; dt never "
             "changes)"),
    ShellKey(("=", "+", "[+]"), "`=`", "faster", "back towards x1"),
    ShellKey(("r",), "R", "reset", "reset the scene (rebuild it from its parameters; compare "
             "mode: every pane, from the same state)"),
    ShellKey(("h", "f1"), "H or F1", "toggle_help",
             "help: the scene's description, its controls and settings"),
    ShellKey(("f2",), "F2", "toggle_large_text",
             "large text for the back row (projector mode): everything scales"),
    ShellKey(("f11",), "F11", "toggle_fullscreen",
             "full screen at the projector's size <-> the window (--fullscreen, --size WxH)"),
    ShellKey((), "mouse wheel", "camera_event", "zoom in and out about the pointer (every scene and every "
             "pane; compare mode: every pane alike)"),
    ShellKey((), "middle button drag", "camera_event", "pan the view (every scene and every pane)"),
    ShellKey(("0", "[0]"), "0", "fit_view", "fit the view again: undo zoom and pan"),
    ShellKey(("f3",), "F3", "toggle_overlays", "hide / show the HUD and metrics (a clean picture)"),
    ShellKey(("f4",), "F4", "toggle_details",
             "HUD details: the few lines a class reads <-> every line, the costs and the metrics"),
    ShellKey(("tab",), "Tab", "toggle_panel", "hide / show the parameter panel"),
    ShellKey(("p",), "P", "toggle_plot",
             "live plot: a list of the scene's numbers to plot over time (in compare mode one "
             "line per pane)"),
    ShellKey(("[",), "[", "scrub_back", "timeline: one snapshot (0.5 s) back; the last 30 s "
             "are kept, the bar under the scene jumps with a click; Space goes on from there"),
    ShellKey(("]",), "]", "scrub_forward", "timeline: one snapshot forward (after a blow-up's "
             "rollback: its last second, frame by frame)"),
    ShellKey(("b",), "B", "toggle_watch", "watch blow-ups: a diverging run goes on, drawn "
             "clipped to the window, for up to a second before the rollback (off: at once)"),
    ShellKey(("n",), "N", "replay_blowup", "after a watched blow-up's rollback: its last second "
             "again, at x1/4"),
    ShellKey(("v",), "V", "toggle_arrows", "velocity and force arrows on / off"),
    ShellKey(("e",), "E", "toggle_energy", "energy bars: kinetic, potential, elastic, lost and "
             "the total against its start, with the zero of each (scenes with an energy)"),
    ShellKey(("f9",), "F9", "toggle_clip", "start / stop a clip of the scene area (GIF, or "
             "--video's file; the message gives the full path)"),
    ShellKey(("f12",), "F12", "screenshot", "screenshot to lab-output/screenshots/ (the message "
             "gives the full path)"),
    ShellKey(("escape",), "Esc", "escape", "close the help; else back to the menu; in the menu: "
             "quit"),
)

# every name of every shell key: they never reach a scene, not even their key_up
SHELL_KEY_NAMES = frozenset(name for k in KEYS for name in k.names)


def action_for(name: str) -> str | None:
    """The action of the shell key called `name` (pygame's key name), or None."""
    return next((k.action for k in KEYS if name in k.names), None)


def help_rows() -> list[tuple[str, str]]:
    """(key, what it does) for the help overlay."""
    return [(k.label.replace("`", ""), k.help) for k in KEYS]


def controls_table() -> str:
    """The README's Controls table (Markdown), produced from KEYS."""
    rows = ["| key / mouse | what it does |", "|---|---|"]
    rows += [f"| {k.label} | {k.help} |" for k in KEYS]
    return "\n".join(rows)


if __name__ == "__main__":
    print(controls_table())
