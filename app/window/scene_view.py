"""The view of a running scene: its SceneRunner (stepping, timing, events, rollback), the
fixed-step clock, the pane that draws the scene with its HUD in the world area, the panel, and
the routing of mouse and keys to the scene (or to the panel while one of its text boxes has the
keyboard).

The HUD box holds everything the shell has to say: the status (time, step, cost), the scene's
own lines, and the messages (a refused value, a blow-up rolled back, what a card asks you to
watch): nothing is drawn over the scene's content. Each message names its topic and goes when
that changes (another value, another card, a reset, another scene).
"""

from __future__ import annotations

import time
import traceback
from typing import TYPE_CHECKING, Any

import pygame

from app import keys
from app.draw import hud
from app.draw.layout import Layout, Pane, draw_scene
from app.draw.text import TEXT
from app.loop import FixedStepClock
from app.runner import SceneRunner
from app.scene import InputEvent, ParamError, Scene, SceneError, Try
from app.window.camera_host import CameraHost
from app.window.instrument_host import InstrumentHost
from app.window.panel_size import panel_scale, panel_width, theme
from app.window.recorder import changed_settings
from app.window.timeline_host import TimelineHost
from app.window.speed import SETTLE_FRAMES, SpeedWatch  # noqa: F401 (tests import it here)
from app.window.views import HelpView, ShellView, WindowLike, safe, slow_text

if TYPE_CHECKING:
    from app.window.panel import ParamPanel

STEP_BUDGET_SECONDS = 0.1   # physics time per frame after which the frame's other steps are
                            # dropped (the window stays responsive; time runs slower)
PANEL_BACKGROUND = (21, 24, 29)
ERROR_TEXT = ("The scene stopped: {message}\n\nThe scene is paused and stays open: fix the code, "
              "then press R to run it again.")
ERROR_LINES = 12            # the HUD shows at most this many lines of an error (the terminal has
                            # the whole traceback)


