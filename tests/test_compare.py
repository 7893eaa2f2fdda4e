"""Compare mode (app/compare.py, --compare): variants checked like --set, run in lockstep from the
same start, the same input to every pane, one JSON object per variant, every pane in one PNG, a
blow-up held in its own pane while the others go on, comparison cards, and the window's panes."""

from __future__ import annotations

import json

import numpy as np
import pygame
import pytest

from app.__main__ import main
from app.compare import CompareRunner, Variant, labels, parse_variant, resolve_variants
from app.draw.text import TEXT
from app.headless import parse_events
from app.runner import run_scene
from app.scene import Effect, InputEvent, Param, ParamError, Scene
from app.vectors import Arrows
from app.window import Window
from scenes import SCENES
from scenes.cloth import ClothScene
from scenes.falling_balls import FallingBallsScene


class Dot(Scene):
    """Points falling under gravity (compare test scene); a mouse press puts point 0 there."""

    name = "dot"
    title = "Dot"
    params = (Param("count", 3, int, 1, 20),
              Param("g", 100.0, float, 0.0, 1000.0, rebuild=False),
              Param("blowup_at", 0, int, 0, 10_000, rebuild=False,
                    help="step at which it goes NaN (0: never)"))
    effects = (Effect("gravity"),)
    error_metric, error_label = "y", "height"

    def build(self):
        self.x = np.zeros((self.p["count"], 2)) + (100.0, 100.0)
        self.v = np.zeros((self.p["count"], 2))
        self.seen: list[tuple[int, str, tuple]] = []

    def step(self, h):
        if "gravity" in self.on:
            self.v[:, 1] += self.p["g"] * h
        self.x += self.v * h
        if self.p["blowup_at"] and self.steps + 1 >= self.p["blowup_at"]:
            self.x[0, 0] = np.nan

    def handle_event(self, event):
        self.seen.append((self.steps, event.kind, tuple(event.pos)))
        if event.kind == "mouse_down":
            self.x[0] = event.pos
            self.v[0] = 0.0

    def metrics(self):
        return {"y": float(self.x[0, 1]), "n": len(self.x), "label": "text"}

    def state_arrays(self):
        return (self.x, self.v)

    def arrows(self):
        self.arrow_calls = getattr(self, "arrow_calls", 0) + 1
        return Arrows(np.arange(len(self.x)), self.x.copy(), self.v.copy(),
                      np.full(len(self.x), 2.0), "every dot")


def small_cloth(**kw):
    return {"rows": 8, "cols": 10, **kw}


# ----- 1. variants are checked like --set ----------------------------------------------------
@pytest.mark.parametrize("args, says", [
    (["--compare", "iterations=2"], "2 to 4 variants; got 1"),
    (["--compare", *[f"iterations={k}" for k in range(2, 7)]], "2 to 4 variants; got 5"),
    (["--compare", "iterations=2", "iterations=abc"], "iterations"),
    (["--compare", "iterations=2", "colour=red"], "no parameter or effect 'colour'"),
    (["--compare", "iterations=2", "iterations=2"], "are the same settings"),
    (["--compare", "iterations=2", "iterations"], "is not KEY=VALUE"),
    (["--compare", "iterations=2", "iterations=0"], "iterations"),
    (["--set", "iterations=3", "--compare", "iterations=2", "iterations=4"], "give it once"),
    (["--compare", "iterations=2,iterations=3", "iterations=4"], "given twice"),
    (["--compare", "shear=maybe", "shear=on"], "on or off"),
    (["--try", "2 vs 20 iterations", "--compare", "iterations=2", "iterations=4"],
     "drop --compare"),
])
def test_bad_variants_are_one_line_and_exit_2(args, says, capsys):
    assert main(["--headless", "--scene", "cloth", *args]) == 2
    err = capsys.readouterr().err
    assert says in err and err.count("\n") == 1 and "Traceback" not in err


def test_compare_needs_one_scene(capsys):
    assert main(["--headless", "--scene", "all", "--compare", "g=1", "g=2"]) == 2
    assert "--compare needs --scene NAME" in capsys.readouterr().err


