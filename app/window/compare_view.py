"""The view of a comparison: two to four variants of one scene side by side, in lockstep
(app/compare.py), drawn as a header and a pane per variant (app/draw/panes.py).

What differs from the view of one scene (scene_view.py, which this extends):
  * one CompareRunner steps every pane on one clock; a pane that blows up is rolled back and
    held, its pane saying why and what to try, while the others go on; R restarts them all
    from the same state;
  * the mouse: a press on any pane is turned into world coordinates by that pane's view and
    delivered to every pane (a drag keeps the pane it began in), so one gesture reaches all;
  * the panel edits "every pane" (a setting the panes share; one they differ in is locked
    there) or one pane's own settings (picked at the top of the panel). A change that rebuilds a
    scene restarts every pane, so they keep starting from the same state;
  * a "try this" card that is a comparison opens its panes; a plain card is applied to every
    pane, each keeping what it differs in.
"""

from __future__ import annotations

import time
from typing import Any

import pygame

from app.compare import CompareRunner, Variant, as_variant, differing, labels, shared_and_own
from app.draw import hud
from app.draw.energy_bars import draw_energy
from app.draw.panes import PaneGrid
from app.frames import compare_header, compare_pane_lines
from app.scene import InputEvent, ParamError, Scene, SceneError, Try
from app.window.scene_view import PANEL_BACKGROUND, STEP_BUDGET_SECONDS, SceneView

EVERY_PANE = "every pane"


