"""In front of a class (issue 15): try cards that do what they say, messages where the HUD goes,
one unit per quantity, the integrator lab's labels at every size, the share of the window the
scene gets, the catalogue and the cards headless, and a window house without circles."""

from __future__ import annotations

import ast
import json
import math
import os
from pathlib import Path

import pygame
import pygame_gui
import pytest

from app.__main__ import main
from app.draw import hud
from app.draw.text import TEXT
from app.scene import Try
from app.units import fmt_number
from scenes import SCENES, get_scene, menu_scenes
from tests.test_window import Tiny, open_window, type_into

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
THEME = Path(ROOT) / "assets" / "theme.json"


def fresh_settings(cls, card: Try) -> dict:
    """What a card means: the scene's defaults plus the card's settings."""
    values, on = cls.resolve(card.settings)
    return {**values, **{e.name: e.name in on for e in cls.effects}}


def click(w, button) -> None:
    w.handle_pygame_event(pygame.event.Event(pygame_gui.UI_BUTTON_PRESSED,
                                             {"ui_element": button}))


def panel_shows(panel, settings: dict) -> None:
    """The panel's boxes, drop-downs and switches show these settings."""
    from app.window.panel import _value_text
    for name, entry in panel.entries.items():
        assert entry.get_text() == _value_text(settings[name]), name
    for name, d in panel.dropdowns.items():
        assert d.selected_option[0] == str(settings[name]), name
    for name, b in panel.toggles.items():
        assert b.text.endswith("ON" if settings[name] else "OFF"), name


# ----- 1. cards ------------------------------------------------------------------------------
@pytest.mark.parametrize("cls", SCENES, ids=[c.name for c in SCENES])
def test_every_card_after_every_other_card_is_the_card_on_a_fresh_scene(cls, tmp_path):
    """Clicked in the window after any other card (and a panel change in between), a card
    gives the settings and the very state of a fresh scene built with its settings, and the
    panel shows them (leather's hertz 1000 stayed under 'Leather past its limit'; pivoting_l's
    slide_max 0 stayed under the PivotJoint card)."""
    w = open_window(cls, tmp_path, size=(1280, 800))
    sv = w.scene_view
    buttons = {card.label: b for b, card in sv.panel.cards.items()}
    fresh = {c.label: fresh_settings(cls, c) for c in cls.tries}
    hashes = {c.label: cls(c.settings).state_hash() for c in cls.tries}
    order = every_pair_once(len(cls.tries))
    click(w, buttons[cls.tries[order[0]].label])
    for i, j in zip(order, order[1:]):
        first, then = cls.tries[i], cls.tries[j]
        w.scene.advance()                                   # it ran
        if i == j:
            sv.apply_setting("hertz", 90)                   # and the teacher fiddled
        click(w, buttons[then.label])
        assert w.scene.settings() == fresh[then.label], (first.label, then.label)
        assert w.scene.state_hash() == hashes[then.label], (first.label, then.label)
        assert w.scene.steps == 0 and not sv.paused and not sv.banner
        panel_shows(sv.panel, fresh[then.label])


def every_pair_once(n: int) -> list[int]:
    """A sequence of 0..n-1 in which every ordered pair (i, j), i == j too, follows each other
    exactly once (an Euler circuit of the complete graph with loops: n*n + 1 clicks instead of
    2 n*n)."""
    left = {i: list(range(n)) for i in range(n)}
    path, stack = [], [0]
    while stack:
        v = stack[-1]
        if left[v]:
            stack.append(left[v].pop())
        else:
            path.append(stack.pop())
    return path[::-1]


