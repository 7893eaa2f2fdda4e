"""The interactive window, driven without its main loop (SDL dummy driver, see conftest.py).

A tiny scene defined here (not registered) stands in for the real ones: a particle falling under
gravity, with an int param, a float param, a choice, a bool and two effects. The tests press keys
and type values the way a user would, by posting pygame events or pygame-gui events to
Window.handle_pygame_event, and check what the shell did to the scene.
"""

from __future__ import annotations

import json

import numpy as np
import pygame
import pygame_gui
import pytest

from app.draw.text import TEXT
from app.scene import Effect, InputEvent, Param, Scene
from app.window import NONFINITE_TEXT, SNAPSHOT_EVERY, Window, run_window


class Tiny(Scene):
    """A point falling under gravity (window test scene).

    U kicks it upwards.
    """

    name = "tiny"
    title = "Tiny test scene"
    category = "Test"
    params = (
        Param("count", 3, int, 1, 20, help="number of points"),
        Param("g", 100.0, float, 0.0, 1000.0, help="gravity", rebuild=False),
        Param("method", "euler", str, choices=("euler", "verlet"), rebuild=False),
        Param("blowup", False, bool, help="go NaN at step 40", rebuild=False),
    )
    effects = (Effect("gravity"), Effect("drag", False))

    def build(self):
        n = self.p["count"]
        self.x = np.zeros((n, 2)) + (100.0, 100.0)
        self.v = np.zeros((n, 2))
        self.seen: list[InputEvent] = []

    def step(self, h):
        if "gravity" in self.on:
            self.v[:, 1] += self.p["g"] * h
        self.x += self.v * h
        if self.p["blowup"] and self.steps >= 40:
            self.x[0, 0] = np.nan

    def handle_event(self, event):
        self.seen.append(event)
        if event.kind == "key_down" and event.key == "u":
            self.v[:, 1] -= 50.0
        if event.kind == "mouse_down":
            self.x[0] = event.pos

    def draw(self, surface, view):
        for p in self.x:
            if np.isfinite(p).all():
                pygame.draw.circle(surface, (200, 200, 255), view.pt(p), int(view.len(5)) + 1)

    def metrics(self):
        return {"y": float(self.x[0, 1]), "n": len(self.x)}

    def state_arrays(self):
        return (self.x, self.v)

    def snapshot(self):
        return (self.x.copy(), self.v.copy())

    def restore(self, snap):
        if snap is None:
            self.reset()
        else:
            self.x, self.v = snap[0].copy(), snap[1].copy()


class Other(Tiny):
    """A second scene, for switching."""
    name = "other"
    title = "Other"


@pytest.fixture
def window(tmp_path):
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    w = Window(screen, [Tiny, Other], screenshot_dir=tmp_path / "shots")
    assert w.open_scene(Tiny)
    yield w
    TEXT.scale = 1.0


def key(w: Window, k: int, up: bool = True) -> None:
    name = pygame.key.name(k)
    w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, scancode=0,
                                             unicode=name if len(name) == 1 else ""))
    if up:
        w.handle_pygame_event(pygame.event.Event(pygame.KEYUP, key=k, mod=0, scancode=0,
                                                 unicode=""))


def mouse(w: Window, kind: int, pos, button: int = 1) -> None:
    if kind == pygame.MOUSEMOTION:
        ev = pygame.event.Event(kind, pos=pos, rel=(0, 0), buttons=(0, 0, 0))
    else:
        ev = pygame.event.Event(kind, pos=pos, button=button)
    w.handle_pygame_event(ev)


def type_into(panel, name: str, text: str) -> bool:
    """Type `text` into the panel's box for `name` and press Enter."""
    entry = panel.entries[name]
    entry.set_text(text)
    return panel.handle(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                           {"text": text, "ui_element": entry}))


def test_space_pauses_and_resumes(window):
    window.update(0.05)
    steps = window.scene.steps
    assert steps == 3                      # 0.05 s at 60 Hz
    key(window, pygame.K_SPACE)
    assert window.clock.paused
    window.update(0.5)
    assert window.scene.steps == steps
    key(window, pygame.K_SPACE)
    window.update(0.05)
    assert window.scene.steps == steps + 3


def test_period_single_steps_exactly_one(window):
    key(window, pygame.K_PERIOD)           # pauses and asks for one step
    assert window.update(0.1) == 1
    assert window.update(0.1) == 0
    assert window.scene.steps == 1
    key(window, pygame.K_PERIOD)
    window.update(0.0)
    assert window.scene.steps == 2
    assert window.scene.time == pytest.approx(2 / 60)


