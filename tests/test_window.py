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

from app.draw import hud
from app.draw.text import TEXT
from app.scene import Effect, InputEvent, Param, Scene
from app.runner import NONFINITE_TEXT
from app.window import Window, run_window
from app.window.scene_view import SETTLE_FRAMES
from tests.toy_scenes import key


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


def open_window(cls, tmp_path, size=(1024, 640), frames: int = 0, **kwargs) -> Window:
    """A Window of `size` with `cls` open, after `frames` frames of 1/60 s (each rendered)."""
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode(size), [cls], screenshot_dir=tmp_path, **kwargs)
    assert w.open_scene(cls)
    for _ in range(frames):
        w.update(1 / 60)
        w.render()
    return w


def slow_steps(monkeypatch, cls, seconds: float) -> None:
    """Make every step of `cls` take `seconds` more wall time (a slow machine, as the window
    sees it)."""
    import time
    step = cls.step

    def slow(self, h):
        time.sleep(seconds)
        step(self, h)

    monkeypatch.setattr(cls, "step", slow)


@pytest.fixture
def window(tmp_path):
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    w = Window(screen, [Tiny, Other], screenshot_dir=tmp_path / "shots")
    assert w.open_scene(Tiny)
    yield w
    TEXT.scale = 1.0


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
    assert window.scene_view.clock.paused
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
    assert window.scene_view.clock.slow_motion == 0.5
    assert window.scene.dt == dt
    assert window.update(0.1) == 3         # 0.1 s of frames = 0.05 s simulated = 3 steps of dt
    key(window, pygame.K_MINUS)
    key(window, pygame.K_MINUS)
    key(window, pygame.K_MINUS)
    assert window.scene_view.clock.slow_motion == 0.125
    key(window, pygame.K_EQUALS)
    assert window.scene_view.clock.slow_motion == 0.25
    assert "speed x1/4" in " ".join(str(getattr(l, "text", l)) for l in window.scene_view.hud_lines())


def test_r_resets(window):
    window.update(0.1)
    window.scene.x[:] = 500.0
    key(window, pygame.K_r)
    assert window.scene.time == 0.0 and window.scene.steps == 0
    assert window.scene.x[0, 0] == 100.0


def test_f2_toggles_large_text_and_widens_the_panel(window):
    narrow = window.scene_view.panel.rect.width
    key(window, pygame.K_F2)
    assert TEXT.scale == pytest.approx(1.6)
    assert window.scene_view.panel.rect.width > narrow
    window.render()
    key(window, pygame.K_F2)
    assert TEXT.scale == 1.0
    assert window.scene_view.panel.rect.width == narrow


def test_bad_typed_value_is_refused_and_the_old_one_kept(window):
    panel = window.scene_view.panel
    for bad in ("abc", "nan", "inf", "99", "2.5", ""):
        type_into(panel, "count", bad)
        assert window.scene.p["count"] == 3
        assert panel.entries["count"].get_text() == "3"
    assert any("count" in text for _, text, *_ in window.messages)
    type_into(panel, "g", "-1")
    assert window.scene.p["g"] == 100.0
    window.render()                        # the error banner draws without trouble


def test_valid_values_change_the_scene(window):
    panel = window.scene_view.panel
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
    window.scene_view.panel.entries["g"].focus()
    key(window, pygame.K_r)
    key(window, pygame.K_SPACE)
    assert window.scene.steps == steps and not window.scene_view.clock.paused


def test_non_finite_state_rolls_back_and_pauses(window):
    window.scene.set("blowup", True)
    for _ in range(100):
        window.update(1 / 60)
        if window.scene_view.clock.paused:
            break
    scene = window.scene
    assert window.scene_view.clock.paused
    assert scene.is_finite()
    # snapshots at steps 0 and 30; it blew up at 41 and goes back to the oldest kept (step 0):
    # the one just before a blow-up may already be a wreck
    assert scene.steps == 0 and scene.time == 0.0
    banner = window.scene_view.banner
    assert banner == NONFINITE_TEXT.format(bad=41 / 60, good=0.0,
                                     advice="Try a smaller dt (raise hertz) or more substeps.")
    window.render()
    key(window, pygame.K_SPACE)            # resuming clears the banner
    assert not window.scene_view.banner


def test_recording_writes_input_json_in_world_coordinates(window, tmp_path):
    # a smaller window: the world is drawn at half size, so screen and world pixels differ
    window.resize(pygame.display.set_mode((800, 600)))
    view = window.scene_view.view
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
    mouse(window, pygame.MOUSEBUTTONDOWN, window.scene_view.view.pt((400.0, 300.0)), 1)
    window.update(0.05)
    key(window, pygame.K_u)
    window.update(0.1)
    key(window, pygame.K_r)                # recorded as a reset
    window.update(0.05)
    mouse(window, pygame.MOUSEBUTTONDOWN, window.scene_view.view.pt((50.0, 60.0)), 3)
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
    assert any(text == f"screenshot saved: {shots[0].resolve()}" for _, text, *_ in window.messages)


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
    assert window.scene_view.panel is None and window.scene_view.world_area().width == 1280
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
    assert err.startswith("python -m app: error: no display for the window: x11 not available; "
                          "use --headless")