def test_the_cards_in_the_order_that_broke_them_keep_their_promises(tmp_path):
    """The issue's own clicks: 'Leather inside its limit', then 'Leather past its limit' blows
    up at h = 16.7 ms (rolled back, its advice in the HUD); 'Implicit Euler at 30 Hz' then reads
    70x at rest and ~90x once the cloth hangs; after 'No slide range' the PivotJoint card turns
    the L again."""
    cls = get_scene("mass_spring_cloth")
    w = open_window(cls, tmp_path, size=(1280, 800))
    sv = w.scene_view
    cards = {c.label: b for b, c in sv.panel.cards.items()}
    click(w, cards["Leather inside its limit"])
    for _ in range(3):
        w.update(1 / 60)
    click(w, cards["Leather past its limit"])
    assert w.scene.p["hertz"] == 60 and w.scene.p["substeps"] == 1
    for _ in range(30):
        w.update(1 / 60)
        if sv.banner:
            break
    assert sv.banner and "16.7 ms" in sv.banner
    click(w, cards["Implicit Euler at 30 Hz"])
    assert not sv.banner
    ratio = lambda: float(w.scene.hud_lines()[0].split("  |  ")[1].split("x")[0])  # noqa: E731
    assert 60 <= ratio() <= 80
    for _ in range(30):                            # re-estimated on the hanging cloth
        w.scene.advance()
    assert 80 <= ratio() <= 100

    pivot = get_scene("pivoting_l")
    w.open_scene(pivot)
    cards = {c.label: b for b, c in w.scene_view.panel.cards.items()}
    click(w, cards["No slide range"])
    click(w, cards["PivotJoint, not the pin"])
    angles = []
    for _ in range(600):
        w.scene.advance()
        angles.append(abs(math.degrees(w.scene.L_body.angle)))
    assert w.scene.p["slide_max"] == pivot.param("slide_max").default and max(angles) > 10


