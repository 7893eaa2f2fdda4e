"""The command line: --list, --json keys, every kind of bad input, exit codes.

A few runs go through a real subprocess (what a user types); the full matrix of bad input runs
in-process through the same main() to keep the suite fast."""

import json
import os
import subprocess
import sys

import pytest

import scenes
from app.__main__ import main
from tests.toy_scenes import Blowup, Toy

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
JSON_KEYS = {"scene", "steps", "sim_seconds", "wall_seconds", "step_ms", "params", "effects",
             "metrics", "state_hash", "finite", "events"}


def run_cli(*args, env_extra=None):
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy")
    env.update(env_extra or {})
    return subprocess.run([sys.executable, "-m", "app", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=120)


@pytest.fixture
def toy_registry(monkeypatch):
    monkeypatch.setattr(scenes, "SCENES", [Toy, Blowup])
    monkeypatch.setattr(Toy, "aliases", {"strength": "g"})


def test_list_names_every_registered_scene():
    r = run_cli("--list")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.strip().splitlines()
    assert [line.split()[0] for line in lines] == [c.name for c in scenes.menu_scenes()]
    assert r.stderr == ""


def test_headless_json_has_the_contract_keys_and_repeats_its_hash():
    name = scenes.SCENES[0].name
    runs = [run_cli("--headless", "--scene", name, "--steps", "30", "--json") for _ in range(2)]
    for r in runs:
        assert r.returncode == 0, r.stderr
    a, b = (json.loads(r.stdout) for r in runs)
    assert JSON_KEYS <= set(a)
    assert a["scene"] == name and a["steps"] == 30 and a["finite"] is True
    assert a["state_hash"] == b["state_hash"]
    assert a["params"]["hertz"] == scenes.SCENES[0].param("hertz").default


def test_bad_scene_through_a_real_subprocess_is_one_line_and_exit_2():
    r = run_cli("--headless", "--scene", "nope")
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "nope" in r.stderr and "accepted" in r.stderr
    assert "Traceback" not in r.stderr


def test_window_on_a_machine_without_a_display_is_exit_2():
    # what a CI machine or an ssh session has: no DISPLAY, no Wayland, no SDL driver chosen
    env = {k: v for k, v in os.environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    r = subprocess.run([sys.executable, "-m", "app", "--scene", scenes.SCENES[0].name,
                        "--seconds", "1"], cwd=ROOT, env=env, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2, r.stderr
    assert r.stderr.count("\n") == 1 and "display" in r.stderr


def test_window_without_a_display_is_exit_2():
    r = run_cli("--scene", scenes.SCENES[0].name, "--seconds", "1",
                env_extra={"SDL_VIDEODRIVER": "offscreen-does-not-exist"})
    assert r.returncode == 2, r.stderr
    assert r.stderr.count("\n") == 1 and "display" in r.stderr


BAD = [
    (["--headless", "--scene", "nope"], "unknown scene"),
    (["--headless"], "--scene"),
    (["--headless", "--scene", "toy", "--seconds", "0"], "seconds"),
    (["--headless", "--scene", "toy", "--seconds", "-1"], "seconds"),
    (["--headless", "--scene", "toy", "--seconds", "nan"], "seconds"),
    (["--headless", "--scene", "toy", "--seconds", "inf"], "seconds"),
    (["--headless", "--scene", "toy", "--seconds", "abc"], "seconds"),
    (["--headless", "--scene", "toy", "--steps", "0"], "steps"),
    (["--headless", "--scene", "toy", "--steps", "2.5"], "steps"),
    (["--headless", "--scene", "toy", "--set", "nope=1"], "no parameter"),
    (["--headless", "--scene", "toy", "--set", "g"], "KEY=VALUE"),
    (["--headless", "--scene", "toy", "--set", "g=abc"], "not a number"),
    (["--headless", "--scene", "toy", "--set", "g=nan"], "finite"),
    (["--headless", "--scene", "toy", "--set", "g=inf"], "finite"),
    (["--headless", "--scene", "toy", "--set", "g=-5"], "out of range"),
    (["--headless", "--scene", "toy", "--set", "size=2.5"], "not an integer"),
    (["--headless", "--scene", "toy", "--set", "hertz=0"], "out of range"),
    (["--headless", "--scene", "toy", "--set", "substeps=0"], "out of range"),
    (["--headless", "--scene", "toy", "--set", "shape=star"], "one of"),
    (["--headless", "--scene", "toy", "--set", "gravity=maybe"], "on or off"),
    (["--headless", "--scene", "toy", "--input", "/nonexistent/events.json"], "cannot read"),
    (["--scene", "all"], "--headless"),
    (["--headless", "--scene", "toy", "--record", "x.json"], "--record"),
    (["--bogus"], "unrecognized"),
    (["bench", "nope"], "unknown benchmark"),
    (["bench", "cloth", "--out", "/proc/no-such-folder"], "cannot write"),
    (["--headless", "--scene", "toy", "--seconds", "1e308"], "at most"),
    (["--headless", "--scene", "toy", "--steps", "99999999999"], "steps"),
    (["--headless", "--scene", "toy", "--screenshot", "/proc/no-such-folder/x.png"],
     "cannot write"),
    (["--headless", "--scene", "toy", "--screenshot", "shot.txt"], ".png"),
    (["--headless", "--scene", "toy", "--screenshot", ""], "file name"),
    (["--headless", "--scene", "toy", "--set", "gravity=900"], "strength"),
    (["--headless", "--scene", "toy", "--set", "g=1", "--set", "strength=2"], "same setting"),
]


@pytest.mark.parametrize("args,fragment", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_usage_is_one_line_on_stderr_and_exit_2(toy_registry, capsys, args, fragment):
    assert main(args) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1, err
    assert fragment in err


BAD_INPUT_FILES = [
    ("{not json", "not valid JSON"),
    ('{"t": 0}', "list"),
    ('[{"t": -1, "type": "mouse_down", "button": 1, "pos": [1, 2]}]', "'t'"),
    ('[{"t": "soon", "type": "mouse_down", "button": 1, "pos": [1, 2]}]', "'t'"),
    ('[{"t": 0, "type": "click", "button": 1, "pos": [1, 2]}]', "'type'"),
    ('[{"t": 0, "type": "mouse_down", "button": 1, "pos": [1]}]', "'pos'"),
    ('[{"t": 0, "type": "mouse_down", "button": 7, "pos": [1, 2]}]', "'button'"),
    ('[{"t": 0, "type": "key_down"}]', "'key'"),
    ('[3]', "object"),
    ('[{"t": 0, "type": "mouse_move", "pos": [1, 2], "button": "x"}]', "'button'"),
    ('[{"t": 0, "type": "mouse_down", "pos": [1, 2], "button": true}]', "'button'"),
    ('[{"t": 0, "type": "mouse_down", "pos": [NaN, 2], "button": 1}]', "'pos'"),
]


@pytest.mark.parametrize("text,fragment", BAD_INPUT_FILES)
def test_malformed_input_file_is_refused(toy_registry, capsys, tmp_path, text, fragment):
    path = tmp_path / "events.json"
    path.write_text(text)
    assert main(["--headless", "--scene", "toy", "--input", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err, err


def test_nonfinite_run_reports_finite_false_and_exits_1(toy_registry, capsys):
    assert main(["--headless", "--scene", "blowup", "--steps", "100", "--json"]) == 1
    out, err = capsys.readouterr()
    summary = json.loads(out)
    assert summary["finite"] is False and summary["steps"] == 11
    assert "non-finite" in err and "substeps" in err


def test_set_reaches_the_scene_and_effects_switch_off(toy_registry, capsys):
    assert main(["--headless", "--scene", "toy", "--steps", "10", "--json",
                 "--set", "g=100", "--set", "gravity=off", "--set", "substeps=3"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["params"]["g"] == 100.0 and s["params"]["substeps"] == 3
    assert s["effects"] == []
    assert s["metrics"]["y"] == 100.0       # no gravity, no vertical motion


def test_scene_all_prints_one_object_per_scene(toy_registry, capsys):
    assert main(["--headless", "--scene", "all", "--steps", "5", "--json"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert [json.loads(line)["scene"] for line in lines] == ["toy", "blowup"]


def test_input_replay_reaches_the_scene(toy_registry, capsys, tmp_path):
    path = tmp_path / "events.json"
    path.write_text(json.dumps([{"t": 0.5, "type": "mouse_down", "button": 1, "pos": [300, 40]},
                                {"t": 0.5, "type": "mouse_up", "button": 1, "pos": [300, 40]}]))
    assert main(["--headless", "--scene", "toy", "--steps", "31", "--json", "--set",
                 "gravity=off", "--input", str(path)]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["events"] == 2 and s["metrics"]["y"] == 40.0


def test_screenshot_writes_a_png(toy_registry, capsys, tmp_path):
    out = tmp_path / "shot.png"
    assert main(["--headless", "--scene", "toy", "--steps", "3", "--screenshot", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_r_key_in_the_input_resets_the_scene_like_the_window(toy_registry, capsys, tmp_path):
    path = tmp_path / "events.json"
    path.write_text(json.dumps([{"t": 0.25, "type": "key_down", "key": "r"},
                                {"t": 0.25, "type": "key_up", "key": "r"}]))
    assert main(["--headless", "--scene", "toy", "--steps", "30", "--json",
                 "--input", str(path)]) == 0
    reset_run = json.loads(capsys.readouterr().out)
    # 15 steps before the reset, 15 after it: the state is that of a fresh 15-step run.
    assert main(["--headless", "--scene", "toy", "--steps", "15", "--json"]) == 0
    fresh = json.loads(capsys.readouterr().out)
    assert reset_run["state_hash"] == fresh["state_hash"]


def test_values_that_do_not_fit_together_are_refused(capsys):
    assert main(["--headless", "--scene", "newtons_cradle", "--set", "balls=3",
                 "--set", "lifted=3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "lifted" in err and "balls-1" in err


def test_screenshot_path_that_is_a_folder_is_refused_before_the_run(toy_registry, capsys, tmp_path):
    folder = tmp_path / "looks_like.png"
    folder.mkdir()
    assert main(["--headless", "--scene", "toy", "--steps", "3", "--screenshot", str(folder)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "folder" in err


def test_an_alias_sets_the_same_setting(toy_registry, monkeypatch, capsys):
    monkeypatch.setattr(Toy, "aliases", {"pull": "gravity", "strength": "g"})
    assert main(["--headless", "--scene", "toy", "--steps", "2", "--json", "--set", "pull=off",
                 "--set", "strength=5"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["effects"] == [] and s["params"]["g"] == 5.0 and "strength" not in s["params"]