def test_minus_is_slow_motion_not_a_smaller_dt(window):
    dt = window.scene.dt
    key(window, pygame.K_MINUS)
    assert window.clock.slow_motion == 0.5
    assert window.scene.dt == dt
    assert window.update(0.1) == 3         # 0.1 s of frames = 0.05 s simulated = 3 steps of dt
    key(window, pygame.K_MINUS)
    key(window, pygame.K_MINUS)
    key(window, pygame.K_MINUS)
    assert window.clock.slow_motion == 0.125
    key(window, pygame.K_EQUALS)
    assert window.clock.slow_motion == 0.25
    assert "speed x1/4" in " ".join(str(getattr(l, "text", l)) for l in window.hud_lines())


def test_r_resets(window):
    window.update(0.1)
    window.scene.x[:] = 500.0
    key(window, pygame.K_r)
    assert window.scene.time == 0.0 and window.scene.steps == 0
    assert window.scene.x[0, 0] == 100.0


def test_f2_toggles_large_text_and_widens_the_panel(window):
    narrow = window.panel.rect.width
    key(window, pygame.K_F2)
    assert TEXT.scale == pytest.approx(1.6)
    assert window.panel.rect.width > narrow
    window.render()
    key(window, pygame.K_F2)
    assert TEXT.scale == 1.0
    assert window.panel.rect.width == narrow


def test_bad_typed_value_is_refused_and_the_old_one_kept(window):
    panel = window.panel
    for bad in ("abc", "nan", "inf", "99", "2.5", ""):
        type_into(panel, "count", bad)
        assert window.scene.p["count"] == 3
        assert panel.entries["count"].get_text() == "3"
    assert any("count" in text for _, text, _ in window.messages)
    type_into(panel, "g", "-1")
    assert window.scene.p["g"] == 100.0
    window.render()                        # the error banner draws without trouble


def test_valid_values_change_the_scene(window):
    panel = window.panel
    window.update(0.1)
    type_into(panel, "g", "250.5")
    assert window.scene.p["g"] == 250.5
    assert window.scene.steps > 0          # g does not rebuild
    type_into(panel, "count", "7")
    assert window.scene.p["count"] == 7
    assert len(window.scene.x) == 7 and window.scene.steps == 0   # count rebuilds
    # the slider snaps an int param to integers
    ctl = panel.numbers["count"]
    for pos, expected in ((1000, 20), (0, 1), (500, 10)):      # 1 + 19 * 0.5 = 10.5 -> 10
        window.handle_pygame_event(pygame.event.Event(
            pygame_gui.UI_HORIZONTAL_SLIDER_MOVED, {"value": pos, "ui_element": ctl.slider}))
        assert window.scene.p["count"] == expected and isinstance(window.scene.p["count"], int)
    # choices, bool params and effects
    window.handle_pygame_event(pygame.event.Event(
        pygame_gui.UI_DROP_DOWN_MENU_CHANGED,
        {"text": "verlet", "ui_element": panel.dropdowns["method"]}))
    assert window.scene.p["method"] == "verlet"
    window.handle_pygame_event(pygame.event.Event(
        pygame_gui.UI_BUTTON_PRESSED, {"ui_element": panel.toggles["drag"]}))
    assert "drag" in window.scene.on
    window.handle_pygame_event(pygame.event.Event(
        pygame_gui.UI_BUTTON_PRESSED, {"ui_element": panel.toggles["gravity"]}))
    assert "gravity" not in window.scene.on


def test_keys_typed_into_the_panel_do_not_reach_the_shell(window):
    window.update(0.1)
    steps = window.scene.steps
    window.panel.entries["g"].focus()
    key(window, pygame.K_r)
    key(window, pygame.K_SPACE)
    assert window.scene.steps == steps and not window.clock.paused


def test_non_finite_state_rolls_back_and_pauses(window):
    window.scene.set("blowup", True)
    for _ in range(100):
        window.update(1 / 60)
        if window.clock.paused:
            break
    scene = window.scene
    assert window.clock.paused
    assert scene.is_finite()
    assert scene.steps == SNAPSHOT_EVERY
    assert scene.time == pytest.approx(SNAPSHOT_EVERY / 60)
    assert window.nonfinite_banner.startswith("The simulation went non-finite")
    assert window.nonfinite_banner == NONFINITE_TEXT.format(bad=41 / 60, good=30 / 60)
    window.render()
    key(window, pygame.K_SPACE)            # resuming clears the banner
    assert not window.nonfinite_banner


