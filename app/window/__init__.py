"""The interactive window, as a package (see app/window/window.py for the loop and the layout).

    window.py     the pygame loop, the window's messages, event routing to the current view
    views.py      the base of every view and the two simple ones (switched like arcade's
                  show_view): the menu and the help overlay
    scene_view.py the view of a running scene: its SceneRunner, clock, pane and input routing
    camera_host.py  zoom (wheel), pan (middle button), 0 to fit again: what the views share
    panel.py      the parameter panel (pygame-gui) with the scene's "try this" cards
    recorder.py   --record: the events a scene received and the command that replays them

Imports run one way: window -> scene_view -> views (and panel, recorder); a view reaches the
window only through the object passed to it (views.WindowLike says what it may ask for). The
shell keys' table is app/keys.py, below the Scene contract. Importing this package imports no
pygame until `Window` or `run_window` is asked for.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Window", "run_window"]


def __getattr__(name: str) -> Any:      # PEP 562: load the pygame parts on first use
    if name in ("Window", "run_window"):
        from app.window import window
        return getattr(window, name)
    raise AttributeError(f"module 'app.window' has no attribute {name!r}")