def test_a_material_label_leaves_out_the_sliders_its_preset_sets():
    """Issue 26: four materials tagged every pane "material=cotton, mass=0.3, tension=15,
    compression=15, shear_stiffness=15, ..." (six lines a pane at 1024x768 with F2, and the
    header listed all seven names); a slider set apart from its preset is still named."""
    from scenes import get_scene
    cls = get_scene("mass_spring_cloth")
    scenes = [cls({"material": m}) for m in ("cotton", "silk", "denim", "leather")]
    assert labels(scenes) == ["material=cotton", "material=silk", "material=denim",
                              "material=leather"]
    scenes = [cls({"material": "cotton"}), cls({"material": "cotton", "tension": 40})]
    assert labels(scenes) == ["material=cotton", "material=custom, tension=40"]


def test_labels_say_what_differs_and_variants_keep_their_text():
    v = [parse_variant("substeps=1,iterations=10"), parse_variant("substeps=10, iterations=1")]
    overrides = resolve_variants(ClothScene, {"rows": 8}, v)
    scenes = [ClothScene(o) for o in overrides]
    assert labels(scenes) == ["iterations=10, substeps=1", "iterations=1, substeps=10"]
    assert v[1].text == "substeps=10, iterations=1" and v[1].settings["iterations"] == "1"
    with pytest.raises(ParamError, match="same settings"):   # 'on' and 'true' are one value
        resolve_variants(ClothScene, {}, [parse_variant("shear=on"), parse_variant("shear=true")])


# ----- 2. lockstep from the same start, the same input ----------------------------------------
DRAG = [{"t": 0.2, "type": "mouse_down", "button": 1, "pos": [480, 250]},
        {"t": 0.3, "type": "mouse_move", "pos": [420, 150]},
        {"t": 0.5, "type": "mouse_up", "button": 1, "pos": [420, 150]}]


def test_each_pane_is_the_variant_run_alone_with_the_same_input():
    """Lockstep changes nothing in a pane: with the same events each pane ends exactly where a
    single run of its variant ends (the same hash), and every pane stood at the same time."""
    events = parse_events(DRAG)
    variants = [{"iterations": 2}, {"iterations": 20}]
    runner = CompareRunner([ClothScene(small_cloth(**v)) for v in variants], events)
    times = []
    for _ in range(45):
        runner.run(1)
        times.append({r.scene.time for r in runner.runners})
    assert all(len(t) == 1 for t in times) and runner.next_event == 3
    for r, v in zip(runner.runners, variants):
        alone = run_scene(ClothScene(small_cloth(**v)), 45, parse_events(DRAG))
        assert r.scene.state_hash() == alone.scene.state_hash()
        assert r.scene.cloth.locked.sum() == alone.scene.cloth.locked.sum() == 11   # 10 pins
    a, b = (r.scene for r in runner.runners)                                        # + the drop
    assert a.state_hash() != b.state_hash()


def test_every_pane_receives_the_same_events_at_the_same_step():
    events = parse_events([{"t": 0.1, "type": "mouse_down", "button": 1, "pos": [5, 6]},
                           {"t": 0.25, "type": "key_down", "key": "u"},
                           {"t": 0.25, "type": "mouse_move", "pos": [7, 8]}])
    runner = CompareRunner([Dot({"g": 100}), Dot({"g": 300})], events)
    runner.run(30)
    a, b = (r.scene for r in runner.runners)
    assert a.seen == b.seen == [(6, "mouse_down", (5.0, 6.0)), (15, "key_down", (0.0, 0.0)),
                                (15, "mouse_move", (7.0, 8.0))]


def test_a_click_drops_a_ball_in_every_pymunk_pane():
    events = parse_events([{"t": 0.05, "type": "mouse_down", "button": 1, "pos": [200, 100]},
                           {"t": 0.06, "type": "mouse_up", "button": 1, "pos": [200, 100]}])
    runner = CompareRunner([FallingBallsScene({"iterations": k, "spawn_rate": 0.0})
                            for k in (2, 30)], events)
    runner.run(10)
    assert [r.scene.metrics()["balls_spawned"] for r in runner.runners] == [1, 1]


def test_different_hertz_share_one_clock():
    runner = CompareRunner([Dot({"hertz": 30}), Dot({"hertz": 60}), Dot({"hertz": 45})])
    assert runner.tick == pytest.approx(1 / 60)
    runner.run(60)
    assert [r.scene.steps for r in runner.runners] == [30, 60, 45]
    assert max(r.scene.time for r in runner.runners) == pytest.approx(1.0)
    assert min(r.scene.time for r in runner.runners) == pytest.approx(1.0)