def test_run_window_screenshot_after_seconds_and_record(monkeypatch, tmp_path):
    import scenes
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    shot, rec = tmp_path / "w.png", tmp_path / "rec.json"
    assert run_window("tiny", {"g": "50"}, record=str(rec), screenshot=str(shot),
                      seconds=0.2) == 0
    assert pygame.image.load(str(shot)).get_size() == (1280, 800)
    assert json.loads(rec.read_text()) == []


def test_run_window_says_it_replaced_a_screenshot_and_a_lost_csv_exits_2(monkeypatch, tmp_path,
                                                                        capsys):
    # once (hostile run, seed 27): the window's --csv that could not be written printed its
    # error and exited 0, and --screenshot replaced a file without a word
    import scenes
    from app import outputs
    from app.headless import Extras
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    shot, table = tmp_path / "w.png", tmp_path / "run.csv"
    table.write_text("old rows")             # seed 2026: the --csv replaced it without a word
    assert run_window("tiny", {}, seconds=0.05, extras=Extras(csv=str(table))) == 0
    assert "run.csv (replaced the file that was there)" in capsys.readouterr().out
    table.unlink()
    commit = outputs.Pending.commit

    def full_disk_for_the_csv(self, *args, **kwargs):
        if self.what != "--csv":
            return commit(self, *args, **kwargs)
        self.discard()
        raise outputs.OutputError(self.failed("No space left on device"))
    monkeypatch.setattr(outputs.Pending, "commit", full_disk_for_the_csv)
    shot.write_bytes(b"old")
    assert run_window("tiny", {}, screenshot=str(shot), seconds=0.1,
                      extras=Extras(csv=str(table))) == 2
    out, err = capsys.readouterr()
    assert "w.png (replaced the file that was there)" in out
    assert err.count("\n") == 1 and "could not write --csv" in err and not table.exists()


def test_typing_a_value_and_enter_sets_it(window):
    entry = window.scene_view.panel.entries["g"]
    entry.focus()
    entry.set_text("")
    pygame.event.clear()
    window.handle_pygame_event(pygame.event.Event(pygame.TEXTINPUT, text="42"))
    key(window, pygame.K_RETURN)
    for ev in pygame.event.get():          # pygame-gui posts UI_TEXT_ENTRY_FINISHED
        window.handle_pygame_event(ev)
    assert window.scene.p["g"] == 42.0
    assert not window.scene_view.panel.is_typing()


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
    grab = w.scene_view.view.pt(cloth.x[:, 5, 6])
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


def test_steps_that_do_not_fit_in_a_frame_are_dropped_and_the_hud_says_why(window, monkeypatch):
    for _ in range(SETTLE_FRAMES):           # the first frames after opening do not count
        window.update(1 / 60)
    assert not any("slower" in str(getattr(x, "text", x)) for x in window.scene_view.hud_lines())
    slow_steps(monkeypatch, Tiny, 0.03)
    dropped = window.scene_view.clock.dropped_steps
    n = window.update(8 / 60)                # asks for 8 steps of 30 ms: the budget is 100 ms
    assert 1 <= n <= 5
    assert window.scene_view.clock.dropped_steps - dropped == 8 - n
    text = " ".join(str(getattr(x, "text", x)) for x in window.scene_view.hud_lines())
    assert "slower than real time: physics takes" in text
    assert "iterations" not in text and "fewer substeps or hertz catch up" in text  # its knobs


def test_a_scene_that_says_it_falls_behind_is_not_echoed_by_the_window(window, monkeypatch):
    """mass_spring_cloth's 'not real time: ...' and the window's 'slower than real time: physics
    takes ...' were shown together: where the scene says it in its own terms, the window is
    silent about the physics (and speaks again when the scene does not)."""
    for _ in range(SETTLE_FRAMES):
        window.update(1 / 60)
    slow_steps(monkeypatch, Tiny, 0.03)
    monkeypatch.setattr(Tiny, "real_time_words", lambda self: "not real time: Tiny's words")
    window.update(8 / 60)
    text = " ".join(str(getattr(x, "text", x)) for x in window.scene_view.hud_lines())
    assert "slower than real time" not in text
    monkeypatch.setattr(Tiny, "real_time_words", lambda self: "")
    window.update(8 / 60)
    text = " ".join(str(getattr(x, "text", x)) for x in window.scene_view.hud_lines())
    assert "slower than real time: physics takes" in text


