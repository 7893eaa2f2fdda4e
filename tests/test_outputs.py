"""Outputs that never lose data (app/outputs.py): every file the lab writes goes to a temporary
file beside its target and is renamed into place only when complete. A failed write (a full disk,
simulated here by a writer or a rename that raises ENOSPC, or an encoder that exits non-zero) or
an interrupted one (KeyboardInterrupt, SIGINT) leaves the old file as it was and says so in one
line; one path named twice, or an output that is an input, is refused before anything runs."""

from __future__ import annotations

import errno
import json
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from app import outputs
from app.__main__ import main
from app.outputs import OutputError, atomic_path, atomic_write, write_bytes, write_text

ROOT = Path(__file__).resolve().parent.parent


def run_main(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def one_error_line(err: str) -> str:
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("python -m app: error: ") and "Traceback" not in err, err
    return lines[0]


def leftovers(folder: Path) -> list[str]:
    """Temporary files left in `folder` (there must be none)."""
    return [p.name for p in folder.iterdir() if ".part" in p.name or p.name.startswith(".probe")]


def full_disk(*args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


# --- the helper itself -------------------------------------------------------------------------

def test_atomic_write_replaces_the_file_whole_and_keeps_its_permissions(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old")
    os.chmod(target, 0o640)
    with atomic_write(target, "w") as f:
        f.write("new")
        assert target.read_text() == "old"          # nothing in place until the block ends
    assert target.read_text() == "new"
    assert stat.S_IMODE(os.stat(target).st_mode) == 0o640
    assert write_text(target, "again") is True      # it replaced a file
    assert write_bytes(tmp_path / "fresh.bin", b"\x00\x01") is False
    assert (tmp_path / "fresh.bin").read_bytes() == b"\x00\x01"
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("error", [OSError(errno.ENOSPC, "No space left on device"),
                                   ValueError("the writer failed"), KeyboardInterrupt()],
                         ids=["full_disk", "writer_raises", "ctrl_c"])
def test_a_write_that_fails_or_is_interrupted_leaves_the_old_file_as_it_was(tmp_path, error):
    target = tmp_path / "table.csv"
    target.write_text("the recorded data")
    expected = KeyboardInterrupt if isinstance(error, KeyboardInterrupt) else OutputError
    with pytest.raises(expected) as caught:
        with atomic_write(target, "w", what="--csv") as f:
            f.write("half a table")
            raise error
    assert target.read_text() == "the recorded data"
    assert leftovers(tmp_path) == []
    if expected is OutputError:
        text = str(caught.value)
        assert "\n" not in text and "--csv" in text and "left as it was" in text, text


def test_a_rename_on_a_full_disk_leaves_the_old_file_and_says_so(tmp_path, monkeypatch):
    target = tmp_path / "shot.png"
    target.write_bytes(b"old png")
    monkeypatch.setattr(outputs.os, "replace", full_disk)
    with pytest.raises(OutputError, match="No space left on device; the file that was there is "
                                          "left as it was"):
        with atomic_path(target, "--screenshot") as tmp:
            Path(tmp).write_bytes(b"new png")
    assert target.read_bytes() == b"old png"
    assert leftovers(tmp_path) == []


def test_a_writer_that_writes_nothing_has_failed(tmp_path):
    with pytest.raises(OutputError, match="wrote nothing; nothing was written"):
        with atomic_path(tmp_path / "chart.png", "the chart"):
            pass
    assert list(tmp_path.iterdir()) == []


def test_a_user_value_is_echoed_once_short_and_on_one_line():
    assert outputs.shown("a\nb\x1b[31m") == "'a\\nb\\x1b[31m'"
    long = outputs.shown("x" * 100_000)
    assert len(long) < 80 and "..." in long
    assert "\n" not in outputs.one_line("line one\nline two\r\u2028") and \
        len(outputs.one_line("y" * 10_000)) <= outputs.MAX_LINE


def test_clash_finds_one_file_under_two_names(tmp_path):
    real = tmp_path / "events.json"
    real.write_text("[]")
    link = tmp_path / "link.json"
    link.symlink_to(real)
    assert "two outputs" in outputs.clash([(str(tmp_path / "a.png"), "--csv"),
                                           (str(tmp_path / "sub/../a.png"), "--screenshot")])
    assert "an output and an input" in outputs.clash([(str(link), "--csv")],
                                                     [(str(real), "--input")])
    assert outputs.clash([(str(tmp_path / "a.csv"), "--csv"),
                          (str(tmp_path / "a.png"), "--screenshot")],
                         [(str(real), "--input")]) is None


def test_temporary_names_are_ascii_and_a_trailing_slash_is_a_folder(tmp_path):
    # once (hostile run, seed 27): pygame saved `--screenshot bad<0xff>.png` under another name
    # than the temporary one it was given, and left it behind; `--csv out.csv/` passed the
    # check before the run and failed after it
    pending = outputs.Pending(os.path.join(tmp_path, "bad\udcff \u540d.png"), "--screenshot")
    assert os.path.basename(pending.tmp).isascii() and pending.tmp.endswith(".png")
    pending.discard()
    assert "names a folder" in outputs.output_problem(str(tmp_path / "out.csv") + "/", "--csv")
    assert leftovers(tmp_path) == []


def test_grading_reports_are_written_whole_or_not_at_all(tmp_path, monkeypatch):
    # once: `exercise grade --out FULL/old.csv` on a full disk ended in a traceback (its own
    # writer, not app/outputs.py) and left its temporary file
    from app.exercises import classroom
    book = tmp_path / "gradebook.csv"
    book.write_text("old")
    monkeypatch.setattr(os, "replace", full_disk)
    with pytest.raises(OutputError, match="No space left"):
        classroom.write_atomic(str(book), "student,score\n", "the gradebook")
    assert book.read_text() == "old" and leftovers(tmp_path) == []


def test_a_scene_file_nested_too_deeply_is_one_line(capsys, tmp_path):
    # once (hostile run, seed 2026): `x = [[[[...]]]]` 5000 deep: tomllib's RecursionError,
    # a traceback
    deep = tmp_path / "deep.toml"
    deep.write_text("x = " + "[" * 5000 + "]" * 5000 + "\n")
    code, _, err = run_main(capsys, "scene", "check", str(deep))
    assert code == 2 and "nested too deeply" in one_error_line(err)


def test_a_scene_file_that_is_a_fifo_is_refused_not_waited_for(capsys, tmp_path):
    # once: `--scene in.toml` and `scene check in.toml` on a FIFO waited for a writer for ever
    fifo = tmp_path / "in.toml"
    os.mkfifo(fifo)
    old = signal.signal(signal.SIGALRM, lambda *a: pytest.fail("waited on the FIFO"))
    signal.alarm(10)
    try:
        for args in (["--headless", "--scene", str(fifo), "--steps", "1"],
                     ["scene", "check", str(fifo)]):
            code, _, err = run_main(capsys, *args)
            assert code == 2 and "not a regular file" in one_error_line(err)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@pytest.mark.parametrize("args,word", [
    (["--headless", "--scene", "cloth", "--steps", "1", "--set", "iteration=3"],
     "accepted: iterations,"),
    (["--headless", "--scene", "integrators", "--steps", "1", "--plot", "rk4_eror",
      "--screenshot", "x.png"], "accepted: rk4_error,"),
    (["--headless", "--scene", "cloth", "--steps", "1", "--compare", "subteps=1",
      "iterations=4"], "accepted: substeps,"),
    (["--headless", "--scene", "cloth", "--steps", "1", "--compare", "x" * 100_000, "g=1"],
     "is not KEY=VALUE"),
    (["--headless", "--scene", "cloth", "--steps", "1", "--compare", "x" * 100_000 + "=1",
      "iterations=4"], "more (all in docs/scenes.md)"),
    (["scene", "check", "q" * 100_000 + ".toml"], "cannot be read"),
    (["x" * 100_000], "unrecognized arguments"),                      # seed 2026: 316
    (["--headless", "--scene", "x" * 100_000, "--steps", "1"], "unknown scene"),   # 305
    (["exercise", "check", "verlet", "--path", "q" * 100_000 + ".py"], "no such file"),
])
def test_every_refusal_is_one_line_of_at_most_300_characters(capsys, args, word):
    # once (hostile run, seed 27): 20 error lines of 376 to 616 characters: a long list of
    # accepted names (now the closest to what was typed first, then cut), and a long --compare
    # value, scene file or --path echoed whole
    code, _, err = run_main(capsys, *args)
    line = one_error_line(err)
    assert code == 2 and len(line) <= 300 and word in line, (len(line), line)


# --- the command line ----------------------------------------------------------------------------

def test_an_output_that_is_also_the_input_is_refused_before_the_run(capsys, tmp_path):
    # once: `--csv ev.json --input ev.json` overwrote the recorded events
    events = tmp_path / "ev.json"
    events.write_text('[{"t": 0.1, "type": "key_down", "key": "r"}]')
    before = events.read_text()
    code, out, err = run_main(capsys, "--headless", "--scene", "cloth", "--steps", "2",
                              "--csv", str(events), "--input", str(events))
    assert code == 2 and out == ""
    assert "an output and an input" in one_error_line(err)
    assert events.read_text() == before


def test_the_scene_file_is_an_input_and_never_an_output(capsys, tmp_path):
    # once (hostile run, seed 27): `--scene s.toml --csv s.toml` exited 0 and replaced the
    # teacher's scene file with the CSV; through a symlink it replaced the link
    scene = tmp_path / "s.toml"
    scene.write_bytes((ROOT / "scenes" / "files" / "pivoting_l.toml").read_bytes())
    (tmp_path / "l.csv").symlink_to(scene)
    before = scene.read_bytes()
    for out in (scene, tmp_path / "l.csv"):
        code, _, err = run_main(capsys, "--headless", "--scene", str(scene), "--steps", "2",
                                "--csv", str(out))
        assert code == 2 and "the scene file (an input)" in one_error_line(err)
    assert scene.read_bytes() == before and (tmp_path / "l.csv").is_symlink()


def test_one_path_for_two_outputs_is_refused_before_the_run(capsys, tmp_path):
    # once: `--csv same.png --screenshot same.png` left only the PNG
    same = tmp_path / "same.png"
    code, out, err = run_main(capsys, "--headless", "--scene", "cloth", "--steps", "2",
                              "--csv", str(same), "--screenshot", str(same))
    assert code == 2 and "two outputs" in one_error_line(err)
    assert not same.exists()


@pytest.mark.parametrize("kind", ["fifo", "folder", "device"])
def test_a_fifo_a_device_or_a_folder_is_refused_where_a_file_is_expected(capsys, tmp_path, kind):
    if kind == "fifo":
        path = tmp_path / "pipe.csv"
        os.mkfifo(path)
    elif kind == "folder":
        path = tmp_path / "folder.csv"
        path.mkdir()
    else:
        path = Path("/dev/null")
    code, out, err = run_main(capsys, "--headless", "--scene", "cloth", "--steps", "2",
                              "--csv", str(path))
    assert code == 2
    assert {"fifo": "FIFO", "folder": "is a folder", "device": "is a device"}[kind] in \
        one_error_line(err)


def test_each_user_value_is_echoed_once_shortened_and_escaped(capsys, tmp_path):
    # once: an unknown --set key, a bad --compare variant and a folder given as --csv were each
    # echoed twice (a 100k-character key: two 30-character cuts; a variant: ~500 characters)
    folder = tmp_path / ("d" * 80)
    folder.mkdir()
    huge = "q" * 100_000
    for args, mark, times in ((["--set", f"{huge}\x1b=1"], "'qqq", 1),
                              (["--set", "a\nb=1"], "a\\nb", 1),
                              (["--compare", f"g={huge}", "g=1"], "'qqq", 1),
                              (["--compare", "g=1", "g=1.0"], "'g=1", 2),     # two variants
                              (["--csv", str(folder)], "d'", 1)):
        code, out, err = run_main(capsys, "--headless", "--scene", "cloth", "--steps", "1", *args)
        line = one_error_line(err)
        assert code == 2 and len(line) <= 600 and "\x1b" not in line, line
        assert line.count(mark) == times, line


def test_a_path_with_a_newline_and_a_huge_path_give_one_short_line(capsys, tmp_path):
    weird = str(tmp_path / "no\nsuch" / "x.csv")
    os.makedirs(os.path.dirname(weird))
    os.chmod(os.path.dirname(weird), 0o500)             # not writable (unless root)
    huge = "p" * 100_000 + ".png"
    for args in (["--csv", weird, "--input", weird], ["--screenshot", huge]):
        code, out, err = run_main(capsys, "--headless", "--scene", "cloth", "--steps", "1", *args)
        assert code == 2
        line = one_error_line(err)
        assert len(line) < 400, len(line)
    os.chmod(os.path.dirname(weird), 0o700)


def test_the_summary_says_when_an_output_replaced_a_file(capsys, tmp_path):
    csv_path, shot = tmp_path / "run.csv", tmp_path / "run.png"
    csv_path.write_text("old")
    code, out, err = run_main(capsys, "--headless", "--scene", "pivoting_l", "--steps", "3",
                              "--csv", str(csv_path), "--screenshot", str(shot), "--json")
    assert code == 0, err
    result = json.loads(out)
    assert result["replaced"] == [str(csv_path)]
    assert csv_path.read_text().startswith("step,t")
    code, out, err = run_main(capsys, "--headless", "--scene", "pivoting_l", "--steps", "3",
                              "--screenshot", str(shot))
    assert code == 0 and f"replaced: {shot} (the file that was there)" in out


def test_a_csv_on_a_full_disk_exits_2_in_one_line_and_keeps_the_old_file(capsys, tmp_path,
                                                                          monkeypatch):
    # once: a 21-line traceback, the old file already truncated
    from app import series
    target = tmp_path / "run.csv"
    target.write_text("the last run's rows")

    class FullWriter:
        def __init__(self, f):
            pass

        def writerow(self, row):
            full_disk()
    monkeypatch.setattr(series.csv, "writer", FullWriter)
    code, out, err = run_main(capsys, "--headless", "--scene", "pivoting_l", "--steps", "3",
                              "--csv", str(target), "--json")
    assert code == 2
    assert "No space left on device; the file that was there is left as it was" in \
        one_error_line(err)
    assert json.loads(out)["csv"] is None
    assert target.read_text() == "the last run's rows" and leftovers(tmp_path) == []


def test_a_gif_that_cannot_be_written_keeps_the_old_clip(capsys, tmp_path, monkeypatch):
    from PIL import Image
    target = tmp_path / "clip.gif"
    target.write_bytes(b"old gif")
    monkeypatch.setattr(Image.Image, "save", full_disk)
    code, out, err = run_main(capsys, "--headless", "--scene", "pivoting_l", "--steps", "6",
                              "--video", str(target), "--width", "160", "--json")
    assert code == 2
    assert "could not write --video" in one_error_line(err)
    assert json.loads(out)["video"] is None
    assert target.read_bytes() == b"old gif" and leftovers(tmp_path) == []


def test_a_bench_chart_that_cannot_be_written_is_one_line(capsys, tmp_path, monkeypatch):
    # once: an 87-line traceback
    from matplotlib.figure import Figure
    monkeypatch.setattr(Figure, "savefig", full_disk)
    code, out, err = run_main(capsys, "bench", "pymunk", "--quick", "--out", str(tmp_path))
    assert code == 2
    line = [ln for ln in err.splitlines() if not ln.startswith("  ..")]
    assert len(line) == 1 and "No space left on device" in line[0], err
    assert leftovers(tmp_path) == []



def test_a_ctrl_c_as_the_temporary_file_is_made_leaves_nothing_behind(tmp_path, monkeypatch):
    # once (a CI run): Ctrl-C right after the temporary file was made, before it was listed
    # for removal: '.clip.nz9m7it2.part.gif' stayed beside the old clip. Here the signal comes
    # as mkstemp returns; the interrupted run's discard_all must find the file
    made = []
    real = outputs.tempfile.mkstemp

    def mkstemp(*args, **kwargs):
        fd, name = real(*args, **kwargs)
        made.append(name)
        os.kill(os.getpid(), signal.SIGINT)           # (Python's handler: KeyboardInterrupt)
        return fd, name
    monkeypatch.setattr(outputs.tempfile, "mkstemp", mkstemp)
    target = tmp_path / "clip.gif"
    target.write_bytes(b"old clip")
    with pytest.raises(KeyboardInterrupt):
        outputs.Pending(target, "--video")
    assert len(made) == 1
    outputs.discard_all()                             # what the command line does on Ctrl-C
    assert target.read_bytes() == b"old clip" and leftovers(tmp_path) == []

def cli(*args, env=None, **kwargs):
    full = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy", **(env or {}))
    return subprocess.Popen([sys.executable, "-m", "app", *args], cwd=ROOT, env=full,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def test_an_mp4_the_encoder_fails_to_write_is_not_reported_as_success(tmp_path):
    # once: exit 0 with "video_bytes": 0 and ffmpeg's own log lines on stderr (a full disk)
    pytest.importorskip("imageio_ffmpeg")
    fake = tmp_path / "ffmpeg"
    fake.write_text("#!/bin/sh\ncat > /dev/null\n"
                    "echo 'frame=   10 fps=0.0 q=-1.0 size=       0kB' >&2\n"
                    "echo '[out#0/mp4 @ 0x55d] Error closing file: No space left on device' >&2\n"
                    "exit 228\n")
    fake.chmod(0o755)
    target = tmp_path / "clip.mp4"
    target.write_bytes(b"old mp4")
    p = cli("--headless", "--scene", "pivoting_l", "--steps", "6", "--video", str(target),
            "--width", "160", "--json", env={"IMAGEIO_FFMPEG_EXE": str(fake)})
    out, err = p.communicate(timeout=120)
    assert p.returncode == 2, err
    line = one_error_line(err)                       # ffmpeg's lines do not leak
    assert "exit status 228" in line and "No space left on device" in line and \
        "left as it was" in line and "0x55d" not in line, line
    assert json.loads(out)["video"] is None
    assert target.read_bytes() == b"old mp4" and leftovers(tmp_path) == []


def wait_for_part(folder: Path, proc, timeout: float = 120) -> None:
    """Until a temporary output appears in `folder` (the run is writing); no speed assumed."""
    end = time.monotonic() + timeout
    while time.monotonic() < end and proc.poll() is None:
        if any(".part" in p.name for p in folder.iterdir()):
            return
        time.sleep(0.05)
    pytest.fail(f"no temporary output appeared (exit {proc.poll()})")


@pytest.mark.parametrize("video", ["clip.gif", "clip.mp4"])
def test_ctrl_c_during_a_clip_and_a_csv_exits_130_in_one_line_and_keeps_the_old_files(
        tmp_path, video):
    # once: a KeyboardInterrupt traceback, and the existing outputs already truncated
    if video.endswith(".mp4"):
        pytest.importorskip("imageio_ffmpeg")
    clip, table = tmp_path / video, tmp_path / "run.csv"
    clip.write_bytes(b"old clip")
    table.write_text("old rows")
    p = cli("--headless", "--scene", "pivoting_l", "--seconds", "600", "--video", str(clip),
            "--width", "160", "--fps", "10", "--csv", str(table),
            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    wait_for_part(tmp_path, p)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("python -m app: interrupted (Ctrl-C)"), err
    assert clip.read_bytes() == b"old clip" and table.read_text() == "old rows"
    assert leftovers(tmp_path) == []


def test_ctrl_c_while_python_m_app_starts_is_one_line_and_130(monkeypatch):
    # once (hostile run, seed 27): a Ctrl-C in the first ~0.3 s (numpy, pygame and pymunk being
    # imported) printed a KeyboardInterrupt traceback and died by the signal, not exit 130
    import app
    monkeypatch.setattr(sys, "orig_argv", [sys.executable, "-m", "app", "--list"])
    assert app._launched_as_the_command_line()
    monkeypatch.setattr(sys, "orig_argv", [sys.executable, "-m", "pytest"])
    assert not app._launched_as_the_command_line()
    written = []
    monkeypatch.setattr(os, "write", lambda fd, data: written.append((fd, data)))

    def leave(code):
        raise SystemExit(code)
    monkeypatch.setattr(os, "_exit", leave)
    with pytest.raises(SystemExit) as e:
        app._ctrl_c_while_starting(signal.SIGINT, None)
    assert e.value.code == 130 and len(written) == 1 and written[0][0] == 2
    assert written[0][1].count(b"\n") == 1 and b"interrupted (Ctrl-C)" in written[0][1]


def test_after_ctrl_c_the_lab_leaves_with_130_itself(monkeypatch):
    # once, under load: the interrupted line printed, then exit by SIGINT (-2), not 130: Python
    # ends by the signal at exit if a KeyboardInterrupt passed through some of its C paths
    from app import __main__ as cli_main
    left = []

    def os_exit(code):
        left.append(code)
        raise SystemExit(code)
    monkeypatch.setattr(os, "_exit", os_exit)
    before = signal.getsignal(signal.SIGINT)
    try:
        with pytest.raises(SystemExit):
            cli_main.leave(130)
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN    # (what follows: shutdown)
    finally:
        signal.signal(signal.SIGINT, before)
    assert left == [130]


def test_a_gif_reports_the_frames_and_seconds_in_the_file(capsys, tmp_path):
    # once: the cradle's GIF held 119 frames where the summary said 120 (Pillow merges equal
    # frames); what is reported is now read back from the file
    from PIL import Image
    target = tmp_path / "cradle.gif"
    code, out, err = run_main(capsys, "--headless", "--scene", "newtons_cradle", "--seconds", "1",
                              "--video", str(target), "--width", "160", "--json")
    assert code == 0, err
    result = json.loads(out)
    with Image.open(target) as im:
        frames = im.n_frames
        ms = 0
        for k in range(frames):
            im.seek(k)
            ms += im.info["duration"]
    assert result["video_frames"] == frames
    assert result["video_seconds"] == pytest.approx(ms / 1000)
    assert result["video_seconds"] == pytest.approx(1.0, abs=0.011)
