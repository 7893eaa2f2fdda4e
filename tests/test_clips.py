"""Clips for slides (app/clips.py, --video, F9 in the window): frames from the fixed-step clock,
their number and size, the same bytes from the same command, the run unchanged by recording,
and bad paths refused in one line before the run. Small clips (320 px, 1 s): speed is measured
by `python -m app bench clips`, never here."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pygame
import pytest

from app.__main__ import main
from app.clips import (MP4_INSTALL, GifWriter, check_video, clip_size, frame_count,
                       frame_steps)
from tests.toy_scenes import key


def run_json(capsys, *args) -> dict:
    assert main(["--headless", *args, "--json"]) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


def test_frames_follow_the_fixed_step_clock():
    # 10 s at 60 Hz, 30 fps: 300 frames, frame k after 2k steps (frame 0: the scene as built)
    assert frame_steps(600, 1 / 60, 30) == [2 * k for k in range(300)]
    # 120 Hz: every 4th step; a step slower than a frame repeats the state (hertz 4 at 30 fps)
    assert frame_steps(240, 1 / 120, 30)[:3] == [0, 4, 8]
    assert frame_steps(8, 1 / 4, 30)[:9] == [0, 1, 1, 1, 1, 1, 1, 1, 2]    # 8/30 s > 1/4 s
    assert frame_count(8, 1 / 4, 30) == 60 and frame_count(1, 1 / 60, 30) == 1


def test_a_gif_has_its_frames_size_and_real_time_durations(tmp_path, capsys):
    from PIL import Image
    out = tmp_path / "pendulum.gif"
    summary = run_json(capsys, "--scene", "double_pendulum", "--seconds", "1", "--video",
                       str(out), "--width", "320")
    assert summary["video"] == str(out) and summary["video_frames"] == 30
    assert summary["video_bytes"] == out.stat().st_size
    with Image.open(out) as gif:
        assert gif.size == (320, 320 * 720 // 960) and gif.info["loop"] == 0
        durations = []
        for k in range(gif.n_frames):       # identical neighbours are merged, their time added
            gif.seek(k)
            durations.append(gif.info["duration"])
        assert 25 <= gif.n_frames <= 30
        assert sum(durations) == 1000       # 30 frames of 1/30 s: 30, 40, 30 ms ... = 1 s
        gif.seek(gif.n_frames - 1)
        last = gif.convert("RGB")
    assert len(last.getcolors(1 << 16)) > 4      # a picture, not an empty frame


def test_the_same_command_gives_the_same_clip_and_the_run_is_unchanged(tmp_path, capsys):
    args = ["--scene", "newtons_cradle", "--seconds", "0.5", "--width", "240", "--clean"]
    a = run_json(capsys, *args, "--video", str(tmp_path / "a.gif"))
    b = run_json(capsys, *args, "--video", str(tmp_path / "b.gif"))
    plain = run_json(capsys, "--scene", "newtons_cradle", "--seconds", "0.5")
    assert (tmp_path / "a.gif").read_bytes() == (tmp_path / "b.gif").read_bytes()
    assert a["state_hash"] == b["state_hash"] == plain["state_hash"]
    assert a["steps"] == plain["steps"] == 60


def test_an_mp4_has_its_frames_and_size_and_the_same_bytes_twice(tmp_path, capsys):
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")    # in requirements-dev.txt
    args = ["--scene", "pivoting_l", "--seconds", "0.5", "--width", "320", "--clean"]
    run_json(capsys, *args, "--video", str(tmp_path / "a.mp4"))
    run_json(capsys, *args, "--video", str(tmp_path / "b.mp4"))
    assert (tmp_path / "a.mp4").read_bytes() == (tmp_path / "b.mp4").read_bytes()
    reader = imageio_ffmpeg.read_frames(str(tmp_path / "a.mp4"))
    try:
        meta = next(reader)
        frames = sum(1 for _ in reader)
    finally:
        reader.close()
    assert meta["codec"] == "h264" and meta["fps"] == 30
    assert meta["size"] == clip_size(_scene("pivoting_l"), 320, True)
    assert frames == 15


def _scene(name: str):
    from scenes import get_scene
    return get_scene(name)({})


def test_clean_crops_to_the_content_and_width_sizes_a_screenshot(tmp_path, capsys):
    shot = tmp_path / "cradle.png"
    run_json(capsys, "--scene", "newtons_cradle", "--steps", "2", "--screenshot", str(shot),
             "--clean", "--width", "640")
    _, _, w, h = _scene("newtons_cradle").content_bounds()
    size = pygame.image.load(str(shot)).get_size()
    assert size[0] == 640 and abs(size[1] - 640 * h / w) <= 2     # the content's shape, not 4:3


BAD = [
    (["--video", "clip.avi"], "accepted: a file name ending in .gif or .mp4"),
    (["--video", ""], "--video needs a file name"),
    (["--video", "/proc/no-such-folder/clip.gif"], "cannot write"),
    (["--video", "clip.gif", "--fps", "60"], "a GIF plays at most 50 fps"),
    (["--video", "clip.gif", "--seconds", "13"], "a GIF 1280 px wide holds at most 366 (12.2 s"),
    (["--video", "clip.gif", "--seconds", "13", "--width", "1920"], "1920 px wide holds at most 162"),
    (["--video", "clip.gif", "--fps", "0"], "accepted: frames per second from 1 to 60"),
    (["--video", "clip.gif", "--width", "10"], "accepted: a width in pixels from 160 to 1920"),
    (["--video", "clip.gif", "--width", "1e3"], "not an integer"),
    (["--fps", "24"], "--fps is a clip's frame rate"),
    (["--clean"], "--clean leaves the HUD out"),
    (["--width", "800"], "--width sizes --screenshot and --video"),
]


@pytest.mark.parametrize("extra, fragment", BAD, ids=[" ".join(a) or "empty" for a, _ in BAD])
def test_bad_clip_options_are_refused_in_one_line_before_the_run(capsys, tmp_path, monkeypatch,
                                                                  extra, fragment):
    monkeypatch.chdir(tmp_path)
    # 12 s of the mass-spring cloth (the longest GIF at 1280 px) take a while: the refusal
    # comes before them
    seconds = [] if "--seconds" in extra else ["--seconds", "12"]
    code = main(["--headless", "--scene", "mass_spring_cloth", *seconds, *extra])
    captured = capsys.readouterr()
    assert code == 2 and captured.out == ""
    assert captured.err.count("\n") == 1 and fragment in captured.err, captured.err
    assert "Traceback" not in captured.err and not list(tmp_path.iterdir())


def test_mp4_without_imageio_ffmpeg_names_the_one_install(capsys, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)       # as if not installed
    code = main(["--headless", "--scene", "cloth", "--seconds", "3600", "--video",
                 str(tmp_path / "clip.mp4")])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and MP4_INSTALL in err and "or give a .gif" in err
    assert check_video("clip.gif", 30) is None                      # GIF needs no extra


def test_gif_durations_add_up_to_real_time_at_any_rate():
    for fps in (7, 24, 30, 50):
        writer = GifWriter("unused.gif", (4, 4), fps)
        writer.frames = 3 * fps
        durations = writer.durations()
        writer.abandon()
        assert sum(durations) == 3000 and all(d % 10 == 0 and d > 0 for d in durations)


def test_f9_records_the_scene_area_as_shown_in_simulated_time(tmp_path):
    """F9 starts a clip, F9 stops it; frames follow the steps run (none while paused, twice as
    many per step in slow motion x1/2); a scene area that changes shape (F2) is fitted into the
    clip's frame; the file is written in the background and named."""
    from PIL import Image

    from app.draw.text import TEXT
    from app.window import Window
    from app.window.clip_recorder import ClipRecorder
    from scenes import get_scene
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((800, 500)), screenshot_dir=tmp_path)
    w.clips = ClipRecorder(fps=30, width=320, folder=tmp_path / "clips")
    assert w.open_scene(get_scene("falling_balls"))

    def frames(n: int, slow_keys: int = 0) -> None:
        for _ in range(n):
            w.update(1 / 60)
            w.render()

    def press(k: int) -> None:
        key(w, k)
    frames(3)
    area = w.scene_view.world_area()
    height = int(320 * area.height / area.width) // 2 * 2
    press(pygame.K_F9)
    assert w.clips.active and w.clips.writer.size == (320, height)
    frames(30)                                  # 0.5 s at x1: 15 frames after frame 0
    assert w.clips.writer.frames == 16
    press(pygame.K_SPACE)
    frames(30)                                  # paused: nothing
    assert w.clips.writer.frames == 16
    press(pygame.K_SPACE)
    press(pygame.K_MINUS)                       # x1/2: 0.25 s simulated plays 0.5 s
    frames(30)
    assert w.clips.writer.frames == 31
    press(pygame.K_F2)                          # large text: the panel widens, the scene area
    frames(8)                                   # narrows; the clip goes on at its size (still
                                                # at x1/2: 4 steps, 4 frames)
    assert w.clips.active and w.clips.writer.frames == 35
    press(pygame.K_F9)
    assert not w.clips.active
    for _ in range(2000):                       # the GIF is written in the background; the
        frames(1)                               # window says so when it is done
        saved = [m.text for m in w.messages if m.text.startswith("clip saved: ")]
        if saved:
            break
    (clip,) = (tmp_path / "clips").glob("falling_balls-*.gif")
    with Image.open(clip) as gif:
        assert gif.size == (320, height)
        stored = gif.n_frames          # Pillow merges identical neighbours: the message says so
    more = "" if stored == 35 else f" ({stored} stored: repeated frames are held longer)"
    assert saved == [f"clip saved: {clip.resolve()} (35 frames{more}, 320x{height}, 1.2 s, "
                     f"{clip.stat().st_size / 1e6:.2f} MB)"]
    TEXT.scale = 1.0
    assert w.clips.finish(w) == []              # nothing left to save on the way out
    pygame.display.quit()


