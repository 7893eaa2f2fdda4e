"""The view of a running scene: its SceneRunner (stepping, timing, events, rollback), the
fixed-step clock, the layout of world, HUD, metrics strip and panel, and the routing of mouse and
keys to the scene (or to the panel while one of its text boxes has the keyboard).
"""

from __future__ import annotations

import time
import traceback
from collections import deque
from typing import TYPE_CHECKING, Any

import pygame

from app.draw import hud
from app.draw.layout import Layout, draw_scene, scene_layout
from app.draw.text import TEXT
from app.loop import FixedStepClock
from app.runner import SceneRunner
from app.scene import InputEvent, ParamError, Scene, SceneError, Try
from app.window import keys
from app.window.views import HelpView, ShellView

if TYPE_CHECKING:
    from app.window.panel import ParamPanel
    from app.window.window import Window

STEP_BUDGET_SECONDS = 0.1   # physics time per frame after which the frame's other steps are
                            # dropped (the window stays responsive; time runs slower)
SETTLE_FRAMES = 20          # frames after opening a scene or a new layout whose hiccups (the
                            # build, the first draw, font loading) are not "slower than real time"
PANEL_BACKGROUND = (21, 24, 29)
ERROR_TEXT = ("The scene stopped: {message}\n\nThe scene is paused and stays open: fix the code, "
              "then press R to run it again.")


