"""The interactive window: the pygame loop, the layout, and the routing of events to the view.

`python -m app` opens the scene menu; `python -m app --scene cloth` opens one scene. A scene runs
exactly as headless: the same `SceneRunner` (app/runner.py) advances it in fixed steps, delivers
its mouse and key events and rolls it back if it goes NaN/inf, so a demo recorded here with
`--record FILE` replays headless step for step. What the window adds is for people in a room:
the views (menu, running scene, help; app/window/views.py), the parameter panel with its "try
this" cards (panel.py), the recorder (recorder.py) and the shell keys, all listed in ONE table
(keys.py) that also produces the help overlay's list and the README's Controls table.

Layout: the world area is the window left of the panel. The HUD box sits at its top left (and,
on its second page, F4, the metrics strip along the bottom); the scene's content
(`content_bounds()`) is fitted into what they leave free (app/draw/layout.py), so they never
cover it, at any text size (F2) and window size. Messages (a refused value, a blow-up, what a
card asks you to watch) are lines of the HUD box, never a banner over the scene, and each names
its topic, so that it goes when what it speaks of changes. F3 hides HUD and metrics for a clean
picture.

The `Window` never owns the main loop, so tests drive it directly (handle_pygame_event, update,
render); `run_window` is the loop the command line calls.
"""

from __future__ import annotations

import asyncio
import os
import sys
import time
import traceback
from pathlib import Path
from typing import Any, NamedTuple, Sequence

import pygame

from app.draw import hud, menu, save_png
from app.outputs import OUTPUT_DIR
from app.draw.text import TEXT
from app.runner import NONFINITE_TEXT, SNAPSHOT_EVERY, SceneRunner
from app.scene import InputEvent, ParamError, Scene, SceneError
from app.window.clip_recorder import ClipRecorder
from app.window.display import open_display as _open_display
from app.window.recorder import Recorder
from app.window.panel_size import PANEL_WIDTH
from app.window.scene_view import SceneView
from app.window.speed import FPS_CAP
from app.window.views import HelpView, MenuView, ShellView

DEFAULT_SIZE = (1280, 800)        # world 960x720 at zoom 1 + a 320 px panel
LARGE_TEXT_SCALE = 1.6
MESSAGE_SECONDS = 4.0
NO_DISPLAY = ("python -m app: error: no display for the window: {}; use --headless, or run under "
              "xvfb-run")

__all__ = ["Window", "Message", "run_window", "window_main", "NONFINITE_TEXT", "SNAPSHOT_EVERY",
           "LARGE_TEXT_SCALE"]

class Message(NamedTuple):
    """A passing message of the window: shown until `until` (the window's clock) or until what
    it speaks of changes. topic: "setting:NAME" (a refused value of NAME), "card" (a card's
    promise), "recording", "scene" (anything else about the open scene); "" is the window's
    own (a screenshot saved), which outlives a scene switch."""

    until: float
    text: str
    color: tuple[int, int, int]
    topic: str = ""


