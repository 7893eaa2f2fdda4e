"""The interactive window, as a package (see app/window/window.py for the loop and the layout).

    window.py     the pygame loop, the layout of world, HUD, metrics and panel, event routing
    views.py      what the window shows, one view at a time (switched like arcade's show_view):
                  the menu and the help overlay
    scene_view.py the view of a running scene: its SceneRunner, clock, layout and input routing
    panel.py      the parameter panel (pygame-gui) with the scene's "try this" cards
    recorder.py   --record: the events a scene received and the command that replays them
    keys.py       the ONE table of shell keys (plain data; app.scene reads it)

Importing this package imports no pygame until `Window` or `run_window` is asked for, so that
app.scene can read the key table.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Window", "run_window"]


def __getattr__(name: str) -> Any:      # PEP 562: load the pygame parts on first use
    if name in ("Window", "run_window"):
        from app.window import window
        return getattr(window, name)
    raise AttributeError(f"module 'app.window' has no attribute {name!r}")