class SceneView(ShellView):
    """A running scene: its runner (stepping, timing, events, rollback), the fixed-step clock,
    the layout of world, HUD, metrics strip and panel, and the routing of input to the scene."""

    def __init__(self, window: "Window", scene: Scene, opened_with: dict[str, Any],
                 events: list[InputEvent] | None = None):
        super().__init__(window)
        self.scene = scene
        self.opened_with = dict(opened_with)
        self.runner = SceneRunner(scene, events, rollback=True)
        self.runner.on_reset = self._after_rebuild
        self.clock = FixedStepClock()
        self.manager = None
        self.panel: ParamPanel | None = None
        self.panel_visible = window.panel_visible
        self.overlays = True                # F3 hides HUD and metrics
        self.banner = ""                    # the non-finite rollback's message
        self.dragging: set[int] = set()     # mouse buttons pressed in the world area
        self.typed_keys: set[int] = set()   # keys pressed while typing into the panel
        self.layout: Layout | None = None
        self.hud_room = (0, 0)              # reserved HUD box; grows, reset by on_layout
        self.settle = SETTLE_FRAMES
        self.frames: deque[float] = deque()  # wall times of the last second's frames
        self.slow: tuple[float, str] | None = None   # (wall time, why) of the last slow frame
        self._shown_ms: float | None = None          # the HUD's physics figure (physics_ms)
        self._ms_mark = 0                            # runner.steps when it was last read
        window.recorder.start(scene.name, self.opened_with)

    # --- lifecycle ---------------------------------------------------------------------------
    def on_show(self) -> None:
        self.on_layout()

    def on_layout(self) -> None:
        """(Re)build the pygame-gui manager and the panel for the window's size and text size."""
        import pygame_gui
        from app.window.panel import ParamPanel, theme
        size = self.window.screen.get_size()
        self.manager = pygame_gui.UIManager(size, theme_path=theme(TEXT.scale))
        self.panel = None
        if self.panel_visible:
            area = self.world_area()
            self.panel = ParamPanel(self, self.manager,
                                    pygame.Rect(area.right, 0, size[0] - area.right, size[1]))
        self.hud_room = (0, 0)
        self.settle = SETTLE_FRAMES
        self.fit()

    @property
    def panel_width(self) -> int:
        if not self.panel_visible:
            return 0
        w = self.window.screen.get_width()
        return min(int(round(self.window.PANEL_WIDTH * TEXT.scale)), int(w * 0.36))

    def world_area(self) -> pygame.Rect:
        """The part of the window left of the panel, where the world is drawn."""
        w, h = self.window.screen.get_size()
        return pygame.Rect(0, 0, max(w - self.panel_width, 1), h)

    def fit(self, lines: list | None = None) -> Layout:
        """Fit the scene's content into the world area less the HUD and the metrics strip (the
        HUD's room only grows until the next on_layout)."""
        if self.overlays and lines is None:
            lines = self.hud_lines()
        self.layout = scene_layout(self.world_area(), self.scene, lines if self.overlays else None,
                                   self.hud_room)
        self.hud_room = self.layout.hud.size
        return self.layout

    @property
    def view(self):
        return self.layout.view

    # --- keys of the table (names are the table's actions) -----------------------------------
    @property
    def paused(self) -> bool:
        return self.clock.paused

    def toggle_pause(self) -> None:
        self.clock.toggle_pause()
        if not self.clock.paused:
            self.banner = ""

    def single_step(self) -> None:
        self.clock.single_step()

    def slower(self) -> None:
        self.clock.slower()

    def faster(self) -> None:
        self.clock.faster()

    def reset(self) -> None:
        """R: rebuild the scene. Recorded as a key "r", which the headless runner replays as a
        reset too."""
        self.runner.clear_error()
        self.deliver(InputEvent("key_down", key="r"))
        self.deliver(InputEvent("key_up", key="r"))

    def toggle_help(self) -> None:
        self.window.show_view(HelpView(self.window, self))

    def toggle_overlays(self) -> None:
        self.overlays = not self.overlays
        self.hud_room = (0, 0)
        self.fit()

    def toggle_panel(self) -> None:
        self.panel_visible = self.window.panel_visible = not self.panel_visible
        self.on_layout()

    def escape(self) -> None:
        self.window.open_menu()

    # --- settings ------------------------------------------------------------------------------
    def apply_setting(self, name: str, value: Any) -> bool:
        """Change a param or effect through scene.set (validated). A refused value keeps the old
        one and shows why; return True if the value was taken."""
        scene, w = self.scene, self.window
        before = scene.settings().get(scene.canonical(name))
        try:
            rebuilt = scene.set(name, value)
        except ParamError as e:
            w.flash(str(e), hud.ERROR_COLOR)
            self._refresh_panel()
            return False
        except SceneError as e:
            self.runner.fail(e)
            self.clock.paused = True
            return False
        except Exception as e:          # a broken scene must not take the room's window down
            traceback.print_exc()
            w.flash(f"{name}={value!r} failed: {type(e).__name__}: {e}", hud.ERROR_COLOR)
            try:
                scene.set(name, before)
            except Exception:
                scene.reset()
            self._after_rebuild()
            return False
        after = scene.settings().get(scene.canonical(name))
        if rebuilt:
            self._after_rebuild()
        if after != before:
            self._recorded_change(scene.canonical(name), after)
        self._refresh_panel()
        return True

    def _recorded_change(self, name: str, value: Any) -> None:
        what = self.window.recorder.panel_change(name, value)
        if what == "restart":     # before the first press: start the recording from here
            self.scene.reset()
            self.runner = SceneRunner(self.scene, rollback=True)
            self.runner.on_reset = self._after_rebuild
            self.window.recorder.start(self.scene.name, changed_settings(self.scene))
            self.window.flash(f"recording restarted with {name}={value}: the replay starts "
                              "from here (given as --set)", hud.WARN_COLOR)
        elif what == "note":
            self.window.flash(f"recording: {name}={value} is a panel change after the first "
                              "press: the replay cannot repeat it (the exit message names it)",
                              hud.WARN_COLOR)

    def apply_try(self, card: Try) -> bool:
        """A "try this" card: check all its settings together (Scene.resolve, the panel's
        validation), apply them one by one, restart the scene and run it; say what to watch
        for."""
        scene = self.scene
        wanted = {scene.canonical(k): v for k, v in card.settings.items()}
        try:
            type(scene).resolve({**scene.settings(), **wanted})
        except ParamError as e:
            self.window.flash(f"{card.label}: {e}", hud.ERROR_COLOR)
            return False
        ok = all([self.apply_setting(k, v) for k, v in wanted.items()])
        if ok:
            # an experiment from a fresh start, running: what the card says to watch then holds
            # whatever ran before (RK4 damped at hertz 4 took long to blow up at 3; a blown-up
            # try stayed paused under the next; "Released high" mid-run changed nothing)
            if self.scene.steps:     # not just rebuilt by the settings (or a recording's
                self.reset()         # restart): a reset, recorded as "r" like the R key
            self.banner = ""         # (a rollback to t = 0 needs no reset, but its banner goes)
            self.clock.paused = False
            # one "Try:" line at a time: stacked ones grew the HUD and shrank the picture
            self.window.messages = [m for m in self.window.messages
                                    if not m[1].startswith("Try: ")]
            self.window.flash(f"Try: {card.watch}", hud.ACCENT_COLOR, seconds=12.0)
        return ok

    def _after_rebuild(self) -> None:
        """The scene was (re)built: new snapshot and timings (the runner), fresh banner."""
        self.banner = ""
        self.runner.rebuilt()
        self._shown_ms = None           # the old world's timings go with it
        self.dragging.clear()
        self._refresh_panel()

    def _refresh_panel(self) -> None:
        if self.panel is not None:
            self.panel.refresh()

    # --- events --------------------------------------------------------------------------------
    def typing(self) -> bool:
        """True while a text box of the panel has the keyboard: then no key goes anywhere else."""
        if self.panel is not None and self.panel.is_typing():
            return True
        focus = self.manager.get_focus_set() if self.manager is not None else None
        return any(type(e).__name__ == "UITextEntryLine" for e in (focus or ()))

    def handle_event(self, ev: pygame.event.Event) -> None:
        typing_before = self.typing()
        consumed = bool(self.manager.process_events(ev)) if self.manager is not None else False
        if self.panel is not None and ev.type >= pygame.USEREVENT and self.panel.handle(ev):
            return
        if ev.type in (pygame.KEYDOWN, pygame.KEYUP, pygame.TEXTINPUT):
            if typing_before or self.typing() or consumed:
                if ev.type == pygame.KEYDOWN:
                    self.typed_keys.add(ev.key)
                return                      # the keys are typing a value into the panel
            if ev.type == pygame.KEYUP and ev.key in self.typed_keys:
                self.typed_keys.discard(ev.key)     # the release of a key typed into the
                return                              # panel (Enter) is not the scene's either
            if ev.type == pygame.KEYDOWN and self.shell_key(ev.key):
                return
            if ev.type in (pygame.KEYDOWN, pygame.KEYUP) and \
                    pygame.key.name(ev.key) not in keys.SHELL_KEY_NAMES:
                kind = "key_down" if ev.type == pygame.KEYDOWN else "key_up"
                self.deliver(InputEvent(kind, key=pygame.key.name(ev.key)))
            return
        if ev.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP, pygame.MOUSEMOTION):
            self._mouse_event(ev, consumed)

    def _mouse_event(self, ev: pygame.event.Event, consumed: bool) -> None:
        in_world = self.world_area().collidepoint(ev.pos) and not consumed
        x, y = self.view.to_world(ev.pos)
        world = (round(x, 2), round(y, 2))     # as recorded, so a replay sees the same numbers
        if ev.type == pygame.MOUSEBUTTONDOWN and ev.button in (1, 3) and in_world:
            self.dragging.add(ev.button)
            self.deliver(InputEvent("mouse_down", pos=world, button=ev.button))
        elif ev.type == pygame.MOUSEBUTTONUP and ev.button in (1, 3) and (
                ev.button in self.dragging or in_world):
            self.dragging.discard(ev.button)
            self.deliver(InputEvent("mouse_up", pos=world, button=ev.button))
        elif ev.type == pygame.MOUSEMOTION and (in_world or self.dragging):
            self.deliver(InputEvent("mouse_move", pos=world))

    def deliver(self, event: InputEvent) -> None:
        """Hand a live event to the scene now (before the next step) and record it."""
        if self.runner.deliver(event):
            self._after_rebuild()
        self.window.recorder.add(event)

    # --- time ----------------------------------------------------------------------------------
    def update(self, frame_seconds: float) -> int:
        """One frame: the panel, then the steps the clock grants, within the step budget."""
        wall = self.window.wall
        self.frames.append(wall)
        while self.frames and self.frames[0] < wall - 1.0:
            self.frames.popleft()
        if self.manager is not None:
            self.manager.update(frame_seconds)
        self._refresh_panel()
        dropped_before = self.clock.dropped_steps
        n = self.clock.steps_for_frame(frame_seconds, self.scene.dt)
        t0 = time.perf_counter()
        ran, rollback = self.runner.run(n, STEP_BUDGET_SECONDS)
        physics = time.perf_counter() - t0
        if rollback is not None:
            self.clock.paused = True
            self.clock.accumulator = 0.0
            self.dragging.clear()
            self.banner = rollback.text()
            self._refresh_panel()
        elif self.runner.error is not None:
            self.clock.paused = True
        elif ran < n:
            self.clock.dropped_steps += n - ran      # the rest would freeze the window
        self.window.recorder.steps_run(self.runner.steps)
        self._watch_speed(frame_seconds, physics, self.clock.dropped_steps > dropped_before)
        return ran

    def _watch_speed(self, frame: float, physics: float, dropped: bool) -> None:
        """Remember why the last frame that dropped steps was slow: physics, drawing or the
        rest (the display, other programs). The first frames after a new layout do not count."""
        if self.settle > 0:
            self.settle -= 1
            return
        if not dropped:
            return
        draw = self.window.last_draw_seconds
        ms = lambda s: f"{1000 * s:.0f} ms"          # noqa: E731
        if physics >= draw and physics >= 0.3 * frame:
            why = (f"physics takes {ms(physics)} of a {ms(frame)} frame: fewer iterations, "
                   "substeps or hertz catch up")
        elif draw >= 0.3 * frame:
            why = (f"drawing takes {ms(draw)} of a {ms(frame)} frame (physics {ms(physics)}): "
                   "a smaller window or fewer effects drawn catch up")
        else:
            why = (f"the display or the machine is slow: a {ms(frame)} frame, of which physics "
                   f"{ms(physics)} and drawing {ms(draw)}")
        self.slow = (self.window.wall, why)

    # --- what the HUD reads --------------------------------------------------------------------
    @property
    def fps(self) -> float:
        if len(self.frames) < 2:
            return 0.0
        span = self.frames[-1] - self.frames[0]
        return (len(self.frames) - 1) / span if span > 0 else 0.0

    def physics_ms(self) -> float | None:
        """The HUD's ms per step: the mean of the steps run since the last call, smoothed
        0.7 old + 0.3 new, exactly as the scenes average their breakdown (effect_costs, read in
        the same call), so its parts add up to at most the total (the runner's 60-step mean
        against the scenes' smoothing read 5.4 ms with parts adding up to 8.7). Held while no
        step runs."""
        steps, recent = self.runner.steps, self.runner.recent_ms
        n = min(steps - self._ms_mark, len(recent))
        if n > 0:
            now = sum(list(recent)[-n:]) / n
            self._shown_ms = now if self._shown_ms is None else 0.7 * self._shown_ms + 0.3 * now
        self._ms_mark = steps
        return self._shown_ms

    def status_lines(self) -> list:
        """The shell's lines of the HUD box: fps, the physics cost, time and speed, warnings."""
        L, scene = hud.Line, self.scene
        lines: list = [f"{self.fps:.0f} fps  |  {hud.dt_text(scene)}",
                       hud.physics_line(self.physics_ms(), safe(scene.effect_costs, {}))]
        state = f"t = {scene.time:.2f} s  |  speed x{_slow_text(self.clock.slow_motion)}"
        if self.clock.paused:
            state += "  |  PAUSED (Space resumes, . steps)"
        slow = self.clock.paused or self.clock.slow_motion != 1.0
        lines.append(L(state, hud.WARN_COLOR if slow else hud.TEXT_COLOR))
        if self.window.recorder.active:
            lines.append(L(f"REC  recording to {self.window.recorder.path} (the replay command is "
                           "printed on exit)", hud.ERROR_COLOR))
        if self.slow is not None and self.window.wall - self.slow[0] < 1.0:
            lines.append(L("slower than real time: " + self.slow[1], hud.WARN_COLOR))
        return lines

    def notes(self) -> list:
        """Passing messages shown at the end of the HUD box (errors get a banner instead)."""
        return [hud.Line(text, color) for _, text, color in self.window.messages
                if color != hud.ERROR_COLOR]

    def hud_lines(self) -> list:
        """Everything in the HUD box, as drawn."""
        return hud.scene_lines(self.scene, self.status_lines(), self.notes())

    # --- drawing -------------------------------------------------------------------------------
    def draw(self, screen: pygame.Surface) -> None:
        scene = self.scene
        area = self.world_area()
        lines = self.hud_lines() if self.overlays else []
        layout = self.fit(lines)
        screen.fill(PANEL_BACKGROUND)
        try:
            bottom = draw_scene(screen, layout, scene, lines if self.overlays else None)
        except SceneError as e:
            self.runner.fail(e)
            self.clock.paused = True
            bottom = area.bottom - 6
        s = TEXT.scale
        if self.runner.error is not None and not scene.draws_own_error:
            top = layout.hud.bottom + 8 if self.overlays else area.top + int(40 * s)
            hud.banner(screen, ERROR_TEXT.format(message=self.runner.error), area,
                       hud.ERROR_COLOR, y=top)
        elif self.banner:              # over the paused picture, never over the HUD box
            top = area.centery - int(60 * s)
            if self.overlays:
                top = max(top, layout.hud.bottom + 8)
            hud.banner(screen, self.banner, area, hud.WARN_COLOR, y=top)
        for _, text, color in reversed(self.window.messages):
            if color == hud.ERROR_COLOR:
                bottom = hud.banner(screen, text, area, color, bottom=bottom).top
        if self.panel is not None:
            screen.fill(PANEL_BACKGROUND, self.panel.rect)
            pygame.draw.line(screen, (60, 66, 76), self.panel.rect.topleft,
                             self.panel.rect.bottomleft, 2)
        if self.manager is not None:
            self.manager.draw_ui(screen)


def changed_settings(scene: Scene) -> dict[str, Any]:
    """The scene's settings that differ from their defaults (the --set of a replay)."""
    defaults, on = type(scene).resolve({})
    now = scene.settings()
    base = {**defaults, **{e.name: e.name in on for e in scene.effects}}
    return {k: v for k, v in now.items() if base.get(k) != v}


def safe(fn, default):
    """fn(), or `default` if the scene raised SceneError (its message is shown elsewhere)."""
    try:
        return fn()
    except SceneError:
        return default


def _slow_text(factor: float) -> str:
    return "1" if factor == 1.0 else f"1/{int(round(1 / factor))}"