class Window:
    """The shell around one view at a time (menu, running scene, help).

    Drive it with handle_pygame_event(ev) for each pygame event, update(frame_seconds) once per
    frame, render() to draw on `screen`. `running` turns False when the user quits.
    """

    PANEL_WIDTH = PANEL_WIDTH        # the panel's width at normal text (panel_size.py)

    def __init__(self, screen: pygame.Surface, scenes: Sequence[type[Scene]] | None = None,
                 large_text: bool = False, events: list[InputEvent] | None = None,
                 screenshot_dir: str | Path = OUTPUT_DIR + "/screenshots",
                 record: str | Path | None = None):
        if scenes is None:
            from scenes import SCENES
            scenes = SCENES
        self.screen = screen
        self.scenes: list[type[Scene]] = list(scenes)
        self.screenshot_dir = Path(screenshot_dir)
        self.running = True
        self.output_failed = False      # an output that could not be written: exit code 2
        self.recorder = Recorder(record)
        self.clips = ClipRecorder()           # F9 (run_window sets --video, --fps, --width)
        self.panel_visible = True
        self.hud_details = False              # F4: the HUD's second page (every scene)
        self.menu_selected = 0
        self.messages: list[Message] = []
        self.wall = 0.0                       # seconds of frames seen (update's clock)
        self.last_draw_seconds = 0.0          # wall time of the last render()
        self._replay = list(events or [])
        self._replay_scene: type[Scene] | None = None
        self._pending_shot: Path | None = None
        self.arrows = False                   # V: the arrows overlay, for every scene
        self.energy_bars = False              # E: the energy bars, for every scene
        self.watch_blowups = False            # B: a blow-up goes on for a second before rollback
        self.csv_path: str | None = None      # --csv FILE: the open scene's metrics go there
        self.plot_start: list[str] = []       # --plot: what the first scene opens plotted
        self._csv_owner = None                # the view whose metrics the file holds
        self.fullscreen = False               # F11 (--fullscreen)
        self.windowed_size: tuple[int, int] = tuple(screen.get_size())   # F11 comes back to it
        self.current_view: ShellView = MenuView(self)
        TEXT.scale = LARGE_TEXT_SCALE if large_text else 1.0

    # --- views ---------------------------------------------------------------------------------
    def show_view(self, view: ShellView) -> None:
        """Make `view` the current one (arcade's show_view)."""
        self.current_view.on_hide()
        self.current_view = view
        view.on_show()

    @property
    def scene_view(self) -> SceneView | None:
        """The running scene's view (also while its help is shown), or None in the menu."""
        v = self.current_view
        v = getattr(v, "under", v)         # the help or the plot's list over a running scene
        return v if isinstance(v, SceneView) else None

    @property
    def scene(self) -> Scene | None:
        sv = self.scene_view
        return sv.scene if sv is not None else None

    @property
    def view(self):
        """The world <-> screen transform of the running scene (app.draw.view.View)."""
        sv = self.scene_view
        return sv.view if sv is not None else None

    @property
    def show_help(self) -> bool:
        return isinstance(self.current_view, HelpView)

    def open_scene(self, scene_cls: type[Scene], overrides: dict[str, Any] | None = None) -> bool:
        """Build scene_cls(overrides) and show it; on a construction error stay in (or go back
        to) the menu and show the error. Return True if the scene is open."""
        try:
            scene = scene_cls(overrides or {})
        except (ParamError, SceneError) as e:     # refused settings, or a student's code failed
            SceneRunner.failures += isinstance(e, SceneError)
            self._to_menu(f"{scene_cls.name}: {e}")
            return False
        except Exception as e:     # a broken scene must not close the classroom's window
            traceback.print_exc()
            self._to_menu(f"{scene_cls.name} failed to build: {type(e).__name__}: {e}")
            return False
        if scene_cls in self.scenes:
            self.menu_selected = self.scenes.index(scene_cls)
        events = None
        if self._replay and self._replay_scene in (None, scene_cls):
            self._replay_scene = scene_cls        # --input events belong to the first scene
            events, self._replay = self._replay, []
        opened_with = {k: str(v) for k, v in (overrides or {}).items()}
        self.messages = [m for m in self.messages if not m.topic]    # the old scene's go
        self.show_view(SceneView(self, scene, opened_with, events))
        if pygame.display.get_init() and pygame.display.get_surface() is not None:
            pygame.display.set_caption(f"Physics lab: {scene_cls.title or scene_cls.name}")
        return True

    def open_compare(self, scene_cls: type[Scene], shared: dict[str, Any], variants: list,
                     card: Any = None) -> bool:
        """Open a comparison of scene_cls (app/compare.py): `shared` settings in every pane,
        each Variant's own in its pane; `card`: the comparison card it comes from. A refused
        comparison stays where the window is and says why. Return True if it is open."""
        from app.compare import resolve_variants
        from app.window.compare_view import CompareView
        try:
            overrides = resolve_variants(scene_cls, shared, variants)
            scenes = [scene_cls(o) for o in overrides]
        except (ParamError, SceneError) as e:
            SceneRunner.failures += isinstance(e, SceneError)
            if self.scene_view is None:
                self._to_menu(f"{scene_cls.name}: {e}")
            else:
                self.flash(f"{scene_cls.name}: {e}", hud.ERROR_COLOR, topic="card")
            return False
        events = None
        if self._replay and self._replay_scene in (None, scene_cls):
            self._replay_scene = scene_cls
            events, self._replay = self._replay, []
        self.messages = [m for m in self.messages if not m.topic]
        self.show_view(CompareView(self, scenes, shared, variants, events))
        if card is not None:
            self.flash(f"Try: {card.label} ({card.changes()}): {card.watch}", hud.ACCENT_COLOR,
                       seconds=12.0, topic="card")
        if pygame.display.get_init() and pygame.display.get_surface() is not None:
            pygame.display.set_caption(f"Physics lab: {scene_cls.title or scene_cls.name}, "
                                       f"{len(scenes)} variants")
        return True

    def own_csv(self, view: Any) -> None:
        """`view` opens the --csv file: the view that had it closes it first (the file holds
        the last scene opened, as --record does)."""
        if self._csv_owner is not None and self._csv_owner is not view:
            self._csv_owner.close_instruments()
        self._csv_owner = view

    def close(self) -> None:
        """The window closes: the --csv file is flushed and closed."""
        if self._csv_owner is not None:
            self._csv_owner.close_instruments()
            self._csv_owner = None

    def open_menu(self) -> None:
        self._to_menu("")

    def _to_menu(self, message: str) -> None:
        self.show_view(MenuView(self, message))

    @property
    def menu_message(self) -> str:
        return self.current_view.message if isinstance(self.current_view, MenuView) else ""

    def switch_scene(self, delta: int) -> None:
        """PageUp/PageDown: the previous/next scene in the menu's order."""
        if not self.scenes:
            return
        order = menu.menu_order(self.scenes)
        cur = type(self.scene) if self.scene is not None else None
        if cur in self.scenes:
            i = order.index(self.scenes.index(cur)) + delta
        else:
            i = order.index(self.menu_selected) + (0 if delta > 0 else -1) \
                if self.menu_selected in order else 0
        self.open_scene(self.scenes[order[i % len(order)]])

    def previous_scene(self) -> None:
        self.switch_scene(-1)

    def next_scene(self) -> None:
        self.switch_scene(+1)

    # --- text size, size -----------------------------------------------------------------------
    @property
    def large_text(self) -> bool:
        return TEXT.scale > 1.0

    def toggle_large_text(self) -> None:
        self.set_large_text(not self.large_text)

    def set_large_text(self, on: bool) -> None:
        TEXT.scale = LARGE_TEXT_SCALE if on else 1.0
        self.relayout()

    def relayout(self) -> None:
        self.current_view.on_layout()

    def toggle_details(self) -> None:
        """F4: the HUD's second page (every line, the costs by effect, the metrics strip) or
        its first (what a class reads every frame); it stays so for the next scene."""
        self.hud_details = not self.hud_details
        self.relayout()

    def toggle_energy(self) -> None:
        """E: the energy bars on or off (every scene that has an energy; it stays so for the
        next scene). A scene without one says why."""
        self.energy_bars = not self.energy_bars
        scene = getattr(self.current_view, "scene", None)
        if self.energy_bars and scene is not None and scene.energies() is None:
            self.flash(f"{scene.title or scene.name} has no energy bars: "
                       f"{scene.no_energy_words}", topic="energy")

    def toggle_watch(self) -> None:
        """B: watch blow-ups (a diverging run goes on, drawn clipped to the window, for up to a
        second before the rollback; N then replays its last second) or roll back at once."""
        self.watch_blowups = not self.watch_blowups
        self.flash("B: blow-ups are " + ("watched for up to a second, then rolled back; N "
                                         "replays the last second" if self.watch_blowups
                                         else "rolled back at once"), topic="watch")

    def resize(self, surface: pygame.Surface | None = None) -> None:
        self.screen = surface or pygame.display.get_surface() or self.screen
        self.relayout()

    def toggle_fullscreen(self) -> None:
        """F11: full screen at the desktop's size, or back to the window's size (--size)."""
        self.set_fullscreen(not self.fullscreen)

    def set_fullscreen(self, on: bool) -> None:
        if not (pygame.display.get_init() and pygame.display.get_surface() is not None):
            return                                  # drawing off-screen: nothing to resize
        if on == self.fullscreen:
            return
        if on:
            self.windowed_size = self.screen.get_size()
            surface = pygame.display.set_mode((0, 0), pygame.FULLSCREEN)
        else:
            surface = pygame.display.set_mode(self.windowed_size, pygame.RESIZABLE)
        self.fullscreen = on
        self.resize(surface)

    # --- messages ------------------------------------------------------------------------------
    def flash(self, text: str, color=hud.WARN_COLOR, seconds: float = MESSAGE_SECONDS,
              topic: str = "scene") -> None:
        """Show a message for a few seconds (in the HUD box), or until its topic is cleared; a
        message on the same topic replaces the last one."""
        self.clear_messages(topic)
        self.messages.append(Message(self.wall + seconds, text, color, topic))

    def clear_messages(self, *topics: str) -> None:
        """Remove the messages on these topics ("setting:" clears every setting's; "" none)."""
        def gone(m: Message) -> bool:
            return any(t and (m.topic == t or (t.endswith(":") and m.topic.startswith(t)))
                       for t in topics)
        self.messages = [m for m in self.messages if not gone(m)]

    # --- the frame -----------------------------------------------------------------------------
    def handle_pygame_event(self, ev: pygame.event.Event) -> None:
        if ev.type == pygame.QUIT:
            self.running = False
        elif ev.type == pygame.VIDEORESIZE:
            self.resize()
        else:
            self.current_view.handle_event(ev)

    def update(self, frame_seconds: float) -> int:
        """Advance the window by one frame of `frame_seconds` wall time; return the number of
        physics steps run."""
        self.wall += frame_seconds
        self.messages = [m for m in self.messages if m.until > self.wall]
        return self.current_view.update(frame_seconds)

    def render(self) -> None:
        t0 = time.perf_counter()
        self.current_view.draw(self.screen)
        self.last_draw_seconds = time.perf_counter() - t0
        self.clips.after_draw(self, self.screen)     # a clip's frames (before the REC box)
        self._save_pending()

    # --- screenshots -----------------------------------------------------------------------------
    def screenshot(self) -> Path:
        """F12: save the next rendered frame to screenshots/<scene>-<timestamp>.png."""
        name = self.scene.name if self.scene is not None else "menu"
        stamp = time.strftime("%Y%m%d-%H%M%S")
        path = self.screenshot_dir / f"{name}-{stamp}.png"
        k = 2
        while path.exists():
            path = self.screenshot_dir / f"{name}-{stamp}-{k}.png"
            k += 1
        self._pending_shot = path
        return path

    def _save_pending(self) -> None:
        if self._pending_shot is None:
            return
        path, self._pending_shot = self._pending_shot, None
        try:
            self.save_screenshot(path)
        except (pygame.error, OSError) as e:
            self.flash(f"screenshot failed: {e}", hud.ERROR_COLOR, topic="")
            return
        self.flash(f"screenshot saved: {path.resolve()}", (140, 230, 140), seconds=6.0, topic="")

    def save_screenshot(self, path: str | Path) -> None:
        save_png(self.screen, path)

    def toggle_clip(self) -> None:
        """F9: start or stop a clip of the scene area (app/window/clip_recorder.py)."""
        self.clips.toggle(self)

    # --- recording (what the tests and run_window read) ------------------------------------------
    @property
    def session_steps(self) -> int:
        sv = self.scene_view
        return sv.runner.steps if sv is not None else 0

    @property
    def session_time(self) -> float:
        """Simulated seconds since the scene was opened (the runner's clock: R included)."""
        sv = self.scene_view
        return sv.runner.clock if sv is not None else 0.0

    @property
    def recorded(self) -> list[dict]:
        s = self.recorder.session
        return s.events if s is not None else []

    def write_recording(self, path: str | Path) -> int:
        """Write the open scene's recorded events to `path` in the --input format; return how
        many."""
        saved, self.recorder.path = self.recorder.path, Path(path)
        try:
            self.recorder.write()
        finally:
            self.recorder.path = saved
        return len(self.recorded)