class CompareView(SceneView):
    """Several scenes in lockstep; `scene` is the one the panel shows (pane A for every pane)."""

    def __init__(self, window, scenes: list[Scene], shared: dict[str, Any],
                 variants: list[Variant], events: list[InputEvent] | None = None):
        self.scenes = list(scenes)
        self.variants = list(variants)
        self.target: int | None = None          # the panel edits every pane (None) or pane k
        self.drag_pane: int | None = None        # the pane a drag began in
        super().__init__(window, scenes[0], shared, events)
        self.grid = PaneGrid(self.scenes, self.camera)
        self.pane = self.grid                    # forget() and layout, as the view uses them

    # --- the hooks of SceneView --------------------------------------------------------------
    def make_runner(self, events: list[InputEvent] | None) -> CompareRunner:
        return CompareRunner(self.scenes, events, rollback=True)

    def runners(self) -> list:
        return self.runner.runners

    def variant_texts(self) -> list[str]:
        return [v.text for v in self.variants]

    def start_recording(self) -> None:
        shared, own = shared_and_own(self.scenes)
        self.window.recorder.start(self.scene.name, shared, [as_variant(o) for o in own])

    # --- the panel's target --------------------------------------------------------------------
    def targets(self) -> list[str]:
        """The panel's choices: every pane, then each pane by its tag and label."""
        return [EVERY_PANE] + [f"{'ABCD'[k]}: {lab}" for k, lab in enumerate(labels(self.scenes))]

    def target_index(self) -> int:
        return 0 if self.target is None else self.target + 1

    def set_target(self, index: int) -> None:
        self.target = None if index <= 0 else index - 1
        self.scene = self.scenes[self.target or 0]
        self.on_layout()

    def locked_settings(self) -> set[str]:
        """Settings the panel cannot change for every pane: those the panes differ in."""
        return set(differing(self.scenes)) if self.target is None else set()

    # --- layout and drawing --------------------------------------------------------------------
    def header_lines(self) -> list:
        zoom = f"zoom x{self.camera.zoom:.2g} (0 fits)" if not self.camera.fitted else ""
        return compare_header(self.scenes, self.runner.world, self.state_lines(), self.notes(),
                              zoom)

    def zoom_state(self) -> list[str]:
        """The zoom is said on the header's first line (a line of its own made the header a row
        taller and re-fitted every pane under the pointer as the wheel turned)."""
        return []

    def pane_lines(self, brief: bool = False) -> list[list]:
        details = self.window.hud_details
        more = [f"{self.fps:.0f} frames per second (drawing "
                f"{1000 * self.window.last_draw_seconds:.1f} ms a frame)"] if details else []
        return compare_pane_lines(self.runner.runners, None, details, more, self.runner.held,
                                  brief=brief, headlines=self.runner.held_headline)

    def fit(self, lines: list | None = None):
        if not self.overlays:
            return self.grid.fit(self.scene_area(), None, [None] * len(self.scenes))
        header = self.header_lines()
        notes = tuple(getattr(n, "text", str(n)) for n in header[1:])   # (not the clock)
        if notes != self._notes_shown:          # a message came or went: redo the rooms
            self._notes_shown = notes
            self.grid.forget()
        return self.grid.fit(self.scene_area(), header, lines or self.pane_lines(),
                             self.window.hud_details, self.pane_lines(brief=True))

    def draw(self, screen: pygame.Surface) -> None:
        try:
            header = self.header_lines() if self.overlays else None
            lines = self.pane_lines() if self.overlays else [None] * len(self.scenes)
        except SceneError as e:                 # a student's scene failed in its HUD text
            self._fail_all(e)
            header, lines = None, [None] * len(self.scenes)
        self.fit(lines if self.overlays else None)
        self.sync_watch()                      # B: a pane's blow-up goes on for a second too
        screen.fill(PANEL_BACKGROUND)
        self.inst.update_scale()
        try:
            layouts = self.grid.draw(screen, self.scene_area(), header, lines,
                                     self.window.hud_details,
                                     self.inst.overlay if self.inst.arrows else None,
                                     self.pane_lines(brief=True) if self.overlays else None,
                                     self.target)
            if self.window.energy_bars:
                for scene, layout in zip(self.scenes, layouts):
                    draw_energy(screen, scene, layout, 20)
        except SceneError as e:
            self._fail_all(e)
        self.draw_chrome(screen)

    def _fail_all(self, error: SceneError) -> None:
        for r in self.runner.runners:
            r.fail(error)
        self.clock.paused = True

    def notes(self) -> list:
        """The header's messages: the window's passing ones and the arrows' legend (a pane's
        own, a blow-up or an error, are in its pane)."""
        shown_there = self.panel is not None and self.panel.watch_box is not None
        return [hud.Line(m.text, m.color) for m in self.window.messages
                if not (shown_there and m.topic == "card" and m.text.startswith("Try: "))
                ] + self.inst.legend()

    # --- time ----------------------------------------------------------------------------------
    def update(self, frame_seconds: float) -> int:
        """One frame: the panel, then the ticks the clock grants (every pane steps to the same
        time), within the step budget; a pane that blew up is held, the others go on."""
        self.speed.frame(self.window.wall)
        if self.manager is not None:
            self.manager.update(frame_seconds)
        self._refresh_panel()
        dropped_before = self.clock.dropped_steps
        n = self.clock.steps_for_frame(frame_seconds, self.runner.tick)
        capped = self.clock.dropped_steps > dropped_before
        t0 = time.perf_counter()
        ran, rollbacks = self.runner.run(n, STEP_BUDGET_SECONDS)
        physics = time.perf_counter() - t0
        self.inst.sample()
        if rollbacks:
            self.dragging.clear()
            self.grid.forget()
            self._refresh_panel()
        if self.runner.stopped:
            self.clock.paused = True
        elif ran < n:
            self.clock.dropped_steps += n - ran
        self.window.recorder.steps_run(self.runner.steps)
        self.speed.watch(self.window.wall, frame_seconds, physics, self.window.last_draw_seconds,
                         self.clock.dropped_steps > dropped_before, capped, self.clock, self.scene,
                         scene_speaks=False)
        return ran

    def replay_blowup(self) -> None:
        """N: a pane's blow-up is held in its pane; the replay is one scene's (say so)."""
        self.window.flash("N (a blow-up's last second again) is for one scene at a time",
                          topic="timeline")

    def _scrub(self, key: str, times: int = 1) -> None:
        """[ and ]: the timeline keeps one scene's run, not a comparison's (it would cost every
        pane its snapshots): say so."""
        self.window.flash("the timeline ([ ]) is for one scene at a time; compare mode keeps "
                          "none", topic="timeline")

    def toggle_pause(self) -> None:
        self.clock.toggle_pause()

    def reset(self) -> None:
        """R: every pane starts again from the same state (held panes too)."""
        self.runner.clear_error()
        self.deliver(InputEvent("key_down", key="r"))
        self.deliver(InputEvent("key_up", key="r"))

    def _after_rebuild(self) -> None:
        self.banner = ""
        self.runner.restart(rebuild=False)
        self.dragging.clear()
        self.drag_pane = None
        self.grid.forget()
        self._refresh_panel()

    # --- the mouse -----------------------------------------------------------------------------
    def layout_at(self, pos):
        """The layout of the pane under `pos` (its view zooms and pans every pane alike)."""
        k = self.grid.pane_at(pos) if self.scene_area().collidepoint(pos) else None
        return self.grid.panes[k].layout if k is not None else None

    def _mouse_event(self, ev: pygame.event.Event, consumed: bool) -> None:
        """A press on any pane, in that pane's world coordinates, to every pane."""
        k = self.grid.pane_at(ev.pos) if not consumed else None
        if k is not None and not self.scene_area().collidepoint(ev.pos):
            k = None
        if self.dragging and self.drag_pane is not None:
            k_view = self.drag_pane             # a drag stays in the pane it began in
        else:
            k_view = k if k is not None else 0
        layout = self.grid.panes[k_view].layout
        if layout is None:
            return
        x, y = layout.view.to_world(ev.pos)
        world = (round(x, 2), round(y, 2))
        if ev.type == pygame.MOUSEBUTTONDOWN and ev.button in (1, 3) and k is not None:
            if not self.dragging:
                self.drag_pane = k
            self.dragging.add(ev.button)
            self.deliver(InputEvent("mouse_down", pos=world, button=ev.button))
            if ev.button == 1:
                self._say_who_caught(k)
        elif ev.type == pygame.MOUSEBUTTONUP and ev.button in (1, 3) and (
                ev.button in self.dragging or k is not None):
            self.dragging.discard(ev.button)
            if not self.dragging:
                self.drag_pane = None
            self.deliver(InputEvent("mouse_up", pos=world, button=ev.button))
        elif ev.type == pygame.MOUSEMOTION and (k is not None or self.dragging):
            self.deliver(InputEvent("mouse_move", pos=world))

    def _say_who_caught(self, k: int) -> None:
        """A press reaches every pane at the same world point; a pane whose cloth has sagged or
        swung elsewhere catches nothing there. Say so (it was silent): which panes caught it."""
        caught = [_grabbing(s) for s in self.scenes]
        if None in caught or all(caught) or not any(caught):
            return                              # not a cloth, or every pane alike
        tags = "ABCD"
        yes = ", ".join(tags[j] for j, c in enumerate(caught) if c)
        no = ", ".join(tags[j] for j, c in enumerate(caught) if not c)
        self.window.flash(f"the press caught the cloth in {yes} only: in {no} it is not under "
                          "that point (every pane gets the same world point)", hud.WARN_COLOR,
                          topic="drag")

    # --- settings ------------------------------------------------------------------------------
    def apply_setting(self, name: str, value: Any) -> bool:
        """The panel: change `name` in the pane picked at its top, or in every pane (not a
        setting the panes differ in). Checked in every pane concerned before any changes; a
        change that rebuilds a scene restarts every pane (the same start for all)."""
        w = self.window
        cls = type(self.scene)
        key = cls.canonical(name)
        topic = f"setting:{key}"
        panes = self.scenes if self.target is None else [self.scenes[self.target]]
        if self.target is None and key in differing(self.scenes):
            w.flash(f"{key} is what the panes differ in: pick a pane at the top of the panel to "
                    "change it there", hud.ERROR_COLOR, topic=topic)
            self._refresh_panel()
            return False
        try:
            parsed = cls.check_setting(name, value)
            if cls.param(key) is not None:
                for s in panes:
                    cls.check_combination({**s.p, key: parsed})
        except ParamError as e:
            w.flash(str(e), hud.ERROR_COLOR, topic=topic)
            self._refresh_panel()
            return False
        before = [s.settings().get(key) for s in panes]
        try:
            rebuilt = [s.set(name, value) for s in panes]
        except SceneError as e:
            self._fail_all(e)
            return False
        w.clear_messages(topic)
        if any(rebuilt):
            self.runner.restart(rebuild=True)    # every pane from the same state again
            self._after_rebuild()
        if [s.settings().get(key) for s in panes] != before:
            w.clear_messages("card")
            self._recorded_change(key, value)
            self.grid.forget()
        self._refresh_panel()
        return True

    def _recorded_change(self, name: str, value: Any) -> None:
        what = self.window.recorder.panel_change(name, value)
        if what == "restart":     # before the first press: the replay starts from these values
            self.runner.restart(rebuild=True)
            self._after_rebuild()
            self.start_recording()
            self.window.flash(f"recording restarted with {name}={value}: the replay starts "
                              "from here (given as --set and --compare)", hud.WARN_COLOR,
                              topic="recording")
        elif what == "note":
            self.window.flash(f"recording: {name}={value} is a panel change after the first "
                              "press: the replay cannot repeat it (the exit message names it)",
                              hud.WARN_COLOR, topic="recording")

    def apply_try(self, card: Try) -> bool:
        """A comparison card opens its panes; a plain card goes to every pane (the defaults plus
        the card), each pane keeping what it differs in."""
        if card.compare:
            return super().apply_try(card)
        _, own = shared_and_own(self.scenes)
        clash = [k for k in card.settings if type(self.scene).canonical(k) in (own[0] or {})]
        if clash:
            self.window.flash(f"{card.label}: it sets {clash[0]}, which is what the panes "
                              "compare; open the scene alone (PageUp, PageDown) to try it",
                              hud.ERROR_COLOR, topic="card")
            return False
        return self.window.open_compare(type(self.scene), dict(card.settings),
                                        [Variant(as_variant(o), o) for o in own], card)


def _grabbing(scene: Scene) -> bool | None:
    """Whether a cloth scene holds a particle under the mouse now (None: not a cloth)."""
    cloth = getattr(scene, "cloth", None)
    return None if cloth is None or not hasattr(cloth, "grabbed") else cloth.grabbed is not None


__all__ = ["CompareView", "EVERY_PANE"]