# ----- 3. a blow-up stays in its pane -----------------------------------------------------------
def test_a_blow_up_is_rolled_back_and_held_in_its_pane_while_the_others_go_on():
    runner = CompareRunner([Dot(), Dot({"blowup_at": 50})], rollback=True)
    ran, rollbacks = runner.run(80)
    assert ran == 80 and list(rollbacks) == [1] and list(runner.held) == [1]
    assert "rolled back" in runner.held[1] and "held here" in runner.held[1]
    a, b = (r.scene for r in runner.runners)
    assert a.steps == 80 and b.is_finite() and b.steps < 50
    runner.run(10)
    assert a.steps == 90 and b.steps < 50                       # held: it does not step
    runner.deliver(InputEvent("key_down", key="r"))           # R: every pane from the start
    assert not runner.held and a.steps == b.steps == 0 and runner.world == 0.0


def test_headless_gives_one_json_object_per_variant(tmp_path, capsys):
    shot = tmp_path / "both.png"
    code = main(["--headless", "--scene", "cloth", "--set", "rows=8", "--set", "cols=10",
                 "--compare", "iterations=2", "substeps=4,iterations=2", "--steps", "30",
                 "--json", "--screenshot", str(shot)])
    assert code == 0
    out = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [o["variant"] for o in out] == ["iterations=2", "substeps=4,iterations=2"]
    assert [o["pane"] for o in out] == ["A", "B"] and [o["label"] for o in out] == \
        ["substeps=1", "substeps=4"]
    assert [o["params"]["substeps"] for o in out] == [1, 4]
    assert all(o["steps"] == 30 and o["params"]["rows"] == 8 and o["finite"] for o in out)
    assert out[0]["reference_error"]["metric"] == "max_stretch"
    assert out[1]["reference_error"]["value"] == out[1]["metrics"]["max_stretch"]
    assert out[0]["screenshot"] == out[1]["screenshot"] == str(shot)
    assert pygame.image.load(str(shot)).get_size() == (1920, 1080)    # every pane in one PNG


def test_headless_a_variant_that_goes_non_finite_stops_alone(capsys):
    args = ["--headless", "--scene", "mass_spring_cloth", "--set", "rows=6", "--set", "cols=6",
            "--compare", "integrator=symplectic_euler", "integrator=implicit_euler",
            "--steps", "40", "--json"]
    assert main(args) == 1
    captured = capsys.readouterr()
    a, b = (json.loads(line) for line in captured.out.splitlines())
    assert not a["finite"] and a["steps"] < 40 and b["finite"] and b["steps"] == 40
    assert "integrator=symplectic_euler" in captured.err and "non-finite" in captured.err


@pytest.mark.parametrize("cls", SCENES, ids=lambda c: c.name)
def test_every_scene_compares(cls, capsys):
    """Every scene, the pymunk ones included, runs as a comparison (here of two seeds)."""
    assert main(["--headless", "--scene", cls.name, "--compare", "seed=1", "seed=2",
                 "--steps", "3", "--json"]) == 0
    out = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [(o["variant"], o["steps"], o["params"]["seed"]) for o in out] == \
        [("seed=1", 3, 1), ("seed=2", 3, 2)]


# ----- 4. comparison cards ----------------------------------------------------------------------
def test_comparison_cards_run_headless_and_are_in_the_catalogue(capsys):
    assert main(["--headless", "--scene", "cloth", "--try", "2 vs 20 iterations", "--steps", "2",
                 "--json"]) == 0
    out = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [o["variant"] for o in out] == ["iterations=2", "iterations=20"]
    assert out[0]["try"]["compare"] == [{"iterations": 2}, {"iterations": 20}]
    assert main(["--list", "--json"]) == 0
    cards = {c["label"]: c for s in json.loads(capsys.readouterr().out)
             for c in s["tries"] + s["comparisons"]}
    assert cards["1x10 vs 10x1"]["compare"] == ["substeps=1,iterations=10",
                                               "substeps=10,iterations=1"]
    compare_cards = [label for label, c in cards.items() if "compare" in c]
    assert len(compare_cards) >= 5 and all(c.compare for s in SCENES for c in s.comparisons)


# ----- 5. the window: panes, the same gesture in every pane, the panel ---------------------------
def open_compare(size, variants=("g=100", "g=300"), shared=None) -> Window:
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode(size), [Dot])
    assert w.open_compare(Dot, shared or {}, [parse_variant(v) for v in variants])
    w.update(1 / 60)
    w.render()
    return w