def test_recording_writes_input_json_in_world_coordinates(window, tmp_path):
    # a smaller window: the world is drawn at half size, so screen and world pixels differ
    window.resize(pygame.display.set_mode((800, 600)))
    view = window.view
    assert view.scale < 1
    window.update(0.1)
    start = view.pt((100.0, 200.0))
    end = view.pt((300.0, 250.0))
    mouse(window, pygame.MOUSEBUTTONDOWN, start, 1)
    mouse(window, pygame.MOUSEMOTION, end)
    mouse(window, pygame.MOUSEBUTTONUP, end, 1)
    key(window, pygame.K_u)
    key(window, pygame.K_SPACE)            # a shell key: not the scene's, not recorded
    mouse(window, pygame.MOUSEBUTTONDOWN, (790, 300), 1)   # over the panel: not recorded
    out = tmp_path / "rec.json"
    assert window.write_recording(out) == 5
    events = json.loads(out.read_text())
    assert [e["type"] for e in events] == ["mouse_down", "mouse_move", "mouse_up",
                                           "key_down", "key_up"]
    tol = 1.0 / view.scale
    assert events[0]["pos"] == pytest.approx([100.0, 200.0], abs=tol)
    assert events[0]["button"] == 1
    assert events[2]["pos"] == pytest.approx([300.0, 250.0], abs=tol)
    assert events[3]["key"] == "u"
    assert all(e["t"] == pytest.approx(6 / 60) for e in events)
    from app.headless import parse_events
    assert [e.to_json() for e in parse_events(events)] == events     # the --input format
    assert window.scene.seen[0].pos == pytest.approx((100.0, 200.0), abs=tol)


def test_a_recorded_demo_replays_headless_to_the_same_state(window, tmp_path):
    from app.headless import load_events, run_scene
    window.update(0.05)
    mouse(window, pygame.MOUSEBUTTONDOWN, window.view.pt((400.0, 300.0)), 1)
    window.update(0.05)
    key(window, pygame.K_u)
    window.update(0.1)
    key(window, pygame.K_r)                # recorded as a reset
    window.update(0.05)
    mouse(window, pygame.MOUSEBUTTONDOWN, window.view.pt((50.0, 60.0)), 3)
    key(window, pygame.K_u)
    window.update(0.1)
    out = tmp_path / "demo.json"
    window.write_recording(out)
    replay = run_scene(Tiny(), window.session_steps, load_events(str(out)))
    assert replay.scene.state_hash() == window.scene.state_hash()
    assert replay.scene.time == pytest.approx(window.scene.time)


def test_replayed_events_reach_the_scene_at_their_time(tmp_path):
    pygame.display.init()
    screen = pygame.display.set_mode((1280, 800))
    w = Window(screen, [Tiny], events=[InputEvent("key_down", key="u", t=0.05)],
               screenshot_dir=tmp_path)
    w.open_scene(Tiny)
    w.update(0.02)
    assert not w.scene.seen
    w.update(0.1)
    assert [e.key for e in w.scene.seen] == ["u"]
    assert w.recorded == []                # replayed events are not the user's


def test_f12_writes_a_png(window, tmp_path):
    key(window, pygame.K_F12)
    window.render()
    shots = list((tmp_path / "shots").glob("tiny-*.png"))
    assert len(shots) == 1
    assert pygame.image.load(str(shots[0])).get_size() == (1280, 800)
    assert any("screenshot saved" in text for _, text, _ in window.messages)


def test_help_menu_and_scene_switching(window):
    key(window, pygame.K_h)
    assert window.show_help
    window.render()
    key(window, pygame.K_ESCAPE)           # closes the help first
    assert not window.show_help and window.scene is not None
    key(window, pygame.K_PAGEDOWN)
    assert type(window.scene) is Other
    key(window, pygame.K_ESCAPE)
    assert window.scene is None
    window.render()
    key(window, pygame.K_1)
    assert type(window.scene) is Tiny
    key(window, pygame.K_TAB)
    assert window.panel is None and window.world_area().width == 1280
    key(window, pygame.K_ESCAPE)
    key(window, pygame.K_ESCAPE)           # Esc in the menu quits
    assert not window.running


def test_a_scene_that_fails_to_build_shows_the_error(window):
    assert not window.open_scene(Tiny, {"count": "999"})
    assert window.scene is None
    assert "count" in window.menu_message
    window.render()


