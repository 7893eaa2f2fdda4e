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
from app.draw.panes import PANE_COLORS, PaneGrid, color_key_line, pane_lines
from app.draw.text import TEXT
from app.instruments import Instruments
from app.runner import SceneRunner, advice

PLOT_SHARE = 0.3           # the plot strip's share of the height (window and screenshots)
PLOT_MIN = 150             # and its least height, px at text scale 1


def plot_height(height: int, scale: float | None = None) -> int:
    """The plot strip's height in an area `height` px tall (text at `scale`, default the
    current one)."""
    k = TEXT.scale if scale is None else scale
    return int(min(max(PLOT_SHARE * height, PLOT_MIN * k), 0.5 * height))


def base_size(scene, clean: bool, compare: bool) -> tuple[float, float]:
    """A picture's shape at text scale 1: the world's size (twice its width and 1.5 times its
    height for a comparison), or with `clean` alone the scene's content's."""
    w, h = scene.world_size
    if compare:
        return 2.0 * w, 1.5 * h
    if clean:
        _, _, cw, ch = scene.content_bounds()
        return float(cw), float(ch)
    return float(w), float(h)


def picture_size(scene, width: int | None, clean: bool, compare: bool,
                 plotting: bool) -> tuple[int, int]:
    """The size of picture(): `width` px wide (default the base size's width) in the base
    shape, plus the plot strip below when metrics are plotted. With a width or `clean`, even
    numbers (a clip's H.264 frames need them)."""
    from app.clips import even
    bw, bh = base_size(scene, clean, compare)
    if width is None and not clean:
        w, h = int(bw), int(bh)
    else:
        width = width or int(scene.world_size[0])
        w, h = even(width), even(width * bh / bw)
    if plotting:
        extra = plot_height(h, w / bw)
        h += extra if width is None and not clean else even(extra)
    return w, h


def compare_header(scenes, t: float, status: list = (), notes: list = (),
                   zoom: str = "") -> list:
    """The comparison's header: one line of the scene's title, the settings compared, the shared
    clock and the `zoom` (if any), which breaks at its " | " where the width is short (as two
    lines, title and clock, the header took a row more than it needs: four panes were that much
    shorter); then the colour key, `status` (pause, slow motion, ...) and `notes` (messages)."""
    compared = sorted({part.split("=")[0] for lab in labels(scenes) for part in lab.split(", ")})
    title = scenes[0].title or scenes[0].name
    dts = {s.dt for s in scenes}
    clock = f"t = {t:.2f} s" + (f" | {hud.dt_text(scenes[0])}" if len(dts) == 1 else
                                " | each pane at its own dt, stepped to the same time")
    return [hud.Line(f"{title}: {len(scenes)} panes compare {', '.join(compared)} | {clock}"
                     + (f" | {zoom}" if zoom else ""), hud.ACCENT_COLOR),
            *color_key_line(scenes[0]), *status, *notes]


def compare_pane_lines(runners: list[SceneRunner], notes: list[list] | None = None,
                       details: bool = False, more: list = (), held: dict | None = None,
                       extra: list = (), brief: bool = False,
                       headlines: dict | None = None) -> list[list]:
    """Every pane's HUD lines: its tag, what differs, its cost and error, the scene's lines,
    its own notes (`notes[k]`; a held pane's reason from `held`: on the first page its one-line
    `headlines[k]` if given, the whole paragraph on the second, F4)."""
    scenes = [r.scene for r in runners]
    names = labels(scenes)
    same_dt = len({s.dt for s in scenes}) == 1
    out = []
    for k, (runner, label) in enumerate(zip(runners, names)):
        s = runner.scene
        own = list(notes[k]) if notes else []
        if held and k in held:
            short = (headlines or {}).get(k) if not details else None
            own.insert(0, hud.Line(short or held[k], hud.WARN_COLOR))
        if runner.error is not None:
            own.insert(0, hud.Line(f"stopped: {runner.error.splitlines()[-1]}", hud.ERROR_COLOR))
        elif not runner.finite:
            own.insert(0, hud.Line(f"went non-finite (NaN/inf, or past the scene's blow-up "
                                   f"bounds) at t = {s.time:.3f} s and stopped there; the "
                                   f"others went on. {advice(s)}", hud.ERROR_COLOR))
        clock = "" if same_dt and not (held and k in held) else \
            f"t = {s.time:.2f} s | {hud.dt_text(s)}"
        # a held pane's first page: its one headline says it all (the scene's own headline,
        # of the state it was rolled back to, made it a 10-line paragraph at F2)
        short_page = brief or (bool(held) and k in held and not details)
        out.append(pane_lines(s, "ABCD"[k], label, PANE_COLORS[k], runner.step_ms,
                              own + list(extra), details, more, clock, short_page))
    return out


def picture(runners: list[SceneRunner], inst: Instruments | None = None,
            compare: bool = False, width: int | None = None,
            clean: bool = False) -> pygame.Surface:
    """A whole frame as a screenshot or a clip shows it (its size: picture_size): the one
    scene, or every pane of a comparison, with the HUD text as the window writes it (less the
    frame rate, which a headless run has none of; none with `clean`), the plot strip below if
    metrics are plotted, the arrows if they are on. Text is scaled with the width."""
    scene = runners[0].scene
    plotting = inst is not None and bool(inst.plot)
    w, h = picture_size(scene, width, clean, compare, plotting)
    bw, _ = base_size(scene, clean, compare)
    saved, TEXT.scale = TEXT.scale, w / bw
    try:
        surface = pygame.Surface((w, h))
        surface.fill((21, 24, 29))
        plot_h = h - picture_size(scene, width, clean, compare, False)[1] if plotting else 0
        area = pygame.Rect(0, 0, w, h - plot_h)
        overlay, legend = None, []
        if inst is not None and inst.arrows:
            inst.update_scale()
            overlay = inst.overlay
            legend = inst.legend()
        if compare:
            t = max(r.scene.time for r in runners)      # the clock (a pane may have stopped)
            header = None if clean else compare_header([r.scene for r in runners], t, (),
                                                       legend)
            lines = [None] * len(runners) if clean else compare_pane_lines(runners)
            brief = None if clean else compare_pane_lines(runners, brief=True)
            PaneGrid([r.scene for r in runners]).draw(surface, area, header, lines,
                                                      overlay=overlay, brief=brief)
        else:
            lines = None if clean else hud.scene_lines(
                scene, [f"t = {scene.time:.2f} s  |  {hud.dt_text(scene)}"], legend)
            Pane(scene).draw(surface, area, lines,
                             overlay=(lambda s, lay: overlay(s, 0, lay)) if overlay else None)
        if plotting:
            inst.draw_plot(surface, pygame.Rect(0, area.bottom, w, plot_h))
    finally:
        TEXT.scale = saved
    return surface


__all__ = ["picture", "picture_size", "base_size", "compare_header", "compare_pane_lines",
           "plot_height"]