# ----------------------------------------------------------------------------------------------
# the main loop (python -m app without --headless)
# ----------------------------------------------------------------------------------------------

def run_window(scene_name: str | None, overrides: dict[str, str], record: str | None = None,
               screenshot: str | None = None, seconds: float | None = None,
               large_text: bool = False, events: list | None = None, card=None,
               compare: list | None = None, extras=None, clips: dict | None = None,
               size: tuple[int, int] | None = None, fullscreen: bool = False) -> int:
    """Open the window (the menu, or `scene_name` with `overrides`, or with the try `card`
    applied as a click applies it, or a comparison of the `compare` variants with `overrides`
    shared) and run it until the user quits, or for `seconds` of wall time. Return the exit
    code (2 when there is no display). With `record`, the events are written and the replay
    command printed on every way out; `clips` (path, fps, width) set up F9's clips, saved and
    named on every way out too; `extras` (app.headless.Extras): --csv, --plot, --arrows;
    `size` (--size WxH): the window's size (default DEFAULT_SIZE), `fullscreen` (--fullscreen):
    start full screen (F11 toggles).

    The loop itself is `window_main`, a coroutine that yields once a frame (what a browser
    build through pygbag needs: docs/developers.md); here asyncio runs it."""
    return asyncio.run(window_main(scene_name, overrides, record, screenshot, seconds,
                                   large_text, events, card, compare, extras, clips, size,
                                   fullscreen))