def test_panes_side_by_side_in_a_wide_window_stacked_in_a_tall_one_at_both_text_sizes():
    for large in (False, True):
        TEXT.scale = 1.6 if large else 1.0
        try:
            wide = open_compare((1900, 700)).scene_view.grid.cells
            tall = open_compare((900, 1000)).scene_view.grid.cells
        finally:
            TEXT.scale = 1.0
        assert wide[0].top == wide[1].top and wide[0].right < wide[1].left
        assert tall[0].left == tall[1].left and tall[0].bottom < tall[1].top


def test_a_drag_on_one_pane_reaches_every_pane_in_world_coordinates():
    w = open_compare((1280, 800))
    view = w.scene_view
    layout_b = view.grid.panes[1].layout
    target = (150.0, 120.0)
    pos = layout_b.view.pt(target)
    ev = pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=pos, button=1)
    w.handle_pygame_event(ev)
    a, b = view.scenes
    assert a.seen[-1][1:] == b.seen[-1][1:] == ("mouse_down", pytest.approx(target, abs=1.0))
    assert np.allclose(a.x[0], b.x[0])
    assert w.recorded[-1]["type"] == "mouse_down"       # --record: replayed with the variants
    assert w.recorder.session.command("demo.json").startswith(
        "python -m app --headless --scene dot --compare g=100 g=300 --input demo.json")


def test_the_panel_edits_every_pane_or_one():
    w = open_compare((1280, 800), ("g=100", "g=300"))
    view = w.scene_view
    a, b = view.scenes
    assert view.apply_setting("count", 5) and a.p["count"] == b.p["count"] == 5
    assert not view.apply_setting("g", 50)              # what they differ in: pick a pane
    assert (a.p["g"], b.p["g"]) == (100.0, 300.0)
    assert "pick a pane" in w.messages[-1].text
    assert view.locked_settings() == {"g"} and "g" not in view.panel.entries
    view.set_target(2)                                  # pane B's own settings
    assert view.scene is b and "g" in view.panel.entries
    assert view.apply_setting("g", 500) and (a.p["g"], b.p["g"]) == (100.0, 500.0)
    assert view.apply_setting("count", 4) and (a.p["count"], b.p["count"]) == (5, 4)
    assert a.steps == b.steps == 0 and set(labels(view.scenes)[1].split(", ")) == {"count=4",
                                                                                   "g=500"}


def test_a_comparison_card_clicked_in_the_window_opens_its_panes():
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1280, 800)), [ClothScene])
    assert w.open_scene(ClothScene, small_cloth())
    card = ClothScene.find_card("1x10 vs 10x1")
    assert w.scene_view.apply_try(card)
    view = w.scene_view
    assert [s.p["substeps"] for s in view.scenes] == [1, 10]
    assert [s.p["rows"] for s in view.scenes] == [28, 28]          # the defaults plus the card
    w.update(1 / 60)
    w.render()
    assert "1x10 vs 10x1" in " ".join(m.text for m in w.messages)


# ----- 6. what the comparison cards promise, measured -------------------------------------------
def run_card(scene_cls, label: str, ticks: int) -> CompareRunner:
    card = scene_cls.find_card(label)
    variants = [Variant(str(v), dict(v)) for v in card.compare]
    overrides = resolve_variants(scene_cls, dict(card.settings), variants)
    runner = CompareRunner([scene_cls(o) for o in overrides])
    runner.run(ticks)
    return runner


@pytest.mark.parametrize("label", ["2 vs 20 iterations", "1x10 vs 10x1"])
def test_cloth_cards_ten_times_less_stretch(label):
    """'about ten times less stretch' for B, after 2 s hanging (measured 11x and 10x)."""
    a, b = (r.scene.metrics()["mean_stretch"] for r in run_card(ClothScene, label, 120).runners)
    assert 5 < a / b < 20


def test_explicit_vs_implicit_card_a_blows_up_b_hangs_on():
    from scenes.mass_spring_cloth import MassSpringClothScene
    scene = MassSpringClothScene({"integrator": "symplectic_euler"})
    assert 26 < scene.dt / scene.explicit_limit() < 28          # "27x ... for cotton at rest"
    runner = run_card(MassSpringClothScene, "Explicit vs implicit at 60 Hz", 30)
    a, b = runner.runners
    assert not a.finite and a.steps <= 10 and b.finite and b.steps == 30