def test_no_display_returns_2_with_one_line(monkeypatch, capsys):
    def refuse(*args, **kwargs):
        raise pygame.error("x11 not available")
    monkeypatch.setattr(pygame.display, "set_mode", refuse)
    assert run_window(None, {}) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert err.startswith("no display for the window: x11 not available; use --headless")


def test_run_window_screenshot_after_seconds_and_record(monkeypatch, tmp_path):
    import scenes
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    shot, rec = tmp_path / "w.png", tmp_path / "rec.json"
    assert run_window("tiny", {"g": "50"}, record=str(rec), screenshot=str(shot),
                      seconds=0.2) == 0
    assert pygame.image.load(str(shot)).get_size() == (1280, 800)
    assert json.loads(rec.read_text()) == []


def test_typing_a_value_and_enter_sets_it(window):
    entry = window.panel.entries["g"]
    entry.focus()
    entry.set_text("")
    pygame.event.clear()
    window.handle_pygame_event(pygame.event.Event(pygame.TEXTINPUT, text="42"))
    key(window, pygame.K_RETURN)
    for ev in pygame.event.get():          # pygame-gui posts UI_TEXT_ENTRY_FINISHED
        window.handle_pygame_event(ev)
    assert window.scene.p["g"] == 42.0
    assert not window.panel.is_typing()


@pytest.mark.parametrize("frames", [[1 / 60] * 40, [0.013, 0.021, 1 / 60, 0.03, 0.011] * 8])
def test_a_demo_recorded_frame_by_frame_on_the_cloth_replays_to_the_same_state(tmp_path, frames):
    """The --record -> --input promise on a real scene, with ordinary 1/60 s and uneven frames
    (times like 0.016667 s must land on the step they were recorded at)."""
    from app.headless import load_events, run_scene
    from scenes.cloth import ClothScene
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1000, 700))      # zoom below 1: window px != world px
    w = Window(screen, [ClothScene], screenshot_dir=tmp_path)
    assert w.open_scene(ClothScene, {"rows": "12", "cols": "12"})
    cloth = w.scene.cloth
    grab = w.view.pt(cloth.x[:, 5, 6])
    script = {3: (pygame.MOUSEMOTION, grab), 5: (pygame.MOUSEBUTTONDOWN, grab)}
    for i in range(6, 20):
        script[i] = (pygame.MOUSEMOTION, (grab[0] + 9 * (i - 5), grab[1] + 6 * (i - 5)))
    script[21] = (pygame.MOUSEBUTTONUP, script[19][1])
    for i, frame in enumerate(frames):
        if i in script:
            mouse(w, *script[i])
        if i == 30:
            key(w, pygame.K_u)
        w.update(frame)
    assert w.scene.cloth.locked.sum() == 12                 # dropped, then U: default pins
    out = tmp_path / "demo.json"
    w.write_recording(out)
    replay = run_scene(ClothScene({"rows": 12, "cols": 12}), w.session_steps, load_events(str(out)))
    assert replay.scene.state_hash() == w.scene.state_hash()


def test_steps_that_do_not_fit_in_a_frame_are_dropped_and_the_hud_says_so(window, monkeypatch):
    import time as _time
    slow_step = Tiny.step

    def step(self, h):
        _time.sleep(0.03)
        slow_step(self, h)

    monkeypatch.setattr(Tiny, "step", step)
    n = window.update(8 / 60)                # asks for 8 steps of 30 ms: the budget is 100 ms
    assert 1 <= n <= 5
    assert window.clock.dropped_steps == 8 - n
    assert any("slower than real time" in str(getattr(x, "text", x)) for x in window.hud_lines())


def test_a_panel_change_while_recording_keeps_time_running_forward_and_warns(tmp_path):
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    w = Window(screen, [Tiny], screenshot_dir=tmp_path, recording=True)
    w.open_scene(Tiny, {"count": "2"})
    for i in range(30):
        if i == 10:
            assert w.apply_setting("hertz", 120)
        if i % 5 == 0:
            key(w, pygame.K_u)
        w.update(1 / 60)
    times = [e["t"] for e in w.recorded]
    assert times == sorted(times) and len(times) == 12
    assert w.recorded_changes == ["hertz=120"]
    assert any("not an event" in m[1] for m in w.messages)
    assert w.replay_command("demo.json") == (
        f"python -m app --headless --scene tiny --set count=2 --input demo.json "
        f"--steps {w.session_steps}")