async def window_main(scene_name: str | None, overrides: dict[str, str],
                      record: str | None = None, screenshot: str | None = None,
                      seconds: float | None = None, large_text: bool = False,
                      events: list | None = None, card=None, compare: list | None = None,
                      extras=None, clips: dict | None = None,
                      size: tuple[int, int] | None = None, fullscreen: bool = False) -> int:
    """The window's main loop as one coroutine (run_window's arguments): each frame reads the
    events, advances the view, draws, flips, and then awaits asyncio.sleep(0) once, so that a
    browser's event loop (pygbag) gets control back between frames; on the desktop that await
    costs nothing and the frame rate is pygame's clock's, as before."""
    try:
        screen = _open_display(size or DEFAULT_SIZE, fullscreen)
    except pygame.error as e:
        print(NO_DISPLAY.format(str(e).strip() or "unknown SDL error"), file=sys.stderr)
        pygame.display.quit()
        return 2
    pygame.font.init()
    pygame.display.set_caption("Physics lab")
    pygame.key.set_repeat()
    from app.draw import formula
    formula.BACKGROUND = screenshot is None      # F4's formulas drawn by a worker: no frame waits
    from scenes import get_scene, menu_scenes
    window = Window(screen, menu_scenes(), large_text=large_text, events=events, record=record)
    window.windowed_size = tuple(size or DEFAULT_SIZE)
    window.fullscreen = fullscreen
    window.clips = ClipRecorder(**(clips or {}))
    if extras is not None:
        window.csv_path, window.arrows = extras.csv, extras.arrows
        window.plot_start = list(extras.plot)
    scene_cls = get_scene(scene_name) if scene_name else None
    if scene_cls is not None and compare is not None:
        window.open_compare(scene_cls, overrides, compare, card if card is not None and
                            card.compare else None)
    elif scene_cls is not None:
        if window.open_scene(scene_cls, overrides) and card is not None:
            window.scene_view.apply_try(card)
    if screenshot and seconds is None:
        seconds = 2.0
    fps_clock = pygame.time.Clock()
    start = time.perf_counter()
    failures = SceneRunner.failures
    code = 0
    try:
        while window.running:
            frame_seconds = min(fps_clock.tick(FPS_CAP) / 1000.0, 0.25)
            for ev in pygame.event.get():
                window.handle_pygame_event(ev)
            window.update(frame_seconds)
            window.render()
            pygame.display.flip()
            if seconds is not None and time.perf_counter() - start >= seconds:
                break
            await asyncio.sleep(0)      # the one yield a frame (a browser's loop runs here)
        if screenshot:
            window.render()
            replaced = os.path.exists(screenshot)
            window.save_screenshot(screenshot)
            if replaced:           # the summary says when a file was replaced (as headless)
                print(f"screenshot: {screenshot} (replaced the file that was there)",
                      flush=True)
    except (KeyboardInterrupt, asyncio.CancelledError):   # Ctrl-C in the terminal (asyncio.run
        code = 130                 # turns a real SIGINT into a cancel of this coroutine): the
                                   # recording and clips are still saved (every way out), then
                                   # exit code 130 and this one line
        print("python -m app: interrupted (Ctrl-C); the window closed as Esc would close it",
              file=sys.stderr, flush=True)
    else:                          # a student's code that raised while the window was open:
        code = 1 if SceneRunner.failures > failures else 0     # exit code 1, as headless
    finally:
        window.close()
        if window.output_failed and code == 0:   # the --csv could not be written (its line
            code = 2                              # is on stderr): not a success
        line = window.recorder.write()
        if line:
            print(line, flush=True)
        for line in window.clips.finish(window):
            print(line, flush=True)
        pygame.display.quit()      # not pygame.quit(): app.draw.text caches fonts
    return code
