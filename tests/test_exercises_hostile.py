"""A grader a course can trust (issue 16): nothing a student's file does can hang the grader,
change a verdict, leave a process behind or flood the terminal; the grader's own errors are the
grader's; a NaN never passes; the live exercise scenes survive whatever the student's code
returns or prints. Each hostile file in tests/exercise_answers/hostile/ is replayed here, through
the grader or the real command line."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pygame
import pytest

from app.__main__ import main
from app.draw.view import View
from app.exercises import get_exercise
from app.exercises.base import Check, Exercise, Result
from app.exercises.channel import (HEADER, MAGIC, MAX_FRAME, ChannelError, FrameReader, encode,
                                   parse)
from app.exercises.grade import OUTPUT_SHOWN, grade, grade_many
from app.exercises.live import exercise_scene
from app.scene import SceneError

ROOT = Path(__file__).resolve().parent.parent
HOSTILE = ROOT / "tests" / "exercise_answers" / "hostile"
VERLET = get_exercise("verlet")


# A hang guard, not a speed claim (issue 27: a suite that passes under load): what is checked is
# what waited (the report's "still running after 0.3 s", "not run"); the wall clock only catches
# a grader that waits for ever, with room for a machine loaded to 20 on 2 cores.
HANG = 60.0

def run_cli(*args: str, env: dict | None = None,
            timeout: float = 2 * HANG) -> subprocess.CompletedProcess:
    full = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy", **(env or {}))
    return subprocess.run([sys.executable, "-m", "app", *args], cwd=ROOT, env=full,
                          capture_output=True, text=True, timeout=timeout)


def graded(name: str, timeout: float = 20.0):
    """Grade a hostile file. The floor of each time limit (the import's whole limit) is 20 s:
    a file expected to finish must not be cut off on a loaded machine (the 20 MB of prints at
    import take ~0.3 CPU-s: ~4 s at load 20 on 2 cores); files meant to run out of time pass
    their own small limit."""
    start = time.monotonic()
    report = grade(VERLET, str(HOSTILE / f"{name}.py"), timeout=timeout)
    return report, time.monotonic() - start


# ----- hostile files through the grader ----------------------------------------------------------
# file -> (words every failed check's text holds, or, for 'imports', the import's)
FAILS = {
    "verlet_exits": ("every", "exit code 3"),
    "verlet_killpg": ("every", ""),         # its kill reaches its own sandbox only
    "verlet_channel_junk": ("imports", "bytes that are not a frame"),
    "verlet_forged_frame": ("imports", "without this run's token"),
    "verlet_half_header": ("every", "a damaged channel"),
    "verlet_stdin": ("imports", "EOFError"),
    "verlet_patches_grader": ("imports", "KeyError: 'app.exercises.grade'"),
    "verlet_forged_token": ("every", ""),
    "verlet_thread": ("free fall", ""),
    # the second pass (issue 16)
    # not in its sandbox; or, where the harness holds the module (stubbed), refused by name
    "verlet_reexports_lab": ("imports", ("No module named 'app.physics'", "the lab's own code")),
    "verlet_closes_fds": ("imports", "channel was closed or redirected"),
    "verlet_dup_over_channel": ("imports", "channel was closed or redirected"),
    "verlet_segfault": ("every", "killed by signal 11 (SIGSEGV)"),
}


@pytest.mark.parametrize("name", sorted(FAILS))
def test_a_hostile_file_ends_quickly_with_failed_checks(name):
    report, seconds = graded(name)
    where, words = FAILS[name]
    checks = {c.name: c for c in report.checks}
    failed = [c for c in report.checks if not c.passed]
    if where == "imports":
        assert report.checks[0].name == "imports" and not report.checks[0].passed
        assert any(w in report.checks[0].error for w in (
            words if isinstance(words, tuple) else (words,))), report.text()
        assert all(c.measured == "not run" for c in report.checks[1:])
    elif where == "every":
        assert len(failed) == len(VERLET.checks), report.text()
        assert all(words in f"{c.measured} {c.error}" for c in failed), report.text()
    else:
        assert not checks[where].passed, report.text()
    assert "Traceback" not in report.text() and "still running" not in report.text()
    assert seconds < 60.0         # no check's time limit hit (a new child per failed check)


def test_patching_the_grader_from_inside_changes_no_verdict():
    # once 5/5 with a step that does nothing: the verdict was computed in the student's process;
    # then 'malformed values' (the verdict moved to the parent); now the grader is not even in
    # the child's memory (a fresh Python that imports the harness only)
    report, _ = graded("verlet_patches_grader")
    assert not any(c.passed for c in report.checks)
    assert "KeyError: 'app.exercises.grade'" in report.checks[0].error, report.text()


def test_a_frame_forged_with_the_stolen_token_only_carries_raw_values_the_parent_judges():
    report, _ = graded("verlet_forged_token")
    first = report.checks[0]           # the forged frame arrived first and was judged: 550 px off
    assert not first.passed and "px off the parabola" in first.measured


def test_an_endless_import_is_stopped_at_the_limit_and_nothing_else_waits():
    report, seconds = graded("verlet_endless_import", timeout=0.3)
    measured = report.checks[0].measured          # when it was stopped: the limit, or a little
    assert measured.startswith("still running after ") and measured.endswith(" s")  # after it
    assert 0.3 <= float(measured.split()[-2]) < HANG, measured    # on a loaded machine (0.4 s)
    assert all(c.measured == "not run" for c in report.checks[1:])
    assert seconds < HANG


def test_several_endless_files_through_check_all_each_cost_one_time_limit(tmp_path, capsys):
    # once: 8 endless files took six minutes (every check waited its limit); now one limit per
    # exercise, several exercises at once (the full 8 at the default 10 s: the slow test below)
    folder = tmp_path / "endless"
    folder.mkdir()
    for name in ("verlet", "constraints", "spring"):
        fn = {"verlet": "verlet_step", "constraints": "satisfy_rods", "spring": "spring_forces"}
        (folder / f"{name}.py").write_text(
            f"def {fn[name]}(*args):\n    while True:\n        pass\n")
    start = time.monotonic()
    assert main(["exercise", "check", "all", "--path", str(folder), "--timeout", "0.3"]) == 1
    seconds = time.monotonic() - start
    out = capsys.readouterr().out
    assert out.count("still running after") == 3 and "ran out of time" in out
    assert seconds < 60.0, seconds     # each its own limit, not one per check


@pytest.mark.slow
def test_eight_endless_files_through_check_all_finish_in_about_a_minute(tmp_path):
    """The issue's figure: 8 endless files, the default 10 s limit (about 40 s: two at a time on
    two cores; the other two exercises' files are missing)."""
    folder = tmp_path / "endless"
    folder.mkdir()
    for e in [e for e in __import__("app.exercises", fromlist=["EXERCISES"]).EXERCISES][:8]:
        (folder / f"{e.name}.py").write_text(
            "".join(f"def {fn}(*args):\n    while True:\n        pass\n\n" for fn in e.functions))
    start = time.monotonic()
    r = run_cli("exercise", "check", "all", "--path", str(folder), timeout=300)
    assert r.returncode == 1 and r.stdout.count("still running after 1") == 8  # 10 s or more
    assert time.monotonic() - start < 90


def marked(monkeypatch) -> str:
    """A mark in the environment of every process the student's code starts (the sandbox passes
    LAB_TEST_* on): `left_behind(mark)` finds them from outside its PID namespace."""
    mark = f"{os.getpid()}-{time.monotonic_ns()}"
    monkeypatch.setenv("LAB_TEST_MARK", mark)
    monkeypatch.setenv("LAB_TEST_PID_FILE", "pids")      # in the child's own folder
    return mark


def left_behind(mark: str, within: float = 5.0) -> list[int]:
    """The live processes that carry `mark` (none, once the grader is done: waits `within` s)."""
    def find() -> list[int]:
        found = []
        for entry in os.listdir("/proc"):
            if entry.isdigit() and alive(int(entry)):
                try:
                    with open(f"/proc/{entry}/environ", "rb") as f:
                        if f"LAB_TEST_MARK={mark}".encode() in f.read():
                            found.append(int(entry))
                except OSError:
                    pass
        return found
    deadline = time.monotonic() + within
    while (found := find()) and time.monotonic() < deadline:
        time.sleep(0.05)
    return found


def test_no_process_the_students_file_started_outlives_the_check(monkeypatch):
    mark = marked(monkeypatch)
    graded("verlet_background")
    assert left_behind(mark) == []


def alive(pid: int) -> bool:
    """True if the process exists and is not a zombie (a killed orphan waits for init)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_output_is_captured_and_capped(capsys):
    # once: 280 MB of prints passed through uncapped
    report, seconds = graded("verlet_prints")
    assert report.passed, report.text()
    assert report.output_bytes > 20_000_000 and len(report.output.encode()) <= OUTPUT_SHOWN
    assert "more bytes not shown" in report.output_text()
    assert capsys.readouterr().out == ""           # nothing of theirs on the grader's stdout


def test_the_students_output_is_shown_in_short_lines_without_control_characters():
    # once (hostile run, seed 27): a file that printed 10 MB of 'x' put one line of 8,000
    # characters on the grader's stderr; an escape sequence would clear the teacher's terminal
    from app.exercises.report import OUTPUT_LINE, Report
    text = Report("verlet", "s.py", [], output="x" * 8000 + "\n\x1b[2Jok\n",
                  output_bytes=10_000_001).output_text()
    assert all(len(line) <= OUTPUT_LINE for line in text.splitlines())
    assert "\x1b" not in text and "\\x1b[2Jok" in text and "more bytes not shown" in text


_ARMED: list = []        # the at-fork hook below sends a Ctrl-C only while armed
os.register_at_fork(after_in_parent=lambda: _ARMED and os.kill(os.getpid(), __import__(
    "signal").SIGINT))


def test_a_ctrl_c_during_the_sandbox_probe_is_raised_not_dropped(capfd):
    # once (hostile run, seed 27): `exercise grade` interrupted in its first half second printed
    # "Exception ignored in: <function _releaseLock>" and a KeyboardInterrupt traceback: the
    # sandbox's probe forked with os.fork, whose at-fork hooks drop a Ctrl-C
    import signal
    from app.exercises import sandbox

    def ctrl_c(sig, frame):           # as the grader's own handler (classroom._CtrlC)
        raise KeyboardInterrupt
    before = signal.signal(signal.SIGINT, ctrl_c)
    _ARMED.append(1)
    try:
        with pytest.raises(KeyboardInterrupt):
            sandbox._unshare_probe(0)
    finally:
        _ARMED.clear()
        signal.signal(signal.SIGINT, before)
    assert "Exception ignored" not in capfd.readouterr().err


def test_the_file_is_imported_once_per_exercise():
    # once: a file that slept 9 s at import was imported again for every check (56 s)
    report, _ = graded("verlet_import_counter")
    assert report.passed and report.output.count("imported") == 1


def test_a_huge_exception_message_is_cut_to_a_readable_size():
    report, _ = graded("verlet_huge_message")
    for c in report.checks:
        assert "ValueError: no no" in c.error and len(c.error) < 2000, len(c.error)


def test_a_name_linked_to_dev_zero_is_refused_not_read(tmp_path, capsys):
    # once: each child read /dev/zero until its time limit (~15 GB at the default 10 s)
    folder = tmp_path / "w"
    folder.mkdir()
    (folder / "verlet.py").symlink_to("/dev/zero")
    start = time.monotonic()
    assert main(["exercise", "check", "all", "--path", str(folder), "--timeout", "5"]) == 1
    assert time.monotonic() - start < 60        # no child read it: each is refused at once
    out = capsys.readouterr().out
    assert "is not a regular file" in out
    assert main(["exercise", "check", "verlet", "--path", str(folder / "verlet.py")]) == 2


@pytest.mark.parametrize("argv", [
    ["exercise", "check", "verlet", "--ref"], ["exercise", "check", "verlet", "--js"],
    ["exercise", "check", "verlet", "--tim", "5"], ["exercise", "check", "verlet", "--pa", "x"],
    ["exercise", "check", "verlet", "--path", ""], ["exercise", "check", "all", "--path", " "],
], ids=["ref", "js", "tim", "pa", "empty_path", "blank_folder"])
def test_abbreviated_options_and_an_empty_path_are_refused(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("python -m app: error:"), err


# ----- the parent's verdicts ---------------------------------------------------------------------
def fake(judge, measure=lambda m: {"v": 1.0}) -> Exercise:
    from types import SimpleNamespace
    return Exercise("fake", "a fake", "-", (), lambda: SimpleNamespace(),
                    (Check("the check", measure, judge),))


def test_the_graders_own_error_is_reported_as_the_graders():
    # once: the cradle's energy None compared with a float, shown as the student's exception
    def judge(raw):
        return Result(raw.number("v") > None, "-", "-")      # a bug in a judge
    report = next(grade_many([(fake(judge), None)]))
    c = report.checks[0]
    assert not c.passed and c.measured == "grader error"
    assert "the grader itself failed" in c.error and "not in your code" in c.error


def test_a_nan_never_passes_whatever_a_judge_compared():
    # once: max(x, abs(nan)) kept x, and NaN bobs passed 'energy kept' with 0.000%
    def judge(raw):
        return Result(max(0.0, abs(raw.number("v"))) < 1.0, "a drift", "< 1")
    report = next(grade_many([(fake(judge, lambda m: {"v": math.nan}), None)]))
    assert not report.checks[0].passed and "NaN" in report.checks[0].hint


def test_the_channel_refuses_junk_oversize_foreign_and_deep_frames():
    token = "ab" * 16
    good = encode(token, 0, "ok", {"x": [1.0, float("nan")]})
    reader = FrameReader()
    frames = reader.feed(good[:5]) + reader.feed(good[5:])       # split anywhere
    assert parse(frames[0], token, 0).raw["x"][0] == 1.0
    assert reader.feed(b"junk junk") == [] and "not a frame" in reader.junk
    too_big = FrameReader()
    assert too_big.feed(HEADER.pack(MAGIC, MAX_FRAME + 1)) == [] and "bytes (at most" in \
        too_big.junk
    for payload, words in ((encode("cd" * 16, 0, "ok")[HEADER.size:], "token"),
                           (encode(token, 3, "ok")[HEADER.size:], "while check 0"),
                           (b"[" * 5000 + b"]" * 5000, "nested deeper"),
                           (b"\xff\xfe", "not JSON"),
                           (encode(token, 0, "passed")[HEADER.size:], "unknown status")):
        with pytest.raises(ChannelError, match=words):
            parse(payload, token, 0)


# ----- the live scenes survive what the student's code does --------------------------------------
def copy_as(tmp_path: Path, hostile: str, name: str) -> Path:
    path = tmp_path / f"{name}.py"          # the file's name says which exercise it is
    path.write_text((HOSTILE / f"{hostile}.py").read_text())
    return path


def test_a_scene_whose_file_starts_a_non_daemon_thread_still_ends(tmp_path):
    # once: the lab waited for the student's thread at exit, for ever
    path = copy_as(tmp_path, "verlet_thread", "verlet")
    r = run_cli("--headless", "--scene", f"exercise:{path}", "--steps", "3", "--json")
    assert r.returncode == 0 and json.loads(r.stdout)["steps"] == 3, r.stderr


def test_fd_level_output_and_subprocesses_never_reach_the_json(tmp_path):
    # once: os.write(1, ...) and subprocess.run(["echo", ...]) in the step polluted --json
    path = copy_as(tmp_path, "verlet_prints", "verlet")
    path.write_text(path.read_text().replace("range(20_000)", "range(3)")
                    .replace("x.shape == (4, 2)", "True"))     # a subprocess in every step
    r = run_cli("--headless", "--scene", f"exercise:{path}", "--steps", "3", "--json")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["steps"] == 3              # stdout is the JSON alone
    assert "fd 1, straight from the step" in r.stderr and "from a subprocess" in r.stderr


def test_nan_from_the_student_reaches_the_metrics_as_null_not_as_the_labs_traceback(tmp_path):
    # once: pinned_drift on a NaN cloth: a traceback from the lab's metrics code
    path = copy_as(tmp_path, "constraints_nan", "constraints")
    r = run_cli("--headless", "--scene", f"exercise:{path}", "--steps", "3", "--json")
    assert "Traceback" not in r.stderr and r.returncode == 1      # non-finite: exit 1
    summary = json.loads(r.stdout)
    assert summary["finite"] is False and summary["metrics"]["mean_stretch"] is None


def test_a_huge_exception_message_neither_floods_the_hud_nor_breaks_the_drawing():
    # once: the HUD asked pygame for a surface as large as the message: 'Out of memory'
    scene = exercise_scene("verlet", path=str(HOSTILE / "verlet_huge_message.py"))({})
    with pytest.raises(SceneError) as info:
        scene.advance()
    assert len(str(info.value)) < 2000
    surface = pygame.Surface(scene.world_size)
    scene.draw(surface, View())
    assert all(len(line) < 200 for line in scene.hud_lines())


def test_the_lab_code_failing_on_a_students_value_stops_the_scene_with_a_message(tmp_path):
    path = tmp_path / "verlet.py"          # returns a tuple of strings: the lab's array_of refuses
    path.write_text("def verlet_step(x, x_prev, a, h, drag):\n    return 'x', 'y'\n")
    scene = exercise_scene("verlet", path=str(path))({})
    with pytest.raises(SceneError, match="verlet_step returned str"):
        scene.advance()


def test_an_unwritten_starter_shows_the_labs_answer_running_beside_the_message():
    """Issue 15, item 7: the window paused on 'write me' showed a blank canvas; now the lab's
    answer runs below the message, in orange, so an instructor can show the target first."""
    scene = exercise_scene("verlet")({})
    with pytest.raises(SceneError, match="NotImplementedError"):
        scene.advance()
    surface = pygame.Surface((960, 720))
    scene.draw(surface, View())
    demo = scene.demo_scene()
    assert demo is not None and demo.is_demo
    pixels = pygame.surfarray.array3d(surface).reshape(-1, 3)
    orange = np.all(np.abs(pixels.astype(int) - (230, 159, 0)) < 30, axis=1).sum()
    assert orange > 200                                      # the ghost is on screen
    t0 = demo.time
    time.sleep(0.05)
    scene.draw(surface, View())
    assert demo.time > t0                                    # and it moves
    assert "orange: the lab's answer" in " ".join(scene.hud_lines())


# ----- the second pass (issue 16): more hostile files -------------------------------------------
def pids_in(path: Path) -> list[int]:
    return [int(p) for p in path.read_text().split()] if path.exists() else []


def none_alive(pids: list[int], within: float = 5.0) -> bool:
    deadline = time.monotonic() + within
    while time.monotonic() < deadline and any(alive(p) for p in pids):
        time.sleep(0.05)
    return not any(alive(p) for p in pids)


def test_a_process_that_stops_itself_gets_nowhere():
    # the child is the first process of its PID namespace: a SIGSTOP it sends itself is ignored
    # (the kernel's rule for a namespace's init); where there is none, the time limit ends it
    report, seconds = graded("verlet_sigstop", timeout=0.15)
    assert not report.checks[0].passed and seconds < HANG      # no hang; speed is not tested


def test_sleeping_processes_forked_at_import_are_all_ended(monkeypatch):
    mark = marked(monkeypatch)
    report, seconds = graded("verlet_fork_flood")
    assert report.passed and seconds < HANG, report.text()     # its step is right; no hang
    assert left_behind(mark) == []


def test_a_chain_of_forks_racing_the_kill_leaves_no_process(monkeypatch):
    # each process forks the next and leaves (setsid would not help it either): when the child
    # ends, the kernel ends every process of its PID namespace, and no new one is born after
    mark = marked(monkeypatch)
    report, _ = graded("verlet_fork_race", timeout=0.2)
    assert report.checks[0].measured.startswith("still running after")
    assert left_behind(mark) == []
    time.sleep(0.2)
    assert left_behind(mark, within=0) == []          # nobody went on forking


def test_a_runaway_allocation_is_a_memory_error_at_the_childs_cap(monkeypatch):
    from app.exercises import sandbox
    # the child's data: Python and NumPy hold ~60 MB of it; 400 MB leaves room for 3 of the
    # file's 100 MB blocks (the cap is sandbox.MEMORY, 3 GB, when not set by a test)
    monkeypatch.setattr(sandbox, "MEMORY", 400 << 20)    # the forked keeper reads it
    report = grade(VERLET, str(HOSTILE / "verlet_memory_creep.py"), timeout=60.0,
                   only=("free fall",))
    assert "MemoryError" in report.checks[0].error, report.text()


@pytest.mark.parametrize("name, only", [
    ("verlet_sys_modules", None),                       # junk in sys.modules: the grader's own
    ("cradle_chdir", ("lifted as asked", "1 in, 1 out")),   # references hold; cwd is not used
])
def test_a_right_answer_with_hostile_side_effects_still_passes(name, only):
    exercise = get_exercise("newtons_cradle" if name.startswith("cradle") else "verlet")
    report = grade(exercise, str(HOSTILE / f"{name}.py"), timeout=5.0, only=only)
    assert report.passed, report.text()


def test_what_a_students_file_leaves_at_exit_neither_hangs_the_scene_nor_follows_the_json(
        tmp_path):
    # once: an atexit handler wrote after the JSON and slept, a __del__ slept at shutdown (the
    # lab hung), and input() waited for a terminal that never answers (a pipe kept open here)
    path = copy_as(tmp_path, "verlet_leaves_traps", "verlet")
    read, write = os.pipe()
    try:
        start = time.monotonic()
        r = subprocess.run([sys.executable, "-m", "app", "--headless", "--scene",
                            f"exercise:{path}", "--steps", "5", "--json"], cwd=ROOT,
                           stdin=read, capture_output=True, text=True, timeout=2 * HANG,
                           env=dict(os.environ, SDL_VIDEODRIVER="dummy",
                                    SDL_AUDIODRIVER="dummy"))
        seconds = time.monotonic() - start
    finally:
        os.close(read)
        os.close(write)
    summary = json.loads(r.stdout)                      # the JSON alone: nothing after it
    assert "EOFError" in summary["error"] and summary["steps"] == 2
    assert r.returncode == 1 and seconds < HANG, (r.returncode, seconds)


def test_the_labs_code_failing_on_a_students_build_is_named_as_the_labs():
    # once: bob 2 placed on bob 1 made the lab's ODE divide by zero, shown as the student's error
    scene = exercise_scene("double_pendulum", path=str(
        ROOT / "tests" / "exercise_answers" / "pendulum_second_from_anchor.py"))(
        {"angle1": 10.0, "angle2": 10.0})
    assert scene.error and "the lab's code failed on what your code returned" in scene.error
    assert "ZeroDivisionError" in scene.error


def test_a_scene_refuses_the_labs_own_answer_and_names_a_missing_function(tmp_path):
    scene = exercise_scene("verlet", path=str(HOSTILE / "verlet_reexports_lab.py"))({})
    assert "uses the lab's own code" in scene.error
    empty = tmp_path / "verlet.py"
    empty.write_text("x = 1\n")
    assert "defines no function verlet_step" in exercise_scene("verlet", path=str(empty))({}).error


def test_a_blow_up_in_an_exercise_scene_points_at_the_grader_not_only_at_dt():
    scene = exercise_scene("constraints", path=str(
        ROOT / "tests" / "exercise_answers" / "constraints_no_pinned_skip.py"))({})
    hint = scene.blowup_hint()
    assert "python -m app exercise check constraints --path" in hint and "raise hertz" in hint


def test_grid_indices_outside_the_particles_are_refused_in_the_child(tmp_path):
    path = tmp_path / "neighbour_grid.py"
    path.write_text("import numpy as np\n\n\ndef grid_pairs(x, cutoff, box):\n"
                    "    return np.array([0]), np.array([len(x)]), 1\n")
    report = grade(get_exercise("neighbour_grid"), str(path), only=("random particles",))
    assert "indices outside 0..399" in report.checks[0].error
    scene = exercise_scene("neighbour_grid", path=str(path))({})   # the scene: a message too
    with pytest.raises(SceneError, match="indices outside"):
        scene.advance()


def test_the_implicit_scenes_hud_shows_a_blown_up_energy_as_a_factor():
    from app.exercises.implicit_spring.scene import share
    assert share(0.3656) == "36.6%" and share(2.4e44) == "2.4e+44x" and share(math.nan) == "NaN"


# ----- the operating system's walls (issue 23) ----------------------------------------------------
from app.exercises import sandbox  # noqa: E402

WALLS = sandbox.protections()
NEEDS_LANDLOCK = pytest.mark.skipif(WALLS.landlock < 1, reason="no Landlock in this kernel")
NEEDS_SIGNAL_WALL = pytest.mark.skipif(
    WALLS.landlock < 6 and not WALLS.namespaces & sandbox.CLONE_NEWPID,
    reason="neither Landlock's signal scope (ABI 6) nor a PID namespace here")
NEEDS_PIDNS = pytest.mark.skipif(not WALLS.namespaces & sandbox.CLONE_NEWPID,
                                 reason="no PID namespace here (needs root or user namespaces)")
NEEDS_NET_WALL = pytest.mark.skipif(WALLS.landlock < 4 and not WALLS.namespaces
                                    & sandbox.CLONE_NEWNET, reason="no network wall here")


def test_a_pids_group_left_by_a_killed_keeper_of_the_same_pid_is_made_again(tmp_path):
    # a keeper killed before it removed its lab-grader-<pid> folder left it behind, and the next
    # keeper given that pid failed its setup ([Errno 17] File exists: two CI-like runs did)
    stale = tmp_path / "lab-grader-4242"
    stale.mkdir()
    assert sandbox.make_group(str(tmp_path), 4242) == str(stale) and stale.is_dir()
    assert sandbox.make_group(str(tmp_path), 4243) == str(tmp_path / "lab-grader-4243")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["lab-grader-4242", "lab-grader-4243"]


def test_every_report_says_which_walls_are_in_force_and_which_are_missing():
    report, _ = graded("verlet_prints")
    first = report.text().splitlines()[0]
    on, off = WALLS.walls()
    assert first.startswith("sandbox: ") and all(w in first for w in on + off)
    assert ("MISSING" in first) == bool(off)


@NEEDS_LANDLOCK
def test_a_file_cannot_write_the_labs_code_nor_outside_its_folder(tmp_path, monkeypatch):
    outside = tmp_path / "outside.txt"
    monkeypatch.setenv("LAB_TEST_OUTSIDE", str(outside))
    grader = ROOT / "app" / "exercises" / "verlet" / "grader.py"
    before = grader.read_bytes()
    report, _ = graded("verlet_writes_lab")
    assert report.passed, report.text()
    assert grader.read_bytes() == before and not outside.exists()
    assert report.output.count("refused") == 2 and "WROTE" not in report.output


@NEEDS_SIGNAL_WALL
def test_a_file_cannot_signal_the_grader_its_group_or_any_process_outside(monkeypatch):
    victim = subprocess.Popen(["sleep", "30"], start_new_session=True)
    try:
        monkeypatch.setenv("LAB_TEST_VICTIM", str(victim.pid))
        monkeypatch.setenv("LAB_TEST_GRADER", str(os.getpid()))   # this process: the grader
        report, _ = graded("verlet_kills_grader")          # this process survives to read it
        assert report.passed, report.text()
        assert victim.poll() is None                       # nobody outside got a signal
    finally:
        victim.kill()
        victim.wait()


@NEEDS_PIDNS
def test_a_setsid_daemon_does_not_outlive_the_check(monkeypatch):
    mark = marked(monkeypatch)
    report, _ = graded("verlet_daemon")
    assert report.passed, report.text()
    assert left_behind(mark) == []


@NEEDS_NET_WALL
def test_a_file_cannot_reach_the_network(monkeypatch):
    import socket
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    server.settimeout(0.5)
    monkeypatch.setenv("LAB_TEST_PORT", str(server.getsockname()[1]))
    try:
        report, _ = graded("verlet_network")
        assert report.passed and "refused" in report.output and "CONNECTED" not in \
            report.output, report.output
        with pytest.raises(socket.timeout):
            server.accept()                                # nothing arrived
    finally:
        server.close()


@NEEDS_LANDLOCK
def test_the_labs_answer_is_out_of_reach_by_exec_importlib_and_frames():
    report = grade(get_exercise("neighbour_grid"), str(HOSTILE / "grid_reaches_reference.py"),
                   timeout=5.0)
    assert "got it" not in report.output, report.output
    assert "exec refused" in report.output and "importlib refused" in report.output
    assert not report.passed


def test_the_harness_holds_the_checks_but_not_the_exercises_answer():
    files = sandbox.harness_files("neighbour_grid")
    assert "app/exercises/neighbour_grid/grader.py" in files
    neighbours = files["app/physics/neighbours.py"]
    assert "def grid_pairs" in neighbours and sandbox.STUB in neighbours
    assert not any(name.startswith("scenes/") for name in files)   # what its checks need only
    assert "app/physics/neighbours.py" not in sandbox.harness_files("verlet")
    cradle = sandbox.harness_files("newtons_cradle")["scenes/newtons_cradle.py"]
    assert cradle.count(sandbox.STUB) >= 1


@pytest.mark.skipif(not WALLS.pids, reason="no pids cgroup here (needs root and the pids "
                    "controller)")
def test_a_fork_bomb_stops_at_the_childs_process_limit_and_leaves_nothing(monkeypatch):
    mark = marked(monkeypatch)
    report, _ = graded("verlet_fork_bomb")
    assert report.passed, report.text()
    forked = int(report.output.split("forked ")[1].split()[0])
    assert 0 < forked < sandbox.PROCESSES
    assert left_behind(mark) == []


@NEEDS_LANDLOCK
def test_a_file_cannot_read_secrets_the_repository_or_other_folders(monkeypatch):
    # with /tmp on the grader's PYTHONPATH too: the child (python -I) does not import from it,
    # and once it could list /tmp (the lab's site_dirs() took every entry of sys.path)
    monkeypatch.setenv("PYTHONPATH", "/tmp")
    monkeypatch.setattr(sys, "path", ["/tmp", *sys.path])
    report, _ = graded("verlet_reads_secrets")
    assert report.passed, report.text()
    assert "READ" not in report.output and report.output.count("refused") == 5, report.output


def test_a_time_limit_is_a_multiple_of_the_references_time_measured_in_the_run(monkeypatch):
    # a right answer once failed a flat 5 s limit on a loaded machine ("an endless loop?"): the
    # limit is now the floor or 20x the reference's own time on this machine, and a timeout
    # says what was measured. Here the reference's time is set (the machine's load, in effect)
    import app.exercises.grade as g
    slow = str(ROOT / "tests" / "exercise_answers" / "right" / "verlet_slow_start.py")
    # The file's first step sleeps 0.6 s; the floor, 0.3 s, is also the import's limit: each
    # side has 0.3 s for a loaded machine's delays (with 0.3 s and 0.1 s the import had 0.1 s)
    monkeypatch.setattr(g, "reference_time", lambda exercise, check: 0.3)      # limit 6 s
    report = grade(VERLET, slow, timeout=0.3, only=("free fall",))
    assert report.passed, report.text()
    monkeypatch.setattr(g, "reference_time", lambda exercise, check: 0.001)    # limit 0.3 s
    report = grade(VERLET, slow, timeout=0.3, only=("free fall",))
    c = report.checks[0]
    assert not c.passed and c.measured.startswith("still running after")
    assert "the reference took 0.001 s on this machine" in c.error and "endless" not in c.error
    assert "20x the reference's 0.001 s, at least 0.3 s" in c.bound