def test_a_card_from_the_command_line_is_the_click(capsys):
    """--headless --try LABEL: the same settings as a click (labels in any case), the card in
    the JSON; a card that does not exist, --try with --set or without one scene: exit 2."""
    assert main(["--headless", "--scene", "pivoting_l", "--try", "no slide RANGE", "--steps",
                 "5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    cls = get_scene("pivoting_l")
    card = cls.find_card("No slide range")
    assert out["params"] == {k: v for k, v in fresh_settings(cls, card).items()
                             if k in out["params"]}
    assert out["try"]["label"] == "No slide range" and out["try"]["watch"] == card.watch
    for args in (["--try", "nope"], ["--try", "No slide range", "--set", "g=100"]):
        assert main(["--headless", "--scene", "pivoting_l", "--steps", "5", *args]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "accepted" in err or "drop --set" in err
    assert main(["--headless", "--scene", "all", "--try", "x"]) == 2


def test_a_card_from_the_command_line_opens_the_window_with_it(tmp_path, capsys):
    """--try in the window is the click: recording from the start, the replay command carries
    the card's values as --set (the card restarted the recording from a fresh scene)."""
    shot, rec = tmp_path / "w.png", tmp_path / "rec.json"
    assert main(["--scene", "pivoting_l", "--try", "No slide range", "--seconds", "0.3",
                 "--screenshot", str(shot), "--record", str(rec)]) == 0
    out = capsys.readouterr().out
    assert "--scene pivoting_l --set slide_max=0" in out and shot.exists()


def test_the_catalogue_lists_every_scene_param_effect_and_card(capsys):
    assert main(["--list", "--json"]) == 0
    catalogue = json.loads(capsys.readouterr().out)
    listed = menu_scenes()          # the registry, then the shipped scene files
    assert [s["name"] for s in catalogue] == [c.name for c in listed]
    assert [s.get("path") for s in catalogue] == [getattr(c, "path", None) or None for c in listed]
    for entry, cls in zip(catalogue, listed):
        assert entry["title"] == cls.title and entry["category"] == cls.category
        assert [p["name"] for p in entry["params"]] == [p.name for p in cls.all_params()]
        for p in entry["params"]:
            prm = cls.param(p["name"])
            assert p["default"] == prm.default and p["help"] == prm.help
            assert p["kind"] in ("int", "float", "bool", "choice")
            assert ("choices" in p) == (p["kind"] == "choice")
            assert ("range" in p) == (p["kind"] in ("int", "float"))
        assert [e["name"] for e in entry["effects"]] == [e.name for e in cls.effects]
        assert [t["label"] for t in entry["tries"]] == [t.label for t in cls.tries]
        for t in entry["tries"]:
            cls.resolve(t["settings"])                    # as given, the scene takes them
            assert t["watch"] and f"--scene {cls.name} --try " in t["command"]


# ----- 2. messages ---------------------------------------------------------------------------
def texts(w) -> list[str]:
    return [str(getattr(x, "text", x)) for x in w.scene_view.hud_lines()]


def test_messages_are_hud_lines_and_go_when_what_they_speak_of_changes(tmp_path):
    """A refused value and a blow-up's advice are lines of the HUD box (which the layout keeps
    off the content), and go when that setting changes, when a card is clicked, or with the
    scene; the window's own message (a screenshot) stays."""
    w = open_window(Tiny, tmp_path, size=(1024, 640), frames=2)
    sv = w.scene_view
    type_into(sv.panel, "count", "abc")
    assert any("'abc'" in t for t in texts(w))
    type_into(sv.panel, "g", "50")                 # another setting: the refusal stays
    assert any("'abc'" in t for t in texts(w))
    type_into(sv.panel, "count", "4")              # that setting: it goes
    assert not any("'abc'" in t for t in texts(w))
    sv.apply_setting("blowup", True)
    for _ in range(80):
        w.update(1 / 60)
    # the first page: one line a class reads; the second (F4): the whole paragraph
    assert sv.banner and sv.banner_short in texts(w) and sv.banner not in texts(w)
    assert sv.banner_short.startswith("Blew up at ") and "F4: why" in sv.banner_short
    w.toggle_details()
    assert sv.banner in texts(w)
    w.toggle_details()
    w.render()
    assert not sv.layout.hud.colliderect(sv.layout.content_rect())
    sv.apply_setting("method", "verlet")           # the settings it spoke of changed
    assert not sv.banner and sv.banner not in texts(w)
    w.screenshot()
    w.render()
    w.flash("about this scene", topic="scene")
    w.open_scene(Tiny)
    assert not any("about this scene" in m.text for m in w.messages)
    assert any("screenshot saved" in m.text for m in w.messages)


def test_a_blow_up_message_goes_when_the_material_changes(tmp_path):
    """Leather's blow-up advice does not stay on screen after switching to cotton."""
    cls = get_scene("mass_spring_cloth")
    w = open_window(cls, tmp_path, size=(1024, 768))
    sv = w.scene_view
    sv.apply_try(cls.find_card("Leather past its limit"))
    for _ in range(30):
        w.update(1 / 60)
    assert sv.banner and any("x past its limit; rolled back" in t for t in texts(w))
    w.toggle_details()
    assert any("symplectic Euler's predicted limit" in t for t in texts(w))
    sv.apply_setting("material", "cotton")
    assert not sv.banner and not any("predicted limit" in t for t in texts(w))


class _QuickPhysics:
    """scene_view's clock for a frame's physics: 0.1 ms between two readings, whatever the
    machine is doing (the tests' own machine, at load 8, took over 5 ms for 8 Tiny steps at
    times: 'physics takes ...' then, not the cap, and the test failed)."""

    def __init__(self):
        self.now = 0.0

    def perf_counter(self) -> float:
        self.now += 1e-4
        return self.now


def test_at_high_hertz_the_hud_names_the_loops_cap_and_what_to_change(tmp_path, monkeypatch):
    """1000 Hz at 60 fps asks for 16.7 steps a frame; the loop runs 8: half real time on any
    machine. The HUD says so (not 'the display or the machine is slow') and names the hertz
    that runs in real time. (The physics' time is a fixed 0.1 ms a frame: the cap binds on
    any machine, and the HUD's cause must not hang on how busy the test's machine is.)"""
    import app.window.scene_view as scene_view
    from app.window.speed import SETTLE_FRAMES
    monkeypatch.setattr(scene_view, "time", _QuickPhysics())
    w = open_window(Tiny, tmp_path, size=(1024, 640))
    w.scene_view.apply_setting("hertz", 1000)
    for _ in range(SETTLE_FRAMES + 3):
        w.update(1 / 60)
    line = next(t for t in texts(w) if t.startswith("slower than real time"))
    assert "at most 8 steps a frame" in line and "0.48x real time on any machine" in line
    assert "hertz 480 or less" in line and "machine is slow" not in line


# ----- 3. units -------------------------------------------------------------------------------
def test_the_hud_and_the_strip_write_a_quantity_in_one_unit_and_noise_as_zero():
    """mass_spring_cloth's energy: 'energy -3.75 J' in the HUD and '-2.46e+05' in the strip in
    the same frame; after a rollback '3.223e-25 J' and 'max_stretch 3.55e-15' for 0."""
    cls = get_scene("mass_spring_cloth")
    scene = cls()
    for _ in range(20):
        scene.advance()
    m = scene.metrics()
    strip = " | ".join(hud.metric_lines(scene, m, 4000))
    energy = scene.shown("energy", m["energy"])
    assert energy.endswith(" J") and f"energy {energy}" in strip
    assert f"energy {energy}" in scene.hud_lines()[1]
    stretch = scene.shown("max_stretch", m["max_stretch"])
    assert stretch.endswith("%") and f"max_stretch {stretch}" in strip
    assert f"max stretch {stretch}" in scene.hud_lines()[1]
    assert scene.shown("energy", 3.223e-25 * 256 ** 2) == "0 J"
    assert scene.shown("max_stretch", 3.55e-15) == "0%"
    scene.restore(cls().snapshot())                # rolled back to the start: nothing moves
    assert scene.shown("energy", scene.metrics()["energy"]) == "0 J"


def test_a_large_reading_is_written_in_full_not_in_powers_of_ten():
    """The Verlet cloth yanked hard showed 'max 1.68e+03%' in its HUD: below 1e5 a number is
    written out whole ('1680%'), its digits kept as far as the unit asks."""
    cloth = get_scene("cloth")()
    assert cloth.shown("max_stretch", 16.804) == "1680%"
    assert cloth.shown("max_stretch", 0.16804) == "16.8%"
    assert fmt_number(12345.6) == "12346" and fmt_number(123456.0) == "123456"
    assert fmt_number(2.5e5 + 0.5) == "2.5e+05" and fmt_number(0.000123) == "0.000123"


@pytest.mark.parametrize("cls", SCENES, ids=[c.name for c in SCENES])
def test_every_declared_unit_is_a_metric_of_its_scene(cls):
    assert set(cls.metric_units) <= set(cls().metrics()), cls.name


# ----- 4. the integrator lab at every size ----------------------------------------------------
@pytest.mark.parametrize("problem", ["spring", "orbit"])
def test_the_integrator_labs_labels_never_overlap_and_grow_with_large_text(problem, tmp_path):
    """At 1024x640, 1024x768, 1280x800 and 1920x1080 and both text sizes no two labels touch
    (the energy chart's '2e-01' and '1e+00' were drawn on top of each other, the names over
    the caption), every label lies inside the scene's room, and large text makes the table's
    and the titles' glyphs larger, not smaller."""
    cls = get_scene("integrators")
    w = open_window(cls, tmp_path, size=(1024, 640))
    w.scene_view.apply_try(Try("t", {"problem": problem, "hertz": 3}, "w"))   # blow-ups
    for _ in range(40):
        w.update(1 / 20)
    heights = {}
    try:
        for size in ((1024, 640), (1024, 768), (1280, 800), (1920, 1080)):
            for large in (False, True):
                w.screen = pygame.Surface(size)
                TEXT.scale = 1.6 if large else 1.0
                w.scene_view.pane.forget()
                w.render()
                d = w.scene.drawing
                room = w.scene_view.layout.content_rect()
                rects = [r for r, _ in d.labels]
                for i, (r, text) in enumerate(d.labels):
                    assert room.contains(r), (size, large, text, r, room)
                    for r2, text2 in d.labels[i + 1:]:
                        assert not r.colliderect(r2), (size, large, text, text2)
                heights[size, large] = (d.table_text, max(r.height for r in rects))
                assert d.table_text >= 11, (size, large)
    finally:
        TEXT.scale = 1.0
    assert heights[(1920, 1080), True][0] > heights[(1920, 1080), False][0]
    assert heights[(1920, 1080), True][1] > heights[(1920, 1080), False][1]


def test_the_integrator_lab_at_1024x768_with_large_text_gives_the_picture_the_room(tmp_path):
    """At 1024x768 with F2 the springs were ~10 px tall, the phase portrait a 60 px flat ellipse
    under a ~170 px blank band: the springs panel and the phase portrait are each at least
    150 px tall, start right under the HUD (no band over 40 px), the springs' drawing and the
    phase curve fill over half of their panels, and the table ends above the scrub bar."""
    from app.draw.integrator_lab import chart_least
    w = open_window(get_scene("integrators"), tmp_path, size=(1024, 768))
    for _ in range(10):
        w.update(1 / 20)
    try:
        for scale in (1.6, 1.0):
            TEXT.scale = scale
            w.scene_view.pane.forget()
            w.render()
            r, d = w.scene.drawing.rects, w.scene.drawing
            box = w.scene_view.layout.hud
            assert r.systems.height >= 150 and r.phase.height >= 150, (scale, r)
            assert r.systems.top - box.bottom <= 40, (scale, box, r.systems)
            assert d.springs_box.height >= 0.5 * r.systems.height, (scale, d.springs_box)
            assert d.phase_curve.height >= 0.55 * r.phase.height, (scale, d.phase_curve)
            # the energy chart is one a class can read, or none (at F2 it was a 50 px plot
            # with one label: tests/test_projector_views.py)
            assert r.energy.height == 0 or r.energy.height >= chart_least(), (scale, r.energy)
            bar = w.scene_view.timeline_bar()
            label = hud.font(hud.HUD_SIZE * 3 // 4).get_height()       # "7 s kept  [ ]"
            assert bar is None or r.table.bottom <= bar.top - label, (scale, r.table, bar)
        # the orbit card's CG message makes the HUD 4 lines taller at F2: the energy chart
        # gives way (the table has E/E0), the picture keeps its 150 px (it had 130)
        w.scene_view.apply_try(get_scene("integrators").find_card("Orbit at hertz 60"))
        for _ in range(40):
            w.update(1 / 20)
        TEXT.scale = 1.6
        w.scene_view.pane.forget()
        w.render()
        r = w.scene.drawing.rects
        assert w.scene.hud_lines()[-1].startswith("implicit Euler")
        assert r.systems.height >= 150 and r.phase.height >= 150, r
    finally:
        TEXT.scale = 1.0


# ----- 5. the share of the window the scene gets ---------------------------------------------
SHARE_SIZES = ((1024, 768), (1920, 1080))


@pytest.mark.parametrize("cls", SCENES, ids=[c.name for c in SCENES])
def test_the_scene_gets_most_of_the_world_area_and_the_first_page_is_short(cls, tmp_path,
                                                                             capsys):
    """The share of the window the scene's content gets on screen (docs/instructors.md's table), at
    1024x768 and 1920x1080, both text sizes: never less than a fifth, at least 45 % in a
    projector window at normal text; the HUD's first page is a few lines."""
    w = open_window(cls, tmp_path, size=(1024, 768), frames=5)
    sv = w.scene_view
    shares = {}
    try:
        for size in SHARE_SIZES:
            for large in (False, True):
                w.screen = pygame.Surface(size)
                TEXT.scale = 1.6 if large else 1.0     # (the panel is not rebuilt: its width
                sv.pane.forget()                       # is all the layout reads of it)
                shares[size, large] = sv.fit().content_share(size)
                lines = hud.box_size(sv.hud_lines(), hud.HUD_SIZE, max_width=10 ** 4)[1]
                assert lines <= 8 * hud.font(hud.HUD_SIZE).get_linesize() + 16, (size, large)
    finally:
        TEXT.scale = 1.0
    with capsys.disabled():
        print(f"\n{cls.name:18} " + "  ".join(f"{shares[k]:.2f}" for k in sorted(shares)))
    assert min(shares.values()) >= 0.2, shares
    assert shares[(1920, 1080), False] >= 0.45, shares


# ----- 6. the panel ----------------------------------------------------------------------------
def test_pointing_at_a_card_shows_what_it_sets_below_the_cards_not_over_them(tmp_path):
    """No tooltip covers the cards (the box under them says what a card does); the other
    tooltips' text grows with F2 like the rest of the panel."""
    from app.window.panel_size import theme
    assert int(theme(1.6)["tool_tip.text_box"]["font"]["size"]) == round(
        1.6 * int(theme(1.0)["tool_tip.text_box"]["font"]["size"]))
    cls = get_scene("mass_spring_cloth")
    # the tooltip is as much wider with F2 as its font is bigger: its lines hold the same words
    # (its width stayed 170 px, and at F2 the cloth's 'tearing' tip wrapped a word a line)
    tip = "rods stretched beyond tear_ratio break"
    lines = {}
    for large in (False, True):
        w = open_window(cls, tmp_path, size=(1280, 800), large_text=large)
        box = pygame_gui.elements.UITooltip(tip, (0, 0), w.scene_view.manager)
        lines[large] = len(box.text_block.text_box_layout.layout_rows)
    assert lines[True] == lines[False], lines
    w = open_window(cls, tmp_path, size=(1024, 768))
    panel = w.scene_view.panel
    button, card = next(iter(panel.cards.items()))
    assert all(b.tool_tip_text is None for b in panel.cards)       # nothing covers a card
    w.handle_pygame_event(pygame.event.Event(pygame_gui.UI_BUTTON_ON_HOVERED,
                                             {"ui_element": button}))
    assert card.changes() in panel._watch_shown and card.watch in panel._watch_shown
    w.handle_pygame_event(pygame.event.Event(pygame_gui.UI_BUTTON_ON_UNHOVERED,
                                             {"ui_element": button}))
    assert card.label not in panel._watch_shown


@pytest.mark.parametrize("cls", [c for c in SCENES if c.tries or c.comparisons],
                         ids=lambda c: c.name)
def test_no_card_label_is_cut_at_large_text_in_a_small_window(cls, tmp_path):
    """'Explicit vs implicit at 60 Hz' was cut to '...60 H' at 1024x768 with F2: every card's
    label fits its button, in the font the button draws it with."""
    pad = int(json.loads(THEME.read_text())["#card"]["misc"]["text_horiz_alignment_padding"])
    w = open_window(cls, tmp_path, size=(1024, 640), large_text=True)
    try:
        panel = w.scene_view.panel
        assert len(panel.cards) == len(cls.tries) + len(cls.comparisons)
        for button, card in panel.cards.items():
            # the font the button draws with, as the theme gives it to this button
            font = button.ui_manager.get_theme().get_font(button.combined_element_ids)
            room = button.relative_rect.width - 2 * pad - 2     # padding each side, the border
            assert font.size(card.label)[0] <= room, (cls.name, card.label)
    finally:
        TEXT.scale = 1.0


# ----- 7. smaller -------------------------------------------------------------------------------
def test_the_cradles_verdict_says_which_setting_breaks_it():
    cls = get_scene("newtons_cradle")
    scene = cls({"gap": -0.01})
    for _ in range(360):
        scene.advance()
    lines = scene.hud_lines()
    assert lines[0] == "1 in, 0 out: NOT like a real cradle"
    assert lines[1].startswith("why: 0 out, not 1")
    assert "gap -0.01: touching balls" in lines[2]


# ----- 8. the house ----------------------------------------------------------------------------
FLOORS = {"app.keys": 0, "app.units": 0, "app.loop": 0, "app.physics": 0, "app.params": 0,
          "app.scene": 1, "app.draw": 2, "app.runner": 2, "app.catalogue": 2,
          "app.vectors": 0, "app.series": 0, "app.equations": 0, "app.energy": 0,
          "app.timeline": 0, "app.outputs": 0, "app.progress": 0, "app.compare": 3,
          "app.form": 0,           # a scene's panel form: plain data (app/form.py)
          "app.ctrl_c": 0,         # Ctrl-C held back across numba's compile (app/ctrl_c.py)
          "app.instruments": 3,
          "app.frames": 3, "app.headless_compare": 3, "app.cli_checks": 3, "app.cli_args": 3,
          "app.pymunk_scene": 3, "app.headless": 3, "scenes": 4, "app.bench": 5,
          "app.pymunk_reader": 0,  # every body of a space read in one C call (pymunk alone)
          "app.scenefile": 3,      # scene files: a pymunk scene made from data
          "app.window": 5, "app.clips": 3, "app.exercises": 5, "app.__main__": 6,
          "app.docs": 7,                    # the docs' generator reads the command line itself
          "app.docs.texts": 0}              # words and units only, no import: the CSV reads it


def import_graph() -> dict[str, set[str]]:
    """Every module of app/ and scenes/ and the lab modules it imports (anywhere in the file,
    also under TYPE_CHECKING and inside functions)."""
    mods = {}
    for base in ("app", "scenes"):
        for folder, _, files in os.walk(os.path.join(ROOT, base)):
            for f in files:
                if f.endswith(".py"):
                    rel = os.path.relpath(os.path.join(folder, f), ROOT)[:-3].replace(os.sep, ".")
                    mods[rel.removesuffix(".__init__")] = os.path.join(folder, f)

    def known(name: str) -> str | None:
        while name and name not in mods:
            name = name.rpartition(".")[0]
        return name or None

    graph = {}
    for mod, path in mods.items():
        deps = set()
        for node in ast.walk(ast.parse(open(path).read())):
            if isinstance(node, ast.Import):
                deps |= {known(a.name) for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                deps |= {known(f"{node.module}.{a.name}") or known(node.module)
                         for a in node.names}
        graph[mod] = {d for d in deps if d and d != mod}
    return graph


def floor(mod: str) -> int:
    return next(f for prefix, f in sorted(FLOORS.items(), key=lambda kv: -len(kv[0]))
                if mod == prefix or mod.startswith(prefix + "."))


def test_imports_run_one_way_no_circle_and_the_contract_below_the_window():
    graph = import_graph()
    for mod, deps in graph.items():
        for dep in deps:
            if mod == "app" or mod == "scenes" and dep.startswith("scenes."):
                continue
            assert floor(dep) <= floor(mod), f"{mod} imports {dep}: up a floor"
    seen, stack = set(), []

    def visit(mod: str) -> None:           # depth-first: a module met again on the stack
        stack.append(mod)
        for dep in sorted(graph.get(mod, ())):
            assert dep not in stack, " -> ".join(stack[stack.index(dep):] + [dep])
            if dep not in seen:
                visit(dep)
        stack.pop()
        seen.add(mod)
    for mod in sorted(graph):
        if mod not in seen:
            visit(mod)
    assert not {d for d in graph["app.scene"] if d.startswith(("app.window", "app.draw"))}
