"""Every registered scene, automatically: builds, steps a simulated second, draws off-screen,
reports finite metrics with the contract's names, prints nothing, hashes deterministically, and
replays input exactly as live events would. Adding a scene to scenes.SCENES adds it here."""

import math
import os
import subprocess
import sys

import numpy as np
import pygame
import pytest

from app.draw.hud import fmt_number
from app.draw.view import View
from app.headless import load_events, run_scene
from app.scene import InputEvent, ParamError, Scene
from app.window import Window
from scenes import SCENES

CONTRACT_METRICS = {
    "cloth": {"particles", "constraints", "iterations", "substeps", "max_stretch",
              "mean_stretch", "pinned_drift", "torn"},
    "falling_balls": {"balls_spawned", "balls_removed", "balls_alive", "tunneled"},
    "pivoting_l": {"angle_deg", "slide_distance", "slide_seen_min", "slide_seen_max", "pin_error"},
    "newtons_cradle": {"lifted", "balls_out", "middle_max_drift", "energy_ratio"},
    "double_pendulum": {"energy_drift", "reference_divergence", "divergence_time"},
    # per integrator (each an effect): error, step_us, energy_ratio
    "mass_spring_cloth": {"particles", "springs", "integrator", "omega_max", "explicit_limit_h",
                          "max_stretch", "mean_stretch", "energy", "cg_iterations",
                          "cg_converged", "cg_residual", "pinned_drift"},
    "integrators": {f"{name}_{m}" for name in ("euler", "symplectic_euler", "verlet", "midpoint",
                                               "rk4", "implicit_euler")
                    for m in ("error", "step_us", "energy_ratio")} | {"implicit_euler_cg_converged"},
    "particle_dance": {"particles", "pair_tests", "neighbour_method", "kinetic_energy"},
}

ids = [s.name for s in SCENES]


def one_second(scene: Scene) -> None:
    for _ in range(round(1.0 / scene.dt)):
        scene.advance()


def drag_events(scene_cls) -> list[InputEvent]:
    """A left-button drag across the middle of the world, then a right click."""
    w, h = scene_cls.world_size
    return [InputEvent("mouse_move", (w * 0.5, h * 0.3), t=0.1),
            InputEvent("mouse_down", (w * 0.5, h * 0.3), 1, t=0.1),
            InputEvent("mouse_move", (w * 0.6, h * 0.4), t=0.2),
            InputEvent("mouse_move", (w * 0.7, h * 0.5), t=0.3),
            InputEvent("mouse_up", (w * 0.7, h * 0.5), 1, t=0.4),
            InputEvent("mouse_down", (w * 0.7, h * 0.5), 3, t=0.5),
            InputEvent("mouse_up", (w * 0.7, h * 0.5), 3, t=0.5)]


def test_registry_is_unique_and_described():
    assert len(SCENES) >= 1
    assert len(set(ids)) == len(ids)
    for cls in SCENES:
        assert cls.name and cls.title and cls.category, cls
        assert (cls.__doc__ or "").strip(), f"{cls.name} needs a docstring (the help overlay)"
        names = cls.setting_names()
        assert len(names) == len(set(names)), f"{cls.name}: a param and an effect share a name"


@pytest.mark.parametrize("cls", SCENES, ids=ids)
def test_declared_defaults_are_valid(cls):
    for prm in cls.all_params():
        assert prm.parse(prm.default) == prm.default, prm
        assert prm.help, f"{cls.name}.{prm.name} needs a one-line help"
    for eff in cls.effects:
        assert eff.help, f"{cls.name} effect {eff.name} needs a one-line help"


