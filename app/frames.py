"""What a picture of a run holds, for the window's compare view and headless screenshots alike:
one scene with its HUD, or a comparison (a header and a pane per variant, app/draw/panes.py),
with the live plot in a strip along the bottom and the arrows over the scenes when they are on.

`compare_header` and `compare_pane_lines` write the HUD text of a comparison; `picture` draws a
whole frame on a new surface (a headless --screenshot saves it).
"""

from __future__ import annotations

import pygame

from app.compare import labels
from app.draw import hud
from app.draw.layout import Pane
from app.draw.panes import PANE_COLORS, PaneGrid, pane_lines
from app.draw.text import TEXT
from app.instruments import Instruments
from app.runner import SceneRunner

PLOT_SHARE = 0.3           # the plot strip's share of the height (window and screenshots)
PLOT_MIN = 150             # and its least height, px at text scale 1


def plot_height(height: int) -> int:
    """The plot strip's height in an area `height` px tall."""
    return int(min(max(PLOT_SHARE * height, PLOT_MIN * TEXT.scale), 0.5 * height))


def compare_header(scenes, t: float, status: list = (), notes: list = ()) -> list:
    """The comparison's header: the scene's title and the settings compared, the shared clock,
    then `status` (pause, slow motion, ...) and `notes` (messages)."""
    compared = sorted({part.split("=")[0] for lab in labels(scenes) for part in lab.split(",")})
    title = scenes[0].title or scenes[0].name
    dts = {s.dt for s in scenes}
    clock = f"t = {t:.2f} s" + (f" | {hud.dt_text(scenes[0])}" if len(dts) == 1 else
                                " | each pane at its own dt, stepped to the same time")
    return [hud.Line(f"{title}: {len(scenes)} panes compare {', '.join(compared)}",
                     hud.ACCENT_COLOR), clock, *status, *notes]


def compare_pane_lines(runners: list[SceneRunner], notes: list[list] | None = None,
                       details: bool = False, more: list = (), held: dict | None = None,
                       extra: list = ()) -> list[list]:
    """Every pane's HUD lines: its tag, what differs, its cost and error, the scene's lines,
    its own notes (`notes[k]`; a held pane's reason from `held`)."""
    scenes = [r.scene for r in runners]
    names = labels(scenes)
    same_dt = len({s.dt for s in scenes}) == 1
    out = []
    for k, (runner, label) in enumerate(zip(runners, names)):
        s = runner.scene
        own = list(notes[k]) if notes else []
        if held and k in held:
            own.insert(0, hud.Line(held[k], hud.WARN_COLOR))
        if runner.error is not None:
            own.insert(0, hud.Line(f"stopped: {runner.error.splitlines()[-1]}", hud.ERROR_COLOR))
        clock = "" if same_dt and not (held and k in held) else \
            f"t = {s.time:.2f} s | {hud.dt_text(s)}"
        out.append(pane_lines(s, "ABCD"[k], label, PANE_COLORS[k], runner.step_ms,
                              own + list(extra), details, more, clock))
    return out


def picture(runners: list[SceneRunner], inst: Instruments | None = None,
            compare: bool = False) -> pygame.Surface:
    """A whole frame as a screenshot shows it: the one scene (its world's size) or every pane
    of a comparison (twice the world's width, 1.5 times its height), the HUD text as the window
    writes it (less the frame rate, which a headless run has none of), the plot strip below if
    metrics are plotted, the arrows if they are on."""
    scene = runners[0].scene
    w, h = scene.world_size
    size = (2 * w, int(1.5 * h)) if compare else (w, h)
    plotting = inst is not None and bool(inst.plot)
    extra_h = plot_height(size[1]) if plotting else 0
    surface = pygame.Surface((size[0], size[1] + extra_h))
    surface.fill((21, 24, 29))
    area = pygame.Rect(0, 0, *size)
    overlay = None
    legend: list = []
    if inst is not None and inst.arrows:
        inst.update_scale()
        overlay = inst.overlay
        legend = inst.legend()
    if compare:
        header = compare_header([r.scene for r in runners], scene.time)
        lines = compare_pane_lines(runners, extra=legend)
        PaneGrid([r.scene for r in runners]).draw(surface, area, header, lines, overlay=overlay)
    else:
        status = [f"t = {scene.time:.2f} s  |  {hud.dt_text(scene)}"]
        lines = hud.scene_lines(scene, status, legend)
        Pane(scene).draw(surface, area, lines,
                         overlay=(lambda s, lay: overlay(s, 0, lay)) if overlay else None)
    if plotting:
        inst.draw_plot(surface, pygame.Rect(0, size[1], size[0], extra_h))
    return surface


__all__ = ["picture", "compare_header", "compare_pane_lines", "plot_height"]