def test_the_docs_clip_commands_run(tmp_path, monkeypatch, capsys):
    """The headless --video commands of docs/instructors.md's "Clips and charts for slides"
    (the README's until issue 18 moved it), shortened to
    0.2 s at 160 px (the same scenes, settings and file names)."""
    import shlex
    text = (Path(__file__).resolve().parent.parent / "docs" / "instructors.md").read_text()
    block = text.split("## Clips and charts for slides", 1)[1].split("## ", 1)[0]
    commands = [shlex.split(line.split("#", 1)[0])[3:] for line in block.splitlines()
                if line.strip().startswith("python -m app --headless") and "--video" in line]
    assert len(commands) == 3
    monkeypatch.chdir(tmp_path)
    for args in commands:
        at = args.index("--seconds")
        args[at + 1] = "0.2"
        assert main(args + ["--width", "160"]) == 0, capsys.readouterr().err
        out = args[args.index("--video") + 1]
        written = [tmp_path / out] if "all" not in args else \
            list((tmp_path / out).parent.glob("all-*.gif"))
        assert written and all(p.stat().st_size > 0 for p in written), args
    capsys.readouterr()


def test_f9_clips_go_to_the_videos_name_then_numbered_ones(tmp_path):
    from app.window.clip_recorder import ClipRecorder
    named = ClipRecorder(path=str(tmp_path / "demo.mp4"))
    assert named.next_path("cloth") == tmp_path / "demo.mp4"
    named.made = 2
    assert named.next_path("cloth") == tmp_path / "demo-3.mp4"
    dated = ClipRecorder(folder=tmp_path)
    first = dated.next_path("cloth")
    assert first.parent == tmp_path and first.name.startswith("cloth-") and first.suffix == ".gif"
    first.write_bytes(b"")                      # never over an existing file
    assert dated.next_path("cloth") != first


