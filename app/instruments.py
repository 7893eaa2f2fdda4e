"""What the shell lays over the scenes, in the window and headless alike: the live plot, the
velocity and force arrows, and the `--csv` file; one `Instruments` per run, with a `Gauge` per
pane (one, or one per variant in compare mode).

  * The plot: the metrics picked (P in the window, `--plot` on the command line), each pane's
    rolling `History`, drawn over the last `window` seconds (app/draw/live_plot.py). The window
    samples once a frame, a headless run once a step.
  * The arrows: off, nothing of them runs (no observer on the runner, no call to
    Scene.arrows(), nothing drawn); on, each pane's `ForceProbe` reads the scene's arrows after
    every step (the net force needs the velocity before it) and one `ArrowScale` serves every
    pane, so arrows compare across panes.
  * The CSV: a row per step headless (the runner's observer), a row per frame in the window.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from app.draw import live_plot
from app.draw.arrows import (ACCEL_FLOOR, VELOCITY_FLOOR, ArrowScale, draw_arrows,
                             legend_lines)
from app.draw.panes import PANE_COLORS
from app.runner import SceneRunner
from app.series import CsvLog, History, plottable
from app.vectors import ForceProbe

WINDOWS = (5.0, 10.0, 30.0, 60.0, 120.0)   # the plot's rolling windows, seconds
DEFAULT_WINDOW = 10.0


@dataclass
class Gauge:
    """One pane's instruments: its runner, its variant (as given; "" alone), its history and
    force probe, and the runner step its last CSV row was written at."""
    runner: SceneRunner
    variant: str = ""
    tag: str = ""
    color: tuple[int, int, int] = PANE_COLORS[0]
    history: History = field(default_factory=History)
    probe: ForceProbe = field(default_factory=ForceProbe)
    csv_step: int = -1


class Instruments:
    def __init__(self, plot: list[str] | tuple = (), window: float = DEFAULT_WINDOW,
                 log: bool = False, arrows: bool = False):
        self.plot = list(plot)
        self.window = window
        self.log = log
        self.arrows = arrows
        self.scale = ArrowScale()
        self.gauges: list[Gauge] = []
        self.csv: CsvLog | None = None
        self.per_step = False           # headless: history and CSV rows after every step

    # --- set-up ------------------------------------------------------------------------------
    def attach(self, runners: list[SceneRunner], variants: list[str] | None = None,
               per_step: bool = False) -> None:
        """Give every pane its gauge (a new scene, a new comparison); hook the observers that
        are on. The CSV (if open) gets the first row: the state before the first step."""
        self.detach()
        self.per_step = per_step
        compare = variants is not None
        self.gauges = [Gauge(r, variants[k] if compare else "", "ABCD"[k] if compare else "",
                             PANE_COLORS[k % len(PANE_COLORS)]) for k, r in enumerate(runners)]
        for g in self.gauges:
            if self.arrows:
                g.runner.observers.append(self._probe_observer(g))
            if per_step:
                g.runner.observers.append(self._step_observer(g))
        self.sample()

    def detach(self) -> None:
        for g in self.gauges:
            g.runner.observers.clear()
        self.gauges = []

    def _probe_observer(self, g: Gauge) -> Callable[[SceneRunner], None]:
        def observe(runner: SceneRunner) -> None:
            g.probe.observe(runner.scene)
        observe.kind = "arrows"         # type: ignore[attr-defined]
        return observe

    def _step_observer(self, g: Gauge) -> Callable[[SceneRunner], None]:
        def observe(runner: SceneRunner) -> None:
            self._sample(g)
        observe.kind = "series"         # type: ignore[attr-defined]
        return observe

    def set_arrows(self, on: bool) -> None:
        """Arrows on or off; off removes their observers (nothing of them runs)."""
        self.arrows = on
        for g in self.gauges:
            g.runner.observers[:] = [o for o in g.runner.observers
                                     if getattr(o, "kind", "") != "arrows"]
            g.probe.forget()
            if on:
                g.runner.observers.insert(0, self._probe_observer(g))

    def open_csv(self, path: str, compare: bool, warn: Callable[[str], None] | None) -> None:
        self.close_csv()
        self.csv = CsvLog(path, compare, warn)

    def close_csv(self) -> bool:
        """Finish the --csv file and rename it into place; True if it replaced a file that
        was there. OutputError (one line) if it could not be written."""
        csv, self.csv = self.csv, None
        if csv is None:
            return False
        csv.close()
        return csv.replaced

    # --- sampling ----------------------------------------------------------------------------
    def sample(self) -> None:
        """Every pane's metrics now (the window calls it once a frame): into the plot's
        history, and a CSV row if the pane stepped since the last one."""
        for g in self.gauges:
            self._sample(g)

    def _sample(self, g: Gauge) -> None:
        scene = g.runner.scene
        if not self.plot and self.csv is None:
            return
        metrics = scene.metrics()
        if self.plot:
            g.history.add(scene.time, metrics)
        if self.csv is not None and g.runner.steps != g.csv_step:
            g.csv_step = g.runner.steps
            self.csv.row(g.runner.steps, scene.time, metrics, g.variant, scene.json_unit)

    # --- the plot ----------------------------------------------------------------------------
    def choices(self) -> list[str]:
        """The metrics a plot can draw (the first pane's numbers, in the scene's order)."""
        if not self.gauges:
            return []
        return list(plottable(self.gauges[0].runner.scene.metrics()))

    def toggle_metric(self, name: str) -> None:
        if name in self.plot:
            self.plot.remove(name)
        else:
            self.plot.append(name)
            for g in self.gauges:       # its history starts now
                g.history.add(g.runner.scene.time, g.runner.scene.metrics())

    def lines(self) -> list[live_plot.Line]:
        """The plot's lines: one per metric (one per metric and pane in compare mode)."""
        out = []
        compare = len(self.gauges) > 1
        for i, name in enumerate(self.plot):
            for g in self.gauges:
                scene = g.runner.scene
                unit = scene.metric_units.get(name)
                ts, vs = g.history.series(name, 0.0)
                if unit is not None:
                    vs = [unit.convert(v) if v == v else v for v in vs]
                label = name + (f" ({unit.symbol})" if unit is not None and unit.symbol else "")
                symbol = unit.symbol if unit is not None else ""
                if compare:         # a pane that went non-finite does not scale the axis
                    out.append(live_plot.Line(f"{g.tag} {label}", g.color, ts, vs, dash=i,
                                              scales=not g.runner.stopped, unit=symbol))
                else:
                    out.append(live_plot.Line(label, live_plot.PALETTE[i % 8], ts, vs,
                                              unit=symbol))
        return out

    def now(self) -> float:
        times = [g.history.now for g in self.gauges if g.history.now is not None]
        return max(times) if times else 0.0

    def draw_plot(self, surface, rect, hint: str = "") -> None:
        live_plot.draw_plot(surface, rect, self.lines(), self.now(), self.window, self.log,
                            hint)

    # --- the arrows --------------------------------------------------------------------------
    def update_scale(self) -> None:
        """One scale for every pane, from what they show now (call once before drawing)."""
        if not self.arrows:
            return
        vel, force, mass = [], [], []
        for g in self.gauges:
            if g.runner.stopped:        # a wreck's speeds would dwarf every other pane's arrows
                continue
            arrows, f = g.probe.current(g.runner.scene)
            if arrows is not None:
                vel.append(arrows.vel)
                if arrows.mass is not None and len(arrows.mass):
                    mass.append(float(np.median(arrows.mass)))
                if f is not None:
                    force.append(f)
        if vel:
            self.scale.update("velocity", np.concatenate(vel), VELOCITY_FLOOR)
        if force:
            self.scale.update("force", np.concatenate(force),
                              ACCEL_FLOOR * (max(mass) if mass else 1.0))

    def overlay(self, surface, k: int, layout) -> None:
        """Pane k's arrows over its scene (nothing while the arrows are off)."""
        if not self.arrows or k >= len(self.gauges):
            return
        g = self.gauges[k]
        if g.runner.stopped:            # a pane that went non-finite: no arrows on its wreck
            return
        arrows, force = g.probe.current(g.runner.scene)
        if arrows is not None and len(arrows.ids):
            draw_arrows(surface, layout.view, arrows, force, self.scale)

    def legend(self) -> list:
        """The HUD's lines for the arrows (none while they are off)."""
        if not self.arrows or not self.gauges:
            return []
        g = self.gauges[0]
        arrows, _ = g.probe.current(g.runner.scene)
        return legend_lines(arrows, self.scale, self.scale.per["force"] is not None)


__all__ = ["Instruments", "Gauge", "WINDOWS", "DEFAULT_WINDOW"]
