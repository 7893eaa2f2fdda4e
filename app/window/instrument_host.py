"""The instruments of a running view (one scene, or a comparison): the live plot along the bottom
of the world area, the velocity and force arrows over the scenes, and the `--csv` file
(app/instruments.py does the work; this is what the window's views share of it).

  P   opens the list of the scene's numbers to plot (app/window/plot_picker.py); the plot takes a
      strip along the bottom of the world area and the scene is fitted above it, never under it
  V   arrows on or off (the panel's Arrows button too); the window remembers it for every scene
"""

from __future__ import annotations

import sys

import pygame

from app.draw import hud
from app.frames import plot_height
from app.instruments import Instruments
from app.window.views import WindowLike

PLOT_HINT = "P: pick metrics"


class InstrumentHost:
    """A mixin for the views of a running scene: `self.window`, `world_area()` and `fit()`
    come from the view."""

    window: WindowLike
    inst: Instruments

    def setup_instruments(self, runners: list, variants: list[str] | None = None) -> None:
        """Attach the instruments to these runners (a new scene, a new comparison, a new runner
        after a recording restarted). The first call opens the window's --csv file."""
        w = self.window
        if not hasattr(self, "inst"):
            self.inst = Instruments(list(w.plot_start), arrows=w.arrows)
            w.plot_start = []               # --plot is for the first scene opened
            if w.csv_path:
                w.own_csv(self)             # the file holds the last scene opened
                self.inst.open_csv(w.csv_path, variants is not None,
                                   lambda text: w.flash(text, hud.WARN_COLOR, topic="csv"))
        self.inst.attach(runners, variants)

    def close_instruments(self) -> None:
        if hasattr(self, "inst"):
            from app.outputs import OutputError
            try:
                if self.inst.close_csv():         # the summary says when it replaced a file
                    print(f"csv: {self.window.csv_path} (replaced the file that was there)",
                          flush=True)
            except OutputError as e:      # a full disk: said on screen and on stderr,
                self.window.flash(str(e), hud.ERROR_COLOR, topic="csv")
                print(f"python -m app: error: {e}", file=sys.stderr)
                self.window.output_failed = True     # and the exit code is 2, not 0
            self.inst.detach()

    # --- the plot ----------------------------------------------------------------------------
    def plot_rect(self) -> pygame.Rect | None:
        """The plot's strip along the bottom of the world area, or None (nothing plotted)."""
        if not self.inst.plot:
            return None
        area = self.world_area()
        h = plot_height(area.height)
        return pygame.Rect(area.left, area.bottom - h, area.width, h)

    def scene_area(self) -> pygame.Rect:
        """Where the scene (or the panes) go: the world area above the plot."""
        area = self.world_area()
        plot = self.plot_rect()
        if plot is not None:
            area.height = max(plot.top - area.top, 1)
        return area

    def toggle_plot(self) -> None:
        """P: the list of numbers to plot; with nothing plotted yet, it opens with one line
        already drawn (the scene's error against its reference, else its first number), not
        an empty strip."""
        from app.window.plot_picker import PlotPicker
        if not self.inst.plot:
            choices = self.inst.choices()
            pick = getattr(self.scene, "error_metric", None)
            pick = pick if pick in choices else (choices[0] if choices else None)
            if pick is not None:
                self.inst.toggle_metric(pick)
                self.plot_changed()
        self.window.show_view(PlotPicker(self.window, self))

    def plot_changed(self) -> None:
        """The plot came, went or changed its metrics: the scene gets a new room."""
        self.on_layout()

    def draw_plot(self, screen: pygame.Surface) -> None:
        rect = self.plot_rect()
        if rect is not None:
            self.inst.draw_plot(screen, rect, PLOT_HINT)

    # --- the arrows --------------------------------------------------------------------------
    def toggle_arrows(self) -> None:
        """V (or the panel's Arrows button): velocity and force arrows on or off."""
        on = not self.inst.arrows
        self.window.arrows = on
        self.inst.set_arrows(on)
        self.forget_layout()
        if getattr(self, "panel", None) is not None:
            self.panel.refresh()

    def forget_layout(self) -> None:
        """The HUD's text changed size (the arrows' legend): redo the room."""


__all__ = ["InstrumentHost", "PLOT_HINT"]