@pytest.mark.parametrize("large", [False, True])
def test_the_rec_box_covers_no_text_in_compare_mode(tmp_path, large):
    """F9 in compare mode at 1024x768: the REC box goes below the header and the panes' HUDs
    it would cover (it was drawn over the header's title and clock)."""
    from app.draw.text import TEXT
    from app.window import Window
    from app.window.clip_recorder import ClipRecorder, _text_boxes
    from scenes.mass_spring_cloth import MassSpringClothScene
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1024, 768)), screenshot_dir=tmp_path)
    w.clips = ClipRecorder(fps=30, width=160, folder=tmp_path / "clips")
    assert w.open_scene(MassSpringClothScene, {"rows": 8, "cols": 8})
    assert w.scene_view.apply_try(MassSpringClothScene.find_card("Explicit vs implicit at 60 Hz"))
    if large:
        TEXT.scale = 1.0
        w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_F2, mod=0,
                                                 scancode=0, unicode=""))
    for k in (pygame.K_F9, None, None, None):
        if k:
            w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, scancode=0,
                                                     unicode=""))
        w.update(1 / 60)
        w.render()
    view = w.scene_view
    boxes = _text_boxes(view)
    assert w.clips.active and len(boxes) == 3 and view.pane.header.height > 0
    assert w.clips.box.collidelist(boxes) == -1, (w.clips.box, boxes)
    # with the panel shown, the REC box is at its bottom, off the scene the class watches
    assert view.panel.rect.contains(w.clips.box)
    assert not view.world_area().colliderect(w.clips.box)
    view.toggle_panel()                          # Tab: no panel, the box goes on the scene area
    w.update(1 / 60)
    w.render()
    boxes = _text_boxes(view)
    assert w.clips.box.collidelist(boxes) == -1, (w.clips.box, boxes)
    assert view.world_area().contains(w.clips.box)
    view.toggle_panel()
    w.clips.stop(w)
    w.clips.finish(w)
    TEXT.scale = 1.0
    pygame.display.quit()