def test_the_frame_that_blew_up_and_was_rolled_back_is_not_slower_than_real_time(window,
                                                                                monkeypatch):
    """The mass-spring card "Leather past its limit" said "slower than real time: physics
    takes 46 ms of a 143 ms frame" over its rollback message: the steps were undone and the
    scene paused, so no frame was slow."""
    for _ in range(SETTLE_FRAMES):
        window.update(1 / 60)
    window.scene_view.apply_setting("blowup", True)
    slow_steps(monkeypatch, Tiny, 0.03)
    for _ in range(60):
        window.update(8 / 60)
        if window.scene_view.banner:
            break
    assert window.scene_view.banner and window.scene_view.clock.paused
    text = " ".join(str(getattr(x, "text", x)) for x in window.scene_view.hud_lines())
    assert "slower than real time" not in text


def test_a_slow_first_frame_after_opening_or_f2_is_not_slower_than_real_time(window):
    for frame in (0.25, 0.25, 1 / 60):       # the build and the first draw take long
        window.update(frame)
    key(window, pygame.K_F2)
    window.update(0.25)
    text = " ".join(str(getattr(x, "text", x)) for x in window.scene_view.hud_lines())
    assert "slower than real time" not in text


def test_the_physics_figure_holds_while_paused(window):
    for _ in range(10):
        window.update(1 / 60)
    key(window, pygame.K_SPACE)
    figure = window.scene_view.status_lines()[0].split(" | ")[2]
    for _ in range(20):
        window.update(1 / 60)
        window.render()
    assert window.scene_view.status_lines()[0].split(" | ")[2] == figure
    assert figure.startswith("physics ") and "ms/step" in figure


class Costly(Tiny):
    """Tiny with a measured 'work' effect whose cost jumps from ~0 to 2 ms a step, and the
    cloth's way of reporting it (mean since the last call, smoothed 0.7 / 0.3)."""
    name = "costly"

    def build(self):
        super().build()
        self.slow, self.work, self._mark, self._cost = False, 0.0, (0, 0.0), None

    def step(self, h):
        import time
        t0 = time.perf_counter()
        while self.slow and time.perf_counter() - t0 < 0.002:
            pass
        self.work += time.perf_counter() - t0
        super().step(h)

    def effect_costs(self):
        steps0, work0 = self._mark
        if self.steps > steps0:
            now = (self.work - work0) * 1000.0 / (self.steps - steps0)
            self._cost = now if self._cost is None else 0.7 * self._cost + 0.3 * now
            self._mark = (self.steps, self.work)
        return {"work": self._cost or 0.0}


def half_unit(shown: str) -> float:
    """Half a unit of the last digit of a figure as printed ('14.7' -> 0.05)."""
    decimals = len(shown.split(".")[1]) if "." in shown else 0
    return 0.5 * 10.0 ** -decimals


def test_the_physics_figure_and_its_breakdown_add_up_when_the_cost_jumps(tmp_path):
    """The HUD's ms/step is taken over the same steps, smoothed the same way, as the scene's
    breakdown: a part never exceeds the total (the cloth read 'physics 5.41 ms/step' with parts
    adding up to 8.7 when the runner's 60-step mean lagged behind the scene's smoothing)."""
    w = open_window(Costly, tmp_path, frames=30)
    w.scene.slow = True
    for _ in range(12):
        w.update(1 / 60)
        w.scene_view.status_lines()                    # reads the figure and the parts
        line = w.scene_view.detail_lines()[0]          # 'physics T ms/step (work P)'
        shown_total, shown_part = line.split()[1], line.split("work ")[1].rstrip(")")
        total, part = float(shown_total), float(shown_part)
        # each figure is rounded to its last digit shown (10 ms and up: one decimal, so 14.71
        # ms may show as 14.7): a part exceeds the total only past both roundings
        assert part <= total + half_unit(shown_total) + half_unit(shown_part), line
    assert part > 0.5                                   # the jump is seen


def test_panel_changes_while_recording(tmp_path):
    """Before the first event a change restarts the recording (the replay gets it as --set);
    after it the change is named as not replayable."""
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    rec = tmp_path / "demo.json"
    w = Window(screen, [Tiny], screenshot_dir=tmp_path, record=rec)
    w.open_scene(Tiny, {"count": "2"})
    for _ in range(5):
        w.update(1 / 60)
    assert w.scene_view.apply_setting("g", 300)           # no event yet: restart
    assert w.session_steps == 0 and w.scene.steps == 0
    for i in range(30):
        if i == 10:
            assert w.scene_view.apply_setting("hertz", 120)
        if i % 5 == 0:
            key(w, pygame.K_u)
        w.update(1 / 60)
    times = [e["t"] for e in w.recorded]
    assert times == sorted(times) and len(times) == 12
    assert any("cannot repeat" in m[1] for m in w.messages)
    line = w.recorder.write()
    assert line.startswith(f"recorded 12 events of tiny over {w.session_steps} steps; replay: "
                           f"python -m app --headless --scene tiny --set count=2 --set g=300.0 "
                           f"--input {rec} --steps {w.session_steps}")
    assert "hertz=120" in line
    assert any("REC" in str(getattr(x, "text", x)) for x in w.scene_view.hud_lines())