def test_all_pairs_vs_grid_card_same_pairs_fewer_tests_round_off_apart():
    from scenes.particle_dance import ParticleDanceScene
    a, b = (r.scene for r in run_card(ParticleDanceScene, "All pairs vs grid", 30).runners)
    assert a.metrics()["pairs_interacting"] == b.metrics()["pairs_interacting"]
    assert b.metrics()["pair_tests"] < a.metrics()["pair_tests"] / 5
    assert 0 < np.abs(a.dance.ps.x - b.dance.ps.x).max() < 1e-6


def test_double_pendulum_substeps_card_b_stays_with_its_ghost_longer():
    from scenes.double_pendulum import DoublePendulumScene
    a, b = (r.scene.metrics() for r in run_card(DoublePendulumScene, "1 vs 10 substeps",
                                                600).runners)
    assert a["divergence_time"] is not None
    assert b["divergence_time"] is None or b["divergence_time"] > a["divergence_time"]
    assert b["energy_drift_max"] < a["energy_drift_max"]


def test_the_docs_compare_commands_run_as_written(tmp_path, capsys, monkeypatch):
    """The commands of the 'Compare mode' section (docs/instructors.md; the README's until
    issue 18) run: window ones headless for two
    steps with a screenshot (same scene, variants, instruments), headless ones as written."""
    import shlex
    from pathlib import Path
    text = (Path(__file__).resolve().parent.parent / "docs" / "instructors.md").read_text()
    block = text.split("## Compare mode, live plots, arrows", 1)[1].split("\n## ", 1)[0]
    commands = [shlex.split(line.strip())[3:] for line in block.splitlines()
                if line.strip().startswith("python -m app")]
    assert len(commands) == 4
    monkeypatch.chdir(tmp_path)
    for args in commands:
        if "--headless" not in args:
            args = args + ["--headless", "--steps", "2", "--screenshot", "shot.png"]
        assert main(args) == 0, (args, capsys.readouterr().err)
    assert (tmp_path / "lab-output" / "cloth.csv").read_text().startswith("variant,step,t (s),")


def test_a_slow_comparison_says_so_in_its_header_even_when_a_pane_has_its_own_words(monkeypatch):
    """The window left out its 'slower than real time' line whenever the scene says it in its
    own HUD; but a pane's first page shows only its headline, so in compare mode a slow pane
    (48x48 denim with solver=direct beside solver=cg) went unsaid: the header says it."""
    from app.window.scene_view import SETTLE_FRAMES
    from tests.test_window import slow_steps
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1280, 800)), [ClothScene])
    assert w.open_scene(ClothScene, small_cloth())
    assert w.scene_view.apply_try(ClothScene.find_card("1x10 vs 10x1"))
    for _ in range(SETTLE_FRAMES):
        w.update(1 / 60)
    slow_steps(monkeypatch, ClothScene, 0.02)
    monkeypatch.setattr(ClothScene, "real_time_words", lambda self: "not real time: its words")
    w.update(8 / 60)
    header = " ".join(str(getattr(x, "text", x)) for x in w.scene_view.header_lines())
    assert "slower than real time: physics takes" in header


def test_the_panes_of_a_comparison_show_one_world_rectangle_at_one_scale():
    """Each pane was fitted to its own scene's content_bounds(): cloth_collisions' heap card
    drew the crushed heap (1 substep) at twice the scale of the standing one (3 substeps), and
    a heap two to three times as tall looked ~1.6 times. The panes now share the union of their
    bounds: one scale, one world rectangle, and every scene's own bounds inside it."""
    from app.draw.panes import PaneGrid
    small = ClothScene({"rows": 6, "cols": 6})
    big = ClothScene({"rows": 40, "cols": 40})
    assert small.content_bounds() != big.content_bounds()
    grid = PaneGrid([small, big])
    for area in (pygame.Rect(0, 0, 1600, 700), pygame.Rect(0, 0, 800, 1000)):
        grid.forget()
        lines = [None, None]
        a, b = grid.fit(area, None, lines)
        assert a.bounds == b.bounds and a.view.scale == pytest.approx(b.view.scale)
        for scene in (small, big):
            x, y, w, h = scene.content_bounds()
            bx, by, bw, bh = a.bounds
            assert bx <= x and by <= y and x + w <= bx + bw and y + h <= by + bh
