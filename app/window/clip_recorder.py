"""F9 in the window: a clip of the scene area, as the room sees it (GIF or MP4, app/clips.py).

F9 starts a clip of the world area (the window left of the panel: the scene with its HUD and
metrics, as shown; F3 first for a clean picture) and F9 again stops it. The clip goes to
clips/<scene>-<date>-<time>.gif, or to the file `--video OUT.gif|OUT.mp4` names (then OUT-2,
OUT-3, ... for the next ones); the red REC box at the top right (below the HUD where it would
cover it; drawn after the frame is taken, so it is not in the clip) gives its full path, and so
does the message when it is saved (in the window and on the terminal).

Frames follow the simulation, not the wall clock, as headless clips do: one frame per 1/fps of
simulated time divided by the slow-motion factor, counted from the steps the runner ran. So a
pause adds nothing to the clip, slow motion plays slow, and a frame the window could not draw in
time (a slow machine) is the previous picture repeated rather than a jump in time. Frames are
`width` px wide at most (default 1280; a smaller scene area is not scaled up); if the area
changes shape while recording (F2, Tab, a resize), it is scaled to fit the clip's frame,
centred. A GIF is written when the clip stops, in a background thread (the window keeps
running); a GIF stops by itself at its size limit (app/clips.py: max_gif_frames, ~19 s of a
960 x 800 scene area at 30 fps). Closing the window saves a clip still running.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any, Protocol

import pygame

from app.outputs import OUTPUT_DIR
from app.clips import (DEFAULT_FPS, DEFAULT_WIDTH, Clip, ClipWriter, check_video, even,
                       max_gif_frames, open_clip)
from app.draw import hud



class Window(Protocol):
    """What a clip asks of the window it records (app/window/window.py's Window, which owns
    this recorder: the import runs one way)."""

    scene_view: Any
    current_view: Any

    def flash(self, text: str, color: tuple = ..., seconds: float = ...,
              topic: str = "") -> None: ...

SAVED_COLOR = (140, 230, 140)


class ClipRecorder:
    """The window's clip: start()/stop() (F9 toggles), after_draw() once per rendered frame."""

    def __init__(self, path: str | None = None, fps: int | None = None, width: int | None = None,
                 folder: str | Path = OUTPUT_DIR + "/clips"):
        self.path = Path(path) if path else None     # --video: where the clips go
        self.fps = fps or DEFAULT_FPS
        self.width = width or DEFAULT_WIDTH
        self.folder = Path(folder)
        self.writer: ClipWriter | None = None
        self.made = 0                     # clips started (names OUT, OUT-2, ...)
        self._view = None                 # the SceneView being recorded
        self._area = pygame.Rect(0, 0, 0, 0)
        self._mark: tuple[object, int] = (None, 0)   # (runner, its steps at the last frame)
        self._video_t = 0.0               # the clip's clock, seconds
        self._next = 0                    # index of the next frame to take
        self._saving: list[tuple[threading.Thread, dict]] = []

    @property
    def active(self) -> bool:
        return self.writer is not None

    # --- F9 ----------------------------------------------------------------------------------
    def toggle(self, window: "Window") -> None:
        if self.active:
            self.stop(window)
        else:
            self.start(window)

    def next_path(self, scene_name: str) -> Path:
        """Where the next clip goes: --video's name (then -2, -3, ...), else clips/<scene>-<stamp>
        .gif (never over an existing file)."""
        if self.path is not None:
            k = self.made + 1
            return self.path if k == 1 else self.path.with_name(
                f"{self.path.stem}-{k}{self.path.suffix}")
        stamp = time.strftime("%Y%m%d-%H%M%S")
        path, k = self.folder / f"{scene_name}-{stamp}.gif", 2
        while path.exists():
            path, k = self.folder / f"{scene_name}-{stamp}-{k}.gif", k + 1
        return path

    def start(self, window: "Window") -> None:
        from app.headless import check_output_path
        view = window.scene_view
        if view is None:
            window.flash("F9 records a clip of a running scene: open one first", hud.WARN_COLOR)
            return
        path = self.next_path(view.scene.name)
        problem = check_video(str(path), self.fps, what="clip") or check_output_path(
            str(path), "clip")
        if problem:
            window.flash(problem, hud.ERROR_COLOR)
            return
        area = view.world_area()
        w = min(self.width, area.width)
        size = (even(w), even(area.height * w / area.width))
        try:
            self.writer = open_clip(str(path), size, self.fps)
        except OSError as e:                    # OutputError: one line, the path in it
            window.flash(str(e), hud.ERROR_COLOR)
            return
        self.made += 1
        self._view, self._area = view, area.copy()
        self._mark = (view.runner, view.runner.steps)
        self._video_t, self._next = 0.0, 0

    def stop(self, window: "Window", why: str = "") -> None:
        """Stop recording and save the clip in a background thread (a message says when)."""
        writer, self.writer, self._view = self.writer, None, None
        if writer is None:
            return
        result: dict = {"path": Path(writer.path).resolve(), "why": why}

        def save() -> None:
            try:
                result["clip"] = writer.close()
            except (OSError, RuntimeError, ValueError) as e:
                result["error"] = str(e)
        thread = threading.Thread(target=save, name="clip-save", daemon=False)
        thread.start()
        self._saving.append((thread, result))
        window.flash(f"{why}saving the clip {result['path']} ...", SAVED_COLOR)

    # --- every frame ---------------------------------------------------------------------------
    def after_draw(self, window: "Window", screen: pygame.Surface) -> None:
        """Once per rendered frame: take the frames that are due from the world area, then
        draw the REC box (after, so it is not in the clip) and report clips saved."""
        self._report(window)
        if not self.active:
            return
        view = window.scene_view
        if view is not self._view:
            self.stop(window, "the scene closed: ")
            return
        self._area = view.world_area()             # F2, Tab or a resize may change it
        runner = view.runner
        if runner is not self._mark[0]:            # a recording restart made a new runner
            self._mark = (runner, 0)
        self._video_t += (runner.steps - self._mark[1]) * view.scene.dt / view.clock.slow_motion
        self._mark = (runner, runner.steps)
        if window.current_view is view:            # not while the help covers the scene
            try:
                while self._next <= self._video_t * self.fps + 1e-6:
                    self.writer.add_surface(self._fitted(screen.subsurface(self._area),
                                                         view.scene.background))
                    self._next += 1
            except (OSError, ValueError) as e:     # ffmpeg gone, a broken pipe
                self.stop(window, f"the clip stopped ({e}): ")
                return
        else:
            self._next = max(self._next, int(self._video_t * self.fps) + 1)
        most = max_gif_frames(*self.writer.size)
        if self.writer.frames >= most and Path(self.writer.path).suffix.lower() == ".gif":
            self.stop(window, f"a GIF of this size holds at most {most} frames (for longer "
                      "clips: --video OUT.mp4): ")
            return
        panel = getattr(view, "panel", None)
        self._draw_box(screen, _text_boxes(view), panel.rect if panel is not None else None)

    def _fitted(self, area: pygame.Surface, background) -> pygame.Surface:
        """The scene area as a frame of the clip's size: as it is if its shape is the clip's
        (scaled down if larger), else scaled to fit and centred on the scene's background (the
        area changed shape while recording: F2, Tab, a resize)."""
        w, h = self.writer.size
        aw, ah = area.get_size()
        if abs(aw * h - ah * w) <= max(w, h):        # the same shape, to a pixel
            return area
        k = min(w / aw, h / ah)
        frame = pygame.Surface((w, h), 0, 32)
        frame.fill(background)
        scaled = pygame.transform.smoothscale(area.convert(32) if area.get_bitsize() < 24
                                              else area, (max(1, int(aw * k)), max(1, int(ah * k))))
        frame.blit(scaled, ((w - scaled.get_width()) // 2, (h - scaled.get_height()) // 2))
        return frame

    def _draw_box(self, screen: pygame.Surface, text_boxes: list[pygame.Rect],
                  panel: pygame.Rect | None = None) -> None:
        """The REC box at the bottom of the panel (off the scene, which the class watches); with
        the panel hidden, at the top right of the scene area, moved down below any text box it
        would cover (the HUD, compare mode's header and panes' HUDs: a narrow window, large
        text); at the bottom right if no room is left under them."""
        seconds = self.writer.frames / self.fps
        lines = [hud.Line(f"REC clip {seconds:.1f} s ({self.writer.frames} frames): F9 stops",
                          hud.ERROR_COLOR),
                 hud.Line(str(Path(self.writer.path).resolve()), hud.DIM_COLOR)]
        if panel is not None and panel.width > 16:
            width = panel.width - 16
            w, h = hud.box_size(lines, hud.HUD_SIZE, max_width=width)
            self.box = pygame.Rect(panel.left + 8, panel.bottom - h - 8, w, h)
            screen.fill((21, 24, 29), self.box.inflate(16, 16).clip(panel))
            hud.text_box(screen, lines, self.box.topleft, hud.HUD_SIZE, max_width=width)
            return
        width = max(1, min(self._area.width - 16, 620))
        w, h = hud.box_size(lines, hud.HUD_SIZE, max_width=width)
        box = pygame.Rect(self._area.right - w - 8, self._area.top + 8, w, h)
        hit = box.collidelist(text_boxes)
        while hit >= 0:
            box.top = text_boxes[hit].bottom + 8
            hit = box.collidelist(text_boxes)
        if box.bottom > self._area.bottom:
            box.bottom = self._area.bottom - 8
        self.box = box                              # where it went (the tests look)
        hud.text_box(screen, lines, box.topleft, hud.HUD_SIZE, max_width=width)

    def _report(self, window: "Window") -> None:
        """Say so for each clip written since the last frame: in the window, and on stdout (a
        clip saved while the menu shows, or just before quitting, is named there too)."""
        for thread, result in [s for s in self._saving if not s[0].is_alive()]:
            self._saving.remove((thread, result))
            text = _saved_text(result)
            window.flash(text, hud.ERROR_COLOR if "error" in result else SAVED_COLOR,
                         seconds=8.0)
            print(text, flush=True)

    def finish(self, window: "Window") -> list[str]:
        """On the way out: stop a clip still running, wait for every clip to be written, and
        return a line per clip saved (the window prints them)."""
        self.stop(window)
        lines = []
        for thread, result in self._saving:
            thread.join()
            lines.append(_saved_text(result))
        self._saving.clear()
        return lines


def _text_boxes(view) -> list[pygame.Rect]:
    """The text boxes on the scene area: the HUD, or compare mode's header and panes' HUDs."""
    grid = view.pane
    layouts = [p.layout for p in grid.panes] if hasattr(grid, "panes") else [view.layout]
    boxes = [lay.hud for lay in layouts if lay is not None]
    header = getattr(grid, "header", None)
    return boxes + ([header] if header is not None else [])


def _saved_text(result: dict) -> str:
    if "error" in result:
        return result["error"]           # OutputError's line: the path, why, what was left
    clip: Clip = result["clip"]
    return (f"clip saved: {result['path']} ({clip.frames} frames, {clip.size[0]}x{clip.size[1]}"
            f", {clip.seconds:.1f} s, {clip.bytes / 1e6:.2f} MB"
            + (", replaced the file that was there)" if clip.replaced else ")"))