@pytest.mark.parametrize("cls", SCENES, ids=ids)
def test_scene_builds_steps_draws_and_reports(cls, capfd):
    scene = cls()
    one_second(scene)
    assert scene.is_finite()
    surface = pygame.Surface(cls.world_size)
    scene.draw(surface, View())
    small = pygame.Surface((cls.world_size[0] // 2 + 100, cls.world_size[1] // 2))
    scene.draw(small, View.fit(cls.world_size, (0, 0, *small.get_size())))
    metrics = scene.metrics()
    assert CONTRACT_METRICS.get(cls.name, set()) <= set(metrics)
    for key, value in metrics.items():
        if value is None:                 # a value that does not exist yet (null, "-")
            assert fmt_number(value) == "-"
            continue
        if isinstance(value, str):        # a named choice (neighbour_method, integrator)
            assert value, key
            continue
        assert isinstance(value, (int, float, np.integer, np.floating)), (key, value)
        assert math.isfinite(value), (key, value)
    from app.draw.hud import Line        # a warning line (slower than real time) is a Line
    assert all(isinstance(line, (str, Line)) and str(getattr(line, "text", line))
               for line in scene.hud_lines())
    assert all(math.isfinite(v) for v in scene.effect_costs().values())
    assert len(scene.state_hash()) == 16
    out, err = capfd.readouterr()       # also what C code (Chipmunk, SDL) writes
    assert out == "" and err == "", "a scene must not print"


@pytest.mark.parametrize("cls", SCENES, ids=ids)
def test_live_events_in_the_window_replay_headless_to_the_same_state(cls, tmp_path):
    """The same drag done live in the window (pygame events in screen pixels, at a zoom below
    1, with uneven frames), recorded, and replayed headless from the file: one state."""
    pygame.display.init()
    pygame.font.init()
    window = Window(pygame.display.set_mode((1000, 700)), [cls], screenshot_dir=tmp_path)
    assert window.open_scene(cls)
    pending = drag_events(cls)
    frames = [0.013, 0.021, 1 / 60, 0.03, 0.011] * 8
    for frame in frames:
        while pending and pending[0].t <= window.session_time + 1e-9:
            e = pending.pop(0)
            screen = window.view.pt(e.pos)
            if e.kind == "mouse_move":
                ev = pygame.event.Event(pygame.MOUSEMOTION, pos=screen, rel=(0, 0),
                                        buttons=(0, 0, 0))
            else:
                kind = pygame.MOUSEBUTTONDOWN if e.kind == "mouse_down" else pygame.MOUSEBUTTONUP
                ev = pygame.event.Event(kind, pos=screen, button=e.button)
            window.handle_pygame_event(ev)
        window.update(frame)
    assert not pending and window.scene.is_finite()
    out = tmp_path / "demo.json"
    assert window.write_recording(out) == len(drag_events(cls))
    replay = run_scene(cls(), window.session_steps, load_events(str(out)))
    assert replay.scene.state_hash() == window.scene.state_hash()
    again = run_scene(cls(), window.session_steps, load_events(str(out)))
    assert again.scene.state_hash() == replay.scene.state_hash()


@pytest.mark.parametrize("cls", SCENES, ids=ids)
def test_snapshot_restore_and_reset(cls):
    scene = cls()
    for _ in range(10):
        scene.advance()
    snap = scene.snapshot()
    assert snap is not None, "every scene can be rolled back (the window's non-finite guard)"
    before = scene.state_hash()
    for _ in range(10):
        scene.advance()
    scene.restore(snap)
    assert scene.state_hash() == before
    scene.reset()
    assert scene.time == 0.0 and scene.steps == 0
    assert scene.state_hash() == cls().state_hash()


@pytest.mark.parametrize("cls", SCENES, ids=ids)
def test_bad_values_are_refused_and_nothing_changes(cls):
    scene = cls()
    before = dict(scene.p)
    for key, value in [("hertz", 0), ("hertz", float("nan")), ("substeps", -1),
                       ("seed", "x"), ("no_such_setting", 1)]:
        with pytest.raises(ParamError):
            scene.set(key, value)
    for prm in cls.all_params():
        if prm.kind in (int, float):
            for value in (float("nan"), float("inf"), prm.hi + 1, prm.lo - 1):
                with pytest.raises(ParamError):
                    scene.set(prm.name, value)
    assert scene.p == before


def test_importing_the_scenes_has_no_side_effects():
    env = {k: v for k, v in os.environ.items() if not k.startswith("SDL_")}
    code = ("import os, scenes, pygame; "
            "assert 'SDL_VIDEODRIVER' not in os.environ; "
            "assert not pygame.display.get_init(); print(len(scenes.SCENES))")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    r = subprocess.run([sys.executable, "-c", code], cwd=root, env=env, capture_output=True,
                       text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(len(SCENES))