def test_hovering_over_the_world_on_the_way_to_the_panel_still_lets_a_change_be_recorded(
        tmp_path):
    """The pointer crosses the world to reach the panel: those moves change nothing, so a panel
    change after them still restarts the recording (it was 'not replayable' before)."""
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    w = Window(screen, [Tiny], screenshot_dir=tmp_path, record=tmp_path / "demo.json")
    w.open_scene(Tiny)
    for x in (300, 500, 700):
        mouse(w, pygame.MOUSEMOTION, (x, 300))
        w.update(1 / 60)
    assert [e["type"] for e in w.recorded] == ["mouse_move"] * 3
    assert w.scene_view.apply_setting("g", 300)
    assert w.recorder.session.settings == {"g": "300.0"} and w.recorded == []
    key(w, pygame.K_u)                     # a press: from now on a change is not replayable
    w.update(1 / 60)
    assert w.scene_view.apply_setting("g", 200)
    assert w.recorder.session.not_replayed == ["g=200.0"]


def test_a_recording_made_before_any_panel_change_replays_with_its_set_values(tmp_path):
    from app.headless import load_events, run_scene
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    rec = tmp_path / "demo.json"
    w = Window(screen, [Tiny], screenshot_dir=tmp_path, record=rec)
    w.open_scene(Tiny)
    w.update(0.1)
    w.scene_view.apply_setting("g", 321.0)
    w.scene_view.apply_setting("count", 5)
    for i in range(20):
        if i in (3, 11):
            key(w, pygame.K_u)
        w.update(1 / 60)
    w.recorder.write()
    assert w.recorder.session.settings == {"g": "321.0", "count": "5"}
    replay = run_scene(Tiny({"g": "321.0", "count": "5"}), w.session_steps,
                       load_events(str(rec)))
    assert replay.scene.state_hash() == w.scene.state_hash()


def test_the_replay_command_is_printed_after_esc_esc(monkeypatch, tmp_path, capsys):
    import scenes
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    script = [[], [pygame.event.Event(pygame.KEYDOWN, key=pygame.K_u, mod=0, scancode=0,
                                      unicode="u")],
              [], [pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE, mod=0, scancode=0,
                                      unicode="")],
              [pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE, mod=0, scancode=0,
                                  unicode="")]]
    monkeypatch.setattr(pygame.event, "get", lambda: script.pop(0) if script else [])
    rec = tmp_path / "rec.json"
    assert run_window("tiny", {}, record=str(rec), seconds=5.0) == 0
    out = capsys.readouterr().out
    assert "recorded 1 events of tiny" in out and f"--input {rec}" in out
    assert [e["key"] for e in json.loads(rec.read_text())] == ["u"]


def test_a_text_box_clicked_a_second_time_gets_the_keys_and_the_shell_none(window):
    """Defect 1 of issue 10: after Enter, a second click on the same box must focus it again,
    and while it has focus no key reaches the shell or the scene."""
    for _ in range(3):
        window.update(1 / 60)
        window.render()
    entry = window.scene_view.panel.entries["g"]
    where = entry.get_abs_rect().center
    for round_ in range(2):
        mouse(window, pygame.MOUSEBUTTONDOWN, where, 1)
        mouse(window, pygame.MOUSEBUTTONUP, where, 1)
        window.update(1 / 60)
        assert window.scene_view.typing(), f"click {round_ + 1} did not focus the box"
        steps, seen = window.scene.steps, len(window.scene.seen)
        for k in (pygame.K_MINUS, pygame.K_r, pygame.K_SPACE, pygame.K_u, pygame.K_h):
            key(window, k)
        assert window.scene_view.clock.slow_motion == 1.0 and not window.scene_view.clock.paused
        assert not window.show_help and window.scene.steps == steps
        assert len(window.scene.seen) == seen
        key(window, pygame.K_RETURN)
        for ev in pygame.event.get():
            window.handle_pygame_event(ev)
        assert not window.scene_view.typing()
        assert len(window.scene.seen) == seen and not window.recorded   # not even Enter's key_up


