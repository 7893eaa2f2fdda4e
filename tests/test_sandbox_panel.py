"""The sandbox's panel in the window (SDL dummy driver): the selected body's fields and the
name Ctrl+S asks are typed into the panel, reach the scene as "edit" and "save" events, and
--record writes them (tests/test_scenefiles.py replays such a session headless)."""

from __future__ import annotations

import json

import pygame
import pytest

from app.draw.text import TEXT
from app.scene import InputEvent
from app.window import Window
from tests.toy_scenes import key as press


def type_enter(w: Window, entry, text: str, resize_to: tuple[int, int] | None = None) -> None:
    """Click into `entry`, replace its text with `text` as typed, press Enter; with resize_to,
    the window is resized before pygame-gui's event for that Enter is handled (the resize lays
    the panel out again: the event then names a box of the panel before)."""
    view = w.scene_view
    view.manager.set_focus_set(entry)
    entry.focus()
    entry.set_text("")
    w.handle_pygame_event(pygame.event.Event(pygame.TEXTINPUT, text=text))
    press(w, pygame.K_RETURN)
    if resize_to is not None:
        w.resize(pygame.display.set_mode(resize_to))     # (a VIDEORESIZE first in the queue)
    for ev in pygame.event.get():          # pygame-gui posts UI_TEXT_ENTRY_FINISHED
        w.handle_pygame_event(ev)
    frame(w)


def open_window(tmp_path, monkeypatch, cls, **options) -> Window:
    """A 1024x768 window on scene `cls`, run from tmp_path (options: Window's, e.g. large_text).
    No event of an earlier test is queued: tests/conftest.py's no_display_events_left."""
    monkeypatch.chdir(tmp_path)
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1024, 768)), [cls], screenshot_dir=tmp_path, **options)
    assert w.open_scene(cls)
    return w


def frame(w: Window) -> None:
    w.update(1 / 60)
    w.render()


def test_the_panel_edits_the_selected_body_and_asks_the_name_to_save(tmp_path, monkeypatch):
    """At 1024x768 with large text (F2), the tightest panel: a field per row, no box over
    another; a refused value changes nothing; the prompt has the keyboard; Esc cancels."""
    from scenes.sandbox import SandboxScene
    w = open_window(tmp_path, monkeypatch, SandboxScene, large_text=True,
                    record=tmp_path / "rec.json")
    try:
        view, scene = w.scene_view, w.scene
        assert view.panel.form.form.title == "Nothing selected" and not view.panel.form.boxes
        for e in (InputEvent("key_down", key="c"), InputEvent("mouse_down", (400, 200), 1),
                  InputEvent("mouse_up", (425, 200), 1)):
            view.deliver(e)
        frame(w)
        form = view.panel.form
        assert set(form.boxes) >= {"mass", "density", "friction", "elasticity", "radius", "x",
                                   "y", "angle", "vx", "vy"} and "type" in form.menus
        where = view.panel.form.boxes["mass"].rect.copy()
        type_enter(w, view.panel.form.boxes["mass"], "abc")          # refused: nothing changes
        assert scene.message_error and "not a finite number" in scene.message, scene.message
        assert view.panel.form.boxes["mass"].rect == where    # the refusal moved no box
        assert scene.selected_body()["density"] == 0.01
        type_enter(w, view.panel.form.boxes["mass"], "4")
        assert scene.named["ball1"].mass == pytest.approx(4.0) and not view.panel.is_typing()
        assert view.panel.form.boxes["mass"].get_text() == "4"
        # every box lies inside the panel, side by side without overlap
        rects = [b.rect for b in view.panel.form.boxes.values()]
        assert all(view.panel.rect.contains(r) for r in rects[:4])
        assert not any(a.colliderect(b) for i, a in enumerate(rects) for b in rects[i + 1:])
        press(w, pygame.K_LCTRL, up=False)
        press(w, pygame.K_s)
        press(w, pygame.K_LCTRL)
        frame(w)
        prompt = view.panel.form.prompt
        assert prompt is not None and prompt.get_text() == "sandbox-1" and view.panel.is_typing()
        type_enter(w, view.panel.form.prompt, "my scene")            # a space: not a name
        assert "is not a name" in scene.message and view.panel.form.prompt is not None
        type_enter(w, view.panel.form.prompt, "ramp")
        assert (tmp_path / "ramp.toml").is_file() and view.panel.form.prompt is None
        press(w, pygame.K_LCTRL, up=False)
        press(w, pygame.K_s)
        press(w, pygame.K_LCTRL)
        frame(w)
        press(w, pygame.K_ESCAPE)                                    # cancels, stays open
        frame(w)
        assert w.scene_view is view and view.panel.form.prompt is None
        assert scene.message == "not saved: cancelled"
    finally:
        w.recorder.write()
        TEXT.scale = 1.0
    kinds = [(e["type"], e.get("field", e.get("name"))) for e in
             json.loads((tmp_path / "rec.json").read_text()) if e["type"] in ("edit", "save")]
    assert kinds == [("edit", "mass"), ("edit", "mass"), ("save", "my scene"), ("save", "ramp"),
                     ("save", "")]


