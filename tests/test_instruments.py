"""The instruments (app/instruments.py): --csv (its columns and rows, numbers as in --json),
the live plot (P's list, the plot's room, axes readable at both text sizes, a line per variant)
and the velocity and force arrows (off: not one call; on: the measured net force is m a)."""

from __future__ import annotations

import csv
import json

import numpy as np
import pygame
import pytest

from app.__main__ import main
from app.compare import parse_variant
from app.draw import live_plot
from app.draw.text import TEXT
from app.instruments import Instruments
from app.runner import SceneRunner
from app.vectors import ForceProbe
from app.window import Window
from scenes.falling_balls import FallingBallsScene
from tests.test_compare import Dot


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


# ----- 1. --csv ----------------------------------------------------------------------------------
def test_csv_has_a_header_and_a_row_per_step_with_the_json_numbers(tmp_path, capsys):
    out = tmp_path / "cloth.csv"
    assert main(["--headless", "--scene", "cloth", "--set", "rows=6", "--set", "cols=6",
                 "--steps", "12", "--json", "--csv", str(out)]) == 0
    summary = json.loads(capsys.readouterr().out)
    rows = read_csv(out)
    metrics = list(summary["metrics"])
    assert [h.partition(" (")[0] for h in rows[0]] == ["step", "t"] + metrics   # names first
    assert rows[0][1] == "t (s)" and "pinned_drift (px)" in rows[0]          # then the unit
    assert "max_stretch" in rows[0] and "particles" in rows[0]     # a ratio, a count: bare
    assert len(rows) == 1 + 13 and summary["csv_rows"] == 13       # the start, then each step
    assert [r[0] for r in rows[1:]] == [str(k) for k in range(13)]
    assert float(rows[-1][1]) == pytest.approx(12 / 60)
    last = dict(zip(["step", "t"] + metrics, rows[-1]))
    for k, v in summary["metrics"].items():                        # as --json writes them
        assert last[k] == json.dumps(v), k


def test_csv_of_a_scene_file_heads_each_metric_with_its_kind_s_unit(tmp_path, capsys):
    out = tmp_path / "galton.csv"
    assert main(["--headless", "--scene", "scenes/files/galton_board.toml", "--steps", "1",
                 "--csv", str(out)]) == 0
    assert read_csv(out)[0] == ["step", "t (s)", "balls_dropped", "balls_in", "mean_x (px)"]


def test_csv_of_a_comparison_has_a_variant_column_and_null_as_an_empty_cell(tmp_path, capsys):
    out = tmp_path / "dp.csv"
    assert main(["--headless", "--scene", "double_pendulum", "--compare", "substeps=1",
                 "substeps=4", "--steps", "5", "--csv", str(out)]) == 0
    rows = read_csv(out)
    assert rows[0][:3] == ["variant", "step", "t (s)"] and "divergence_time (s)" in rows[0]
    assert [r[0] for r in rows[1:]] == ["substeps=1", "substeps=4"] * 6
    col = rows[0].index("divergence_time (s)")
    assert all(r[col] == "" for r in rows[1:])          # null until the ghost parts: empty


def test_csv_in_the_window_writes_a_row_per_frame(tmp_path):
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1024, 640)), [Dot])
    w.csv_path = str(tmp_path / "w.csv")
    assert w.open_scene(Dot)
    for _ in range(5):
        w.update(1 / 30)          # two steps a frame
        w.render()
    w.close()
    rows = read_csv(tmp_path / "w.csv")
    assert rows[0] == ["step", "t (s)", "y", "n", "label"]     # no unit known for a toy's
    assert [r[0] for r in rows[1:]] == ["0", "2", "4", "6", "8", "10"]
    assert rows[1][4] == "text"


def test_csv_and_plot_refuse_what_they_cannot_do(tmp_path, capsys):
    assert main(["--headless", "--scene", "cloth", "--plot", "stretchiness", "--screenshot",
                 str(tmp_path / "a.png")]) == 2
    err = capsys.readouterr().err
    assert "no such number" in err and "max_stretch" in err and err.count("\n") == 1
    assert main(["--headless", "--scene", "cloth", "--plot", "max_stretch"]) == 2
    assert "--screenshot" in capsys.readouterr().err
    assert main(["--headless", "--scene", "cloth", "--csv", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err


# ----- 2. the arrows -----------------------------------------------------------------------------
def test_arrows_off_cost_no_call_and_on_they_measure_the_net_force():
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1024, 640)), [Dot])
    assert w.open_scene(Dot, {"g": 50.0})
    view = w.scene_view
    for _ in range(10):
        w.update(1 / 60)
        w.render()
    assert not hasattr(w.scene, "arrow_calls")          # off: Scene.arrows() never called
    assert view.runner.observers == []                   # and nothing hooked on the steps
    w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_v, mod=0,
                                             scancode=0, unicode="v"))
    assert w.arrows and view.inst.arrows
    for _ in range(3):
        w.update(1 / 60)
        w.render()
    calls = w.scene.arrow_calls
    assert calls >= 3
    arrows, force = view.inst.gauges[0].probe.current(w.scene)
    assert force == pytest.approx(np.tile([0.0, 2.0 * 50.0], (3, 1)))   # m g, m = 2
    assert any("net force" in str(getattr(x, "keys", "")) for x in view.notes())
    view.toggle_arrows()                                  # off again: the calls stop
    for _ in range(5):
        w.update(1 / 60)
        w.render()
    assert w.scene.arrow_calls == calls and view.runner.observers == []