def test_try_cards_apply_their_settings_and_say_what_to_watch(window):
    from app.scene import Try
    panel = window.scene_view.panel
    Tiny.tries = (Try("heavy", {"g": 900, "drag": "on"}, "it falls faster"),
                  Try("bad", {"count": 99}, "never"))
    try:
        window.scene_view.on_layout()
        panel = window.scene_view.panel
        cards = {c.label: b for b, c in panel.cards.items()}
        window.handle_pygame_event(pygame.event.Event(pygame_gui.UI_BUTTON_PRESSED,
                                                      {"ui_element": cards["heavy"]}))
        assert window.scene.p["g"] == 900 and "drag" in window.scene.on
        assert any("it falls faster" in m[1] for m in window.messages)
        window.handle_pygame_event(pygame.event.Event(pygame_gui.UI_BUTTON_PRESSED,
                                                      {"ui_element": cards["bad"]}))
        assert window.scene.p["count"] == 3                       # refused, nothing changed
        assert any("count" in m[1] for m in window.messages if m[2] == (255, 120, 110))
    finally:
        Tiny.tries = ()


def test_a_card_starts_afresh_and_runs_and_shows_its_choice(window):
    """A card restarts the scene and runs it, also after the last one blew up (rolled back,
    paused), the panel's drop-down shows the card's choice, and only the latest card's line is
    in the HUD."""
    from app.scene import Try
    Tiny.tries = (Try("blow", {"blowup": True}, "it goes NaN"),
                  Try("calm", {"blowup": False, "method": "verlet"}, "it falls"))
    try:
        sv = window.scene_view
        sv.on_layout()
        cards = {c.label: b for b, c in sv.panel.cards.items()}
        press = lambda label: window.handle_pygame_event(pygame.event.Event(
            pygame_gui.UI_BUTTON_PRESSED, {"ui_element": cards[label]}))
        press("blow")
        for _ in range(60):
            window.update(1 / 60)
        assert sv.paused and sv.banner                      # rolled back and paused
        press("calm")
        assert not sv.paused and not sv.banner and window.scene.steps == 0
        assert sv.panel.dropdowns["method"].selected_option[0] == "verlet"
        assert [m[1] for m in window.messages if m[1].startswith("Try: ")] == [
            "Try: calm (blowup=off, method=verlet): it falls"]
        window.update(1 / 60)
        assert window.scene.steps > 0
    finally:
        Tiny.tries = ()


def test_a_card_while_recording_before_any_press_is_a_set_not_an_event(tmp_path):
    """The card's restart is the recording's restart: no "r" in the file, its values as --set."""
    from app.scene import Try
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1280, 800))
    Tiny.tries = (Try("heavy", {"g": 900}, "it falls faster"),)
    try:
        w = Window(screen, [Tiny], screenshot_dir=tmp_path, record=tmp_path / "demo.json")
        w.open_scene(Tiny)
        for _ in range(5):
            w.update(1 / 60)
        assert w.scene_view.apply_try(Tiny.tries[0])
        assert w.recorded == [] and w.recorder.session.settings == {"g": "900.0"}
        assert w.scene.steps == 0 and not w.scene_view.paused
    finally:
        Tiny.tries = ()


class Failing(Tiny):
    """A scene whose (student's) code fails at step 5."""
    name = "failing"

    def step(self, h):
        if self.steps >= 5:
            from app.scene import SceneError
            raise SceneError("exercise.py line 3: ZeroDivisionError\nin my_step(h)")
        super().step(h)


def test_a_scene_error_pauses_the_window_and_shows_the_message(tmp_path):
    w = open_window(Failing, tmp_path, frames=20)
    sv = w.scene_view
    assert w.scene is not None and sv.clock.paused and w.running
    assert sv.runner.error.startswith("exercise.py line 3")
    assert w.scene.steps == 5
    key(w, pygame.K_r)                                   # R runs it again
    assert sv.runner.error is None and w.scene.steps == 0


class FailingAndSaysSo(Failing):
    """Like an exercise scene: draw() shows the error it raised."""
    name = "failing_says_so"
    draws_own_error = True


@pytest.mark.parametrize("cls, shown", [(Failing, 1), (FailingAndSaysSo, 0)])
def test_a_scene_error_is_shown_once(tmp_path, cls, shown):
    """The HUD repeats the error only for a scene that does not draw it itself (an exercise's
    traceback showed twice, a banner over the scene's box)."""
    w = open_window(cls, tmp_path, frames=20)
    w.render()
    text = [str(getattr(x, "text", x)) for x in w.scene_view.hud_lines()]
    assert sum("ZeroDivisionError" in t for t in text) == shown


def test_headless_reports_a_scene_error_and_goes_on(capsys):
    from app.headless import run_headless
    code = run_headless([Failing, Tiny], {}, 20, None, None, None, True)
    out, err = capsys.readouterr()
    rows = [json.loads(line) for line in out.splitlines()]
    assert code == 1
    assert rows[0]["error"].startswith("exercise.py line 3") and rows[0]["steps"] == 5
    assert rows[1]["scene"] == "tiny" and rows[1]["error"] is None and rows[1]["steps"] == 20
    assert "failing: exercise.py line 3" in err