def test_a_value_typed_before_the_window_is_resized_still_reaches_the_scene(tmp_path,
                                                                           monkeypatch):
    """Enter in a box queues pygame-gui's event for it; a resize handled before that event lays
    the panel out again (a new box): the value still arrives, refused or taken, not lost."""
    from scenes.sandbox import SandboxScene
    w = open_window(tmp_path, monkeypatch, SandboxScene)
    view, scene = w.scene_view, w.scene
    for e in (InputEvent("key_down", key="c"), InputEvent("mouse_down", (400, 200), 1),
              InputEvent("mouse_up", (425, 200), 1)):
        view.deliver(e)
    frame(w)
    for typed, resize_to in (("abc", (1100, 800)), ("4", (1024, 768))):
        entry = view.panel.form.boxes["mass"]
        type_enter(w, entry, typed, resize_to)
        assert view.panel.form.boxes["mass"] is not entry      # (laid out again: a new box)
        if typed == "abc":
            assert scene.message_error and "not a finite number" in scene.message, scene.message
        else:
            assert scene.named["ball1"].mass == pytest.approx(4.0), scene.message
            assert not view.panel.is_typing()


def test_panel_events_for_a_scene_without_a_form_are_refused_in_one_line(tmp_path, capsys):
    """An "edit" event replayed into a scene that has no fields of its own would change nothing
    in silence: --input refuses it (exit 2, one line); the sandbox takes it."""
    from app.__main__ import main
    events = tmp_path / "edit.json"
    events.write_text(json.dumps([{"t": 0, "type": "edit", "field": "mass", "value": "3"}]))
    assert main(["--headless", "--scene", "cloth", "--input", str(events), "--steps", "1"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and 'the event "edit"' in err and "cloth has none" in err
    assert main(["--headless", "--scene", "sandbox", "--input", str(events), "--steps", "1"]) == 0


def test_a_setting_typed_before_the_window_is_resized_still_reaches_the_scene(tmp_path,
                                                                             monkeypatch):
    """The settings panel's number boxes, as the form's above: Enter, then a resize handled
    before pygame-gui's event lays the panel out again; the value typed is still applied."""
    from scenes.cloth import ClothScene
    w = open_window(tmp_path, monkeypatch, ClothScene)
    view, scene = w.scene_view, w.scene
    for typed, resize_to in (("7", (1100, 800)), ("12", (1024, 768))):
        entry = view.panel.entries["iterations"]
        type_enter(w, entry, typed, resize_to)
        assert view.panel.entries["iterations"] is not entry    # (laid out again: a new box)
        assert scene.p["iterations"] == int(typed)
        assert view.panel.entries["iterations"].get_text() == typed
        assert not view.panel.is_typing()


def test_a_save_that_cannot_be_written_says_so_in_one_line_and_leaves_nothing(tmp_path,
                                                                             monkeypatch):
    """Ctrl+S onto a name that is a folder: app/outputs' one line (what, why, the old one kept),
    the name once, the prompt kept for another name, and no temporary file left."""
    from scenes.sandbox import SandboxScene
    monkeypatch.chdir(tmp_path)
    (tmp_path / "ramp.toml").mkdir()
    scene = SandboxScene({})
    scene.answered("save", "ramp")                 # it is there: Enter again replaces it
    scene.answered("save", "ramp")
    assert scene.message_error and scene.message.startswith(
        "not saved: could not write scene file 'ramp.toml': "), scene.message
    assert scene.message.count("ramp.toml") == 1 and "\n" not in scene.message
    assert scene.asking == ("save", "ramp")
    assert [p.name for p in tmp_path.iterdir()] == ["ramp.toml"]
    assert (tmp_path / "ramp.toml").is_dir()