def test_the_net_force_on_a_falling_ball_is_m_g_and_on_a_resting_one_zero():
    scene = FallingBallsScene({"spawn_rate": 0.0})
    scene.on_click((300.0, 50.0), 1)                     # one ball, high in the air
    probe = ForceProbe()
    runner = SceneRunner(scene)
    runner.observers.append(lambda r: probe.observe(r.scene))
    runner.run(5)
    arrows, force = probe.current(scene)
    assert len(arrows.ids) == 1 and arrows.of == "every ball"
    assert force[0] == pytest.approx([0.0, arrows.mass[0] * 900.0], rel=1e-6)
    runner.run(600)                                       # it lands and comes to rest
    arrows, force = probe.current(scene)
    assert np.abs(force).max() < 0.01 * arrows.mass[0] * 900.0


# ----- 3. the live plot --------------------------------------------------------------------------
def test_p_lists_the_numbers_and_the_plot_gets_its_own_room():
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1024, 640)), [Dot])
    assert w.open_scene(Dot)
    view = w.scene_view
    whole = view.scene_area().height
    w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_p, mod=0,
                                             scancode=0, unicode="p"))
    picker = w.current_view
    assert picker.items()[:2] == ["y", "n"] and "label" not in picker.items()   # numbers only
    assert view.inst.plot == ["y"]             # it opens with a line drawn (the first number)
    for k in (pygame.K_DOWN, pygame.K_RETURN):                                  # and n
        w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, scancode=0,
                                                 unicode=""))
    assert view.inst.plot == ["y", "n"]
    for _ in range(6):
        w.update(1 / 60)
        w.render()
    plot = view.plot_rect()
    assert view.scene_area().height < whole and view.scene_area().bottom <= plot.top
    assert view.pane.layout.area.bottom <= plot.top                # the scene stays above it
    lines = view.inst.lines()
    assert [ln.label for ln in lines] == ["y", "n"] and len(lines[0].ts) == 7
    w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE, mod=0,
                                             scancode=0, unicode=""))
    assert w.current_view is view and view.plot_rect() is not None     # the plot stays


def test_a_compared_metric_is_a_line_per_variant_in_the_variants_colours():
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1280, 800)), [Dot])
    w.plot_start = ["y"]
    assert w.open_compare(Dot, {}, [parse_variant("g=100"), parse_variant("g=300")])
    for _ in range(4):
        w.update(1 / 60)
        w.render()
    lines = w.scene_view.inst.lines()
    assert [ln.label for ln in lines] == ["A y", "B y"]
    assert lines[0].color != lines[1].color
    assert lines[1].vs[-1] > lines[0].vs[-1]           # B falls faster (g = 300)


@pytest.mark.parametrize("scale", [1.0, 1.6])
def test_plot_axes_are_round_numbers_whose_labels_never_overlap(scale):
    TEXT.scale = scale
    try:
        surface = pygame.Surface((700, 220))
        ts = [k / 60 for k in range(600)]
        lines = [live_plot.Line("a", (255, 0, 0), ts, [1e-3 * np.sin(t) + 2e-3 for t in ts]),
                 live_plot.Line("b (%)", (0, 255, 0), ts, [1e-3 * t for t in ts], dash=1)]
        for log in (False, True):
            drawn = live_plot.draw_plot(surface, surface.get_rect(), lines, ts[-1], 10.0, log)
            for axis in ("x", "y"):
                rects = drawn[axis]
                assert len(rects) >= 2, (axis, log)
                assert all(surface.get_rect().contains(r) for r in rects)
                assert not any(a.colliderect(b) for i, a in enumerate(rects)
                               for b in rects[i + 1:]), (axis, log)
    finally:
        TEXT.scale = 1.0
    assert live_plot.nice_ticks(0.0, 10.0) == [0, 2, 4, 6, 8, 10]
    assert live_plot.nice_ticks(-0.013, 0.041, 6) == pytest.approx([-0.01, 0, 0.01, 0.02,
                                                                     0.03, 0.04])


def test_headless_plot_and_arrows_go_into_the_screenshot(tmp_path, capsys):
    shot = tmp_path / "p.png"
    assert main(["--headless", "--scene", "falling_balls", "--steps", "30", "--plot",
                 "balls_alive", "--arrows", "--screenshot", str(shot)]) == 0
    w, h = pygame.image.load(str(shot)).get_size()
    assert w == 960 and h > 720                          # the plot strip below the world


def test_instruments_off_hook_nothing():
    runner = SceneRunner(Dot())
    inst = Instruments()
    inst.attach([runner])
    assert runner.observers == []
    runner.run(5)
    assert not hasattr(runner.scene, "arrow_calls")