class SceneView(CameraHost, TimelineHost, InstrumentHost, ShellView):
    """A running scene: its runner (stepping, timing, events, rollback), the fixed-step clock,
    the layout of world, HUD, metrics strip and panel, and the routing of input to the scene."""

    def __init__(self, window: WindowLike, scene: Scene, opened_with: dict[str, Any],
                 events: list[InputEvent] | None = None):
        super().__init__(window)
        self.scene = scene
        self.opened_with = dict(opened_with)
        self.runner = self.make_runner(events)
        self.clock = FixedStepClock()
        self.manager = None
        self.panel: ParamPanel | None = None
        self.panel_visible = window.panel_visible
        self.overlays = True                # F3 hides HUD and metrics
        self.banner = ""                    # the non-finite rollback's message (in the HUD)
        self.banner_short = ""              # the same in one line (the first page; F4: all)
        self.dragging: set[int] = set()     # mouse buttons pressed in the world area
        self.typed_keys: set[int] = set()   # keys pressed while typing into the panel
        self.setup_camera()                 # wheel zoom, middle-button pan (0 fits again)
        self.pane = Pane(scene, self.camera)   # the scene and its HUD in the world area
        self._notes_shown: tuple = ()       # the messages the HUD's room was made for
        self.speed = SpeedWatch()            # frames per second; why a frame dropped steps
        self._shown_ms: float | None = None          # the HUD's physics figure (physics_ms)
        self._ms_mark = 0                            # runner.steps when it was last read
        self.start_recording()
        self.setup_instruments(self.runners(), self.variant_texts())

    # --- what a comparison (compare_view.py) does otherwise ------------------------------------
    def make_runner(self, events: list[InputEvent] | None) -> SceneRunner:
        runner = SceneRunner(self.scene, events, rollback=True)
        runner.on_reset = self._after_rebuild
        return runner

    def runners(self) -> list[SceneRunner]:
        """Every pane's runner (one here)."""
        return [self.runner]

    def variant_texts(self) -> list[str] | None:
        return None

    def start_recording(self) -> None:
        self.window.recorder.start(self.scene.name, self.opened_with)

    # --- lifecycle ---------------------------------------------------------------------------
    def on_show(self) -> None:
        self.on_layout()

    def on_layout(self) -> None:
        """(Re)build the pygame-gui manager and the panel for the window's size and text size."""
        import pygame_gui
        from app.window.panel import ParamPanel
        size = self.window.screen.get_size()
        scale = panel_scale(self.panel_width, TEXT.scale) if self.panel_visible else TEXT.scale
        self.manager = pygame_gui.UIManager(size, theme_path=theme(scale))
        self.panel = None
        if self.panel_visible:
            area = self.world_area()
            self.panel = ParamPanel(self, self.manager, pygame.Rect(
                area.right, 0, size[0] - area.right, size[1]), scale)
        self.pane.forget()
        self.speed.restart()
        self.fit()

    @property
    def panel_width(self) -> int:     # (narrower at F2 in a small window: panel_size.py)
        return panel_width(self.window.screen.get_width(), TEXT.scale) if self.panel_visible \
            else 0

    def world_area(self) -> pygame.Rect:
        """The part of the window left of the panel, where the world is drawn."""
        w, h = self.window.screen.get_size()
        return pygame.Rect(0, 0, max(w - self.panel_width, 1), h)

    def fit(self, lines: list | None = None) -> Layout:
        """Fit the scene's content into the world area less the HUD (and, on its second page,
        the metrics strip); the HUD's room only grows until the next on_layout or message."""
        if self.overlays and lines is None:
            lines = self.hud_lines()
        notes = tuple(n.text for n in self.notes())
        if notes != self._notes_shown:      # a message came or went: the room is redone
            self._notes_shown = notes
            self.pane.forget()
        return self.pane.fit(self.scene_area(), lines if self.overlays else None,
                             strip=self.window.hud_details)

    def forget_layout(self) -> None:
        self.pane.forget()

    @property
    def layout(self) -> Layout | None:
        return self.pane.layout

    @property
    def view(self):
        return self.pane.layout.view

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
        """R: rebuild the scene (recorded as a key "r": the headless runner resets too)."""
        self.runner.clear_error()
        self.deliver(InputEvent("key_down", key="r"))
        self.deliver(InputEvent("key_up", key="r"))

    def toggle_help(self) -> None:
        self.window.show_view(HelpView(self.window, self))

    def toggle_overlays(self) -> None:
        self.overlays = not self.overlays
        self.pane.forget()
        self.fit()

    def toggle_details(self) -> None:
        """F4: the HUD's second page or its first (the window remembers it for every scene)."""
        self.window.hud_details = not self.window.hud_details
        self.pane.forget()
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
        topic = f"setting:{scene.canonical(name)}"
        before = scene.settings().get(scene.canonical(name))
        try:
            rebuilt = scene.set(name, value)
        except ParamError as e:
            w.flash(str(e), hud.ERROR_COLOR, topic=topic)
            self._refresh_panel()
            return False
        except SceneError as e:
            self.runner.fail(e)
            self.clock.paused = True
            return False
        except Exception as e:          # a broken scene must not take the room's window down
            traceback.print_exc()
            w.flash(f"{name}={value!r} failed: {type(e).__name__}: {e}", hud.ERROR_COLOR,
                    topic=topic)
            try:
                scene.set(name, before)
            except Exception:
                scene.reset()
            self._after_rebuild()
            return False
        after = scene.settings().get(scene.canonical(name))
        w.clear_messages(topic)            # the refusal it answers is out of date
        if rebuilt:
            self._after_rebuild()
        if after != before:
            # what was said about the old settings no longer holds: the blow-up and its advice,
            # the card's promise ("watch ..." is about the card's values)
            self.banner = ""
            w.clear_messages("card")
            self._recorded_change(scene.canonical(name), after)
        self._refresh_panel()
        return True

    def _recorded_change(self, name: str, value: Any) -> None:
        what = self.window.recorder.panel_change(name, value)
        if what == "restart":     # before the first press: start the recording from here
            self.scene.reset()
            self.runner = SceneRunner(self.scene, rollback=True)
            self.runner.on_reset = self._after_rebuild
            self.setup_instruments([self.runner])
            self.window.recorder.start(self.scene.name, changed_settings(self.scene))
            self.window.flash(f"recording restarted with {name}={value}: the replay starts "
                              "from here (given as --set)", hud.WARN_COLOR, topic="recording")
        elif what == "note":
            self.window.flash(f"recording: {name}={value} is a panel change after the first "
                              "press: the replay cannot repeat it (the exit message names it)",
                              hud.WARN_COLOR, topic="recording")

    def apply_try(self, card: Try) -> bool:
        """A "try this" card (a click, or --try in the window): the scene's defaults plus the
        card's settings, whatever ran or was set before (Scene.apply_card, as --headless --try
        does), rebuilt and running; the HUD says what the card set and what to watch for."""
        scene, w = self.scene, self.window
        if card.compare:                    # a comparison: its panes replace this view
            from app.compare import Variant
            from app.scene import variant_text
            return w.open_compare(type(scene), dict(card.settings),
                                  [Variant(variant_text(v), dict(v)) for v in card.compare], card)
        before = scene.settings()
        try:
            scene.apply_card(card)
        except ParamError as e:             # refused as a whole: nothing changed
            w.flash(f"{card.label}: {e}", hud.ERROR_COLOR, topic="card")
            return False
        except Exception as e:              # a broken scene must not take the window down
            traceback.print_exc()
            w.flash(f"{card.label} failed: {type(e).__name__}: {e}", hud.ERROR_COLOR,
                    topic="card")
            scene.reset()
            self._after_rebuild()
            return False
        self.runner.clear_error()
        self._after_rebuild()               # a new world: snapshots, timings, the banner go
        w.clear_messages("setting:", "card")
        self.clock.paused = False           # an experiment from a fresh start, running
        self.clock.accumulator = 0.0
        if scene.settings() != before:
            self._recorded_change("card", card.label)
        w.flash(f"Try: {card.label} ({card.changes()}): {card.watch}", hud.ACCENT_COLOR,
                seconds=12.0, topic="card")
        if self.panel is not None:
            self.panel.show_watch(card)
        return True

    def _after_rebuild(self) -> None:
        """The scene was (re)built: new snapshot and timings (the runner), fresh banner."""
        self.banner = ""
        self.runner.rebuilt()
        self._shown_ms = None           # the old world's timings go with it
        self.dragging.clear()
        self._refresh_panel()

    def _refresh_panel(self) -> None:
        if self.panel is not None:
            self.panel = self.panel.refreshed()   # built anew if the scene's form changed shape

    # --- events --------------------------------------------------------------------------------
    def typing(self) -> bool:
        """True while a text box of the panel has the keyboard: then no key goes anywhere else."""
        if self.panel is not None and self.panel.is_typing():
            return True
        focus = self.manager.get_focus_set() if self.manager is not None else None
        return any(type(e).__name__ == "UITextEntryLine" for e in (focus or ()))

    def handle_event(self, ev: pygame.event.Event) -> None:
        if self.panel is not None and self.panel.took_escape(ev):
            return                          # Esc cancelled the panel's prompt or field
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
        if self.camera_event(ev, consumed):
            return
        if ev.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP, pygame.MOUSEMOTION):
            self._mouse_event(ev, consumed)
            self.pane_hold()

    def _mouse_event(self, ev: pygame.event.Event, consumed: bool) -> None:
        if consumed or not self.timeline_mouse(ev):      # a click on the scrub bar is its own
            self._world_mouse(ev, consumed)

    def _world_mouse(self, ev: pygame.event.Event, consumed: bool) -> None:
        in_world = self.scene_area().collidepoint(ev.pos) and not consumed
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
        self.speed.frame(self.window.wall)
        if self.manager is not None:
            self.manager.update(frame_seconds)
        self._refresh_panel()
        dropped_before = self.clock.dropped_steps
        n = self.clock.steps_for_frame(frame_seconds, self.scene.dt)
        capped = self.clock.dropped_steps > dropped_before       # the loop's cap dropped some
        t0 = time.perf_counter()
        ran, rollback = self.runner.run(n, STEP_BUDGET_SECONDS)
        physics = time.perf_counter() - t0
        self.inst.sample()
        if rollback is not None:
            self.clock.paused = True
            self.clock.accumulator = 0.0
            self.dragging.clear()
            self.banner, self.banner_short = rollback.text(), rollback.short_text()
            self.speed.restart(forget=True)    # undone steps: not "slower than real time"
            self._refresh_panel()
        elif self.runner.error is not None:
            self.clock.paused = True
        elif ran < n:
            self.clock.dropped_steps += n - ran      # the rest would freeze the window
        self.window.recorder.steps_run(self.runner.steps)
        self.speed.watch(self.window.wall, frame_seconds, physics, self.window.last_draw_seconds,
                         self.clock.dropped_steps > dropped_before, capped, self.clock, self.scene)
        return ran

    # --- what the HUD reads --------------------------------------------------------------------
    @property
    def fps(self) -> float:
        return self.speed.fps

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
        """The shell's lines of the HUD box: one line of time, step, cost and frame rate; then,
        only when they apply, pause and slow motion, recording, slower than real time."""
        scene = self.scene
        self._costs = safe(scene.effect_costs, {})     # read with physics_ms: the same steps
        return [f"t = {scene.time:.2f} s | {hud.dt_text(scene)} | "
                f"{hud.physics_text(self.physics_ms())}"] + self.state_lines()

    def state_lines(self) -> list:
        """The status lines that apply only sometimes: paused, slow motion, recording, slower
        than real time."""
        L, clock = hud.Line, self.clock
        lines: list = []
        state = []
        if clock.paused:
            state.append("PAUSED (Space resumes, . steps)")
        if clock.slow_motion != 1.0:
            state.append(f"speed x{slow_text(clock.slow_motion)} (- slower, = faster)")
        state += self.zoom_state()
        if state:
            lines.append(L("  |  ".join(state), hud.WARN_COLOR))
        if self.window.recorder.active:
            lines.append(L(f"REC  recording to {self.window.recorder.path} (the replay command is "
                           "printed on exit)", hud.ERROR_COLOR))
        slow = self.speed.line(self.window.wall)
        if slow:
            lines.append(L(slow, hud.WARN_COLOR))
        return lines

    def detail_lines(self) -> list:
        """The shell's lines on the HUD's second page: the physics cost by effect, the frame
        rate, the timeline's span and cost."""
        costs, tl = getattr(self, "_costs", {}), self.runner.timeline
        return ([hud.physics_line(self._shown_ms, costs)] if costs else []) + [
            f"{self.fps:.0f} frames per second (drawing {1000 * self.window.last_draw_seconds:.1f}"
            " ms a frame)"] + ([tl.text()] if tl is not None else [])

    def notes(self) -> list:
        """The messages, as HUD lines: the scene's error, the rollback's advice, then the
        window's passing messages (newest last; a card's "Try:" only with the panel hidden:
        the panel shows it under the cards)."""
        lines = []
        if self.runner.error is not None and not self.scene.draws_own_error:
            text = ERROR_TEXT.format(message=self.runner.error).split("\n")
            if len(text) > ERROR_LINES:
                text = text[:ERROR_LINES - 1] + [f"... ({len(text) - ERROR_LINES + 1} more lines "
                                                 "in the terminal)"]
            lines.append(hud.Line("\n".join(text), hud.ERROR_COLOR))
        if self.banner:
            short = getattr(self, "banner_short", "") if not self.window.hud_details else ""
            lines.append(hud.Line(short or self.banner, hud.WARN_COLOR))
        lines += self.timeline_notes()
        # a card's promise is in the panel's box under the cards while the panel is shown
        shown_there = self.panel is not None and self.panel.watch_box is not None
        return lines + [hud.Line(m.text, m.color) for m in self.window.messages
                        if not (shown_there and m.topic == "card" and m.text.startswith("Try: "))
                        ] + self.inst.legend()

    def hud_lines(self) -> list:
        """Everything in the HUD box, as drawn."""
        status = self.status_lines()
        details = self.window.hud_details
        return hud.scene_lines(self.scene, status, self.notes(), details,
                               self.detail_lines() if details else ())

    # --- drawing -------------------------------------------------------------------------------
    def draw(self, screen: pygame.Surface) -> None:
        scene = self.scene
        try:
            lines = self.hud_lines() if self.overlays else None
        except SceneError as e:
            self.runner.fail(e)
            self.clock.paused = True
            lines = None
        layout = self.fit(lines)
        screen.fill(PANEL_BACKGROUND)
        self.inst.update_scale()
        overlay = (lambda s, lay: self.inst.overlay(s, 0, lay)) if self.inst.arrows else None
        try:
            draw_scene(screen, layout, scene, lines, strip=self.window.hud_details,
                       overlay=overlay)
        except SceneError as e:
            self.runner.fail(e)
            self.clock.paused = True
            screen.fill(scene.background, layout.area)
        self.draw_over(screen, layout)
        self.draw_chrome(screen)

    def draw_chrome(self, screen: pygame.Surface) -> None:
        """What every view draws over its scene area: the live plot, the panel's background and
        edge, the panel's widgets."""
        self.draw_plot(screen)
        if self.panel is not None:
            screen.fill(PANEL_BACKGROUND, self.panel.rect)
            pygame.draw.line(screen, (60, 66, 76), self.panel.rect.topleft,
                             self.panel.rect.bottomleft, 2)
        if self.manager is not None:
            self.manager.draw_ui(screen)