def test_headless_warns_about_events_after_the_end(capsys):
    from app.headless import run_headless
    events = [InputEvent("key_down", key="u", t=0.05), InputEvent("key_down", key="u", t=9.0)]
    assert run_headless([Tiny], {}, 30, None, events, None, True) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["events"] == 1
    assert err.count("\n") == 1 and "1 --input event(s) not delivered" in err
    assert "the last step starts at t = 0.483333 s" in err and "due at t = 9 s" in err
    # an event at the last step's start is delivered; one just after it is not
    events = [InputEvent("key_down", key="u", t=29 / 60), InputEvent("key_down", key="u",
                                                                     t=30 / 60)]
    assert run_headless([Tiny], {}, 30, None, events, None, True) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["events"] == 1 and "1 --input event(s) not delivered" in err


def test_the_key_table_makes_the_keys_the_help_and_the_reference():
    from pathlib import Path
    from app.scene import SHELL_KEYS
    from app import keys
    from app.window.scene_view import SceneView
    from app.window.views import HelpView, MenuView
    reference = (Path(__file__).resolve().parent.parent / "docs" / "reference.md").read_text()
    assert keys.controls_table() in reference          # the key table (README's until issue 18)
    assert {n for k in keys.KEYS for n in k.names} <= SHELL_KEYS
    for k in keys.KEYS:                 # every action is a method of a view or of the window
        assert any(hasattr(c, k.action) for c in (SceneView, MenuView, HelpView, Window)), k


def test_the_menu_numbers_scenes_in_the_order_shown(window):
    class A(Tiny):
        name, title, category = "a", "A", "First"

    class B(Tiny):
        name, title, category = "b", "B", "Second"

    class C(Tiny):
        name, title, category = "c", "C", "First"

    window.scenes = [A, B, C]
    window.open_menu()
    window.render()
    entries = window.current_view.entries
    assert [(window.scenes[e.index].name, e.number) for e in entries] == [("a", 1), ("c", 2),
                                                                         ("b", 3)]
    key(window, pygame.K_2)
    assert type(window.scene) is C


def test_help_text_is_wrapped_never_cut():
    from app.draw.hud import HelpPage, reflow
    doc = "First line of a paragraph\ngoes on here.\n\n- a list item\n- another"
    assert reflow(doc) == "First line of a paragraph goes on here.\n\n- a list item\n- another"
    TEXT.scale = 1.6
    try:
        page = HelpPage(400, "T", doc * 20, [("Space", "pause " * 30)], [("x", "y " * 50)])
        assert page.height > 640                      # longer than the screen: it scrolls
        assert all(img.get_width() <= 400 for _, _, img in page.items)
    finally:
        TEXT.scale = 1.0


def test_a_wrapped_line_keeps_a_number_with_its_unit_and_cuts_a_path_that_is_too_wide():
    """'physics 6.84' then 'ms/step' on the next row read as a bare number (the 1920x1080
    mass-spring HUD did), and a clip's path wider than its box ran off the window."""
    from app.draw.hud import wrap
    from app.draw.text import font
    pygame.font.init()
    f = font(28)
    text = "t = 3.82 s | dt = 1/60 s | physics 6.84 ms/step"
    room = f.size(text)[0] - 5                 # the unit no longer fits on the first row
    # rows break between phrases (issue 26: "physics" / "2.47 ms/step" in a narrow pane)
    assert wrap(text, f, room) == ["t = 3.82 s | dt = 1/60 s", "physics 6.84 ms/step"]
    one = "physics 6.84 ms/step"                  # a phrase wider than its row: between words,
    assert wrap(one, f, f.size(one)[0] - 5) == ["physics", "6.84 ms/step"]   # the unit kept
    pane = "physics 1.92 ms/step | largest stretch 7.15%"
    assert wrap(pane, f, f.size(pane)[0] * 2 // 3) == ["physics 1.92 ms/step",
                                                       "largest stretch 7.15%"]
    gaps = "L angle  -14.4 deg   slide  37.7 px (range 0..37.5)"   # two spaces part phrases,
    assert wrap(gaps, f, f.size(gaps)[0] - 5) == ["L angle  -14.4 deg",  # not a padded number
                                                  "slide 37.7 px (range 0..37.5)"]
    eq = "cotton, implicit Euler: h = 16.667 ms = 33x symplectic Euler's limit"
    assert not any(r.endswith(("h =", "=")) for r in wrap(eq, f, f.size(eq)[0] // 2))
    sweeps = "2 iterations x 1 substeps = 2 sweeps/step"            # '=' after a count's noun
    assert wrap(sweeps, f, f.size(sweeps)[0] - 5) == ["2 iterations x 1 substeps",
                                                      "= 2 sweeps/step"]
    semi = "omega*h = 0.150; spring's limits: 2, RK4 2.83"          # '; ' parts them too
    assert wrap(semi, f, f.size(semi)[0] - 5) == ["omega*h = 0.150;", "spring's limits: 2, RK4 2.83"]
    path = "/work/a-rather-long-folder/clips/mass_spring_cloth-20261124-075704.gif"
    rows = wrap(f"clip saved: {path} (93 frames)", f, 250)
    assert all(f.size(r)[0] <= 250 for r in rows) and path in "".join(rows)
    assert rows[1].endswith("/") or rows[2].startswith("/")    # cut at a slash where it can


def test_fmt_number_shows_a_missing_value_as_a_dash():
    from app.draw.hud import fmt_number
    assert fmt_number(None) == "-"


# ----- the layout rule, for every registered scene -------------------------------------------
from scenes import SCENES  # noqa: E402


@pytest.mark.parametrize("cls", SCENES, ids=[c.name for c in SCENES])
def test_hud_metrics_and_panel_never_cover_the_content(cls, tmp_path):
    """At both text sizes, at 1024x640, 1280x800 and 1920x1080, on both pages of the HUD (F4),
    the HUD box, the metrics strip and the panel do not intersect the screen rectangle of the
    scene's content_bounds() (the layout is computed as render() computes it; the panel is what
    the world area leaves)."""
    w = open_window(cls, tmp_path, frames=3)
    sv = w.scene_view
    try:
        for scale in (1.0, 1.6):
            TEXT.scale = scale
            for size in ((1024, 640), (1280, 800), (1920, 1080)):
                for details in (False, True):
                    w.hud_details = details
                    w.screen = pygame.Surface(size)
                    sv.pane.forget()
                    layout = sv.fit()
                    area = layout.area
                    content = layout.content_rect()
                    panel = pygame.Rect(area.right, 0, size[0] - area.right, size[1])
                    drawn = hud.box_size(sv.hud_lines(), layout.hud_text,
                                         max_width=layout.hud_width)
                    where = (scale, size, details)
                    assert panel.width >= 300 and area.width >= 600, where
                    assert drawn[0] <= layout.hud.width and drawn[1] <= layout.hud.height, where
                    assert area.contains(content), (where, content, area)
                    assert content.width > 0.25 * area.width or \
                        content.height > 0.25 * area.height, where     # fitted, not a stamp
                    assert (layout.strip.height > 0) == (details and w.scene.metrics_box)
                    for name, rect in (("HUD", layout.hud), ("metrics", layout.strip),
                                       ("panel", panel)):
                        assert not rect.colliderect(content), (where, name, rect, content)
    finally:
        TEXT.scale = 1.0


@pytest.mark.parametrize("cls", SCENES, ids=[c.name for c in SCENES])
def test_every_try_card_is_accepted_by_the_scene(cls):
    assert 2 <= len(cls.tries) <= 4
    for card in cls.tries:
        values, on = cls.resolve(card.settings)         # the panel's validation
        assert card.label and card.watch


class BrokenAtBuild(Tiny):
    """A scene whose (student's) code fails while it is built."""
    name = "broken"

    def build(self):
        from app.scene import SceneError
        raise SceneError("exercise.py line 9: NameError: name 'x' is not defined")


def test_a_scene_error_while_building_goes_back_to_the_menu_with_the_message(tmp_path, capsys):
    pygame.display.init()
    w = Window(pygame.display.set_mode((1024, 640)), [BrokenAtBuild], screenshot_dir=tmp_path)
    assert not w.open_scene(BrokenAtBuild)
    assert w.scene is None and "NameError" in w.menu_message and w.running
    w.render()
    assert capsys.readouterr().err == ""           # the message, not a traceback


def test_f3_hides_hud_and_metrics_and_the_content_grows(window):
    key(window, pygame.K_F4)                # the second page: a taller HUD and the strip
    window.update(1 / 60)
    window.render()
    before = window.scene_view.layout.content_rect(window.scene.content_bounds())
    key(window, pygame.K_F3)
    window.render()
    layout = window.scene_view.layout
    assert layout.hud.height == 0 and layout.strip.height == 0
    after = layout.content_rect(window.scene.content_bounds())
    assert after.width * after.height > before.width * before.height
    key(window, pygame.K_F3)
    window.render()
    assert window.scene_view.layout.hud.height > 0


def test_the_help_scrolls_and_keeps_the_other_shell_keys(window):
    TEXT.scale = 1.6                        # a long page: it scrolls
    key(window, pygame.K_h)
    window.render()
    help_view = window.current_view
    assert help_view.page.height > help_view.page_rect.height
    key(window, pygame.K_DOWN)
    assert help_view.scroll > 0
    key(window, pygame.K_END)
    window.render()
    assert help_view.scroll == help_view.page.height - help_view.page_rect.height
    key(window, pygame.K_SPACE)             # waits until the help is closed
    key(window, pygame.K_r)
    assert not window.scene_view.clock.paused and window.show_help
    key(window, pygame.K_ESCAPE)
    assert not window.show_help and window.scene is not None


@pytest.mark.parametrize("scale", [1.0, 1.6])
def test_every_menu_entry_is_on_screen_in_a_small_window(scale, tmp_path):
    pygame.display.init()
    screen = pygame.display.set_mode((1024, 640))
    w = Window(screen, SCENES, screenshot_dir=tmp_path, large_text=scale > 1)
    try:
        w.render()
        entries = w.current_view.entries
        assert sorted(e.number for e in entries) == list(range(1, len(SCENES) + 1))
        assert all(screen.get_rect().contains(e.rect.inflate(-12, 0)) for e in entries)
    finally:
        TEXT.scale = 1.0


def test_the_panel_buttons_fit_their_labels_at_large_text_in_the_smallest_window(tmp_path):
    w = open_window(Tiny, tmp_path, size=(1024, 640), large_text=True)
    try:
        panel = w.scene_view.panel
        font = panel.manager.get_theme().get_font(["button"])
        for button, text in ((panel.pause_button, "Resume"), (panel.reset_button, "Reset"),
                             (panel.help_button, "Help")):
            assert button.rect.width >= font.size(text)[0] + 8, text
        assert panel.help_button.rect.right <= panel.rect.right
    finally:
        TEXT.scale = 1.0


def test_large_text_never_shrinks_the_integrator_table_in_a_projector_window(tmp_path):
    """F2 in a 1920x1080 window: the integrator lab gives its energy chart and table the full
    width, so the table's glyphs are not smaller than at normal text (they were: 27 -> 26 px,
    the larger HUD lowered the zoom and the table's box squeezed its text; now 27 -> 28 px.
    The table is bound by its height: F3, which hides the HUD, is what makes it large)."""
    from scenes.integrators import IntegratorsScene
    w = open_window(IntegratorsScene, tmp_path, frames=3)
    sizes = {}
    try:
        for scale in (1.0, 1.6):
            w.screen = pygame.display.set_mode((1920, 1080))
            w.set_large_text(scale > 1)
            w.render()
            sizes[scale] = w.scene.table_text
    finally:
        w.set_large_text(False)
        TEXT.scale = 1.0
    assert sizes[1.6] >= sizes[1.0], sizes


def test_rollback_goes_to_the_oldest_of_the_snapshots_kept():
    """Three snapshots are kept (every 30 steps); a blow-up at step 100 goes back to step 30,
    and the next one goes back to where that rollback landed."""
    from app.runner import SNAPSHOTS_KEPT, SceneRunner
    assert SNAPSHOTS_KEPT == 3
    scene = Tiny()
    runner = SceneRunner(scene, rollback=True)
    runner.rebuilt()
    for _ in range(99):
        runner.run(1)
    scene.set("blowup", True)                 # Tiny goes NaN a few steps after this
    while runner.run(1)[1] is None:
        pass
    assert scene.steps == 30 and scene.is_finite()   # kept: 30, 60, 90 -> the oldest
    while runner.run(1)[1] is None:
        pass
    assert scene.steps == 30


def test_the_cached_theming_ids_are_pygame_guis_own(tmp_path):
    """app/window/gui_ids.py answers before pygame_gui's cache: for every id lists a scene's
    panel asked for, the same list as pygame_gui's own function gives."""
    from pygame_gui.core.ui_appearance_theme import UIAppearanceTheme
    from app.window import gui_ids
    open_window(Costly, tmp_path, frames=2)
    assert UIAppearanceTheme.build_all_combined_ids is gui_ids.build_all_combined_ids
    assert len(gui_ids._IDS) >= 5
    theme = UIAppearanceTheme.__new__(UIAppearanceTheme)
    theme.unique_theming_ids = {}
    for key, ids in gui_ids._IDS.items():
        lists = [None if k is None else list(k) for k in key]
        assert gui_ids._ORIGINAL(theme, *lists) == ids


def test_the_lab_answers_tint_is_the_formula():
    """app/exercises/live.py's table: brightness l (the largest channel) -> (0.35 + 0.65 l/255)
    of the ghost's colour, as the float formula it replaced, to the unit."""
    from app.exercises.live import GHOST, TINT
    light = np.arange(256)
    exact = (0.35 + 0.65 * light[:, None] / 255.0) * np.array(GHOST)
    assert TINT.shape == (256, 3) and np.abs(TINT - exact).max() < 1.0
