"""Progress on long work (app/progress.py): a tqdm bar with the time left on a terminal, a few
plain lines when stderr is not one (none for a short run). A fake clock: no wall time here."""

from __future__ import annotations

import io

from app.progress import PLAIN_EVERY, PLAIN_FIRST, Progress


class Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self) -> float:
        return self.t


def test_a_short_run_prints_nothing_when_stderr_is_not_a_terminal():
    out, clock = io.StringIO(), Clock()
    with Progress(100, "clip", "frames", stream=out, clock=clock) as bar:
        for _ in range(100):
            clock.t += (PLAIN_FIRST - 1) / 100
            bar.update(1)
    assert out.getvalue() == ""


def test_a_long_run_prints_a_few_plain_lines_with_the_time_left():
    out, clock = io.StringIO(), Clock()
    with Progress(40, "scenes", "scenes", stream=out, clock=clock) as bar:
        for k in range(40):
            clock.t += 1.0                      # 40 s of work, 1 s a scene
            bar.update(1, note=f"scene {k}")
    lines = out.getvalue().splitlines()
    assert 3 <= len(lines) <= 40 / PLAIN_EVERY + 2, lines
    assert lines[0] == "  .. scenes: 10/40 scenes (25%), 10 s, ~30 s left (scene 9)", lines[0]
    assert lines[-1].startswith("  .. scenes: 40/40 scenes (100%), 40 s")


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_on_a_terminal_it_is_a_tqdm_bar_with_the_time_left():
    out = Terminal()
    with Progress(5, "exercises checked", stream=out) as bar:
        assert bar._bar is not None and type(bar._bar).__module__.startswith("tqdm")
        for _ in range(5):
            bar.update(1)
        bar.say("a line above the bar")
    text = out.getvalue()
    assert "exercises checked" in text and "5/5" in text and "<" in text   # elapsed<left
    assert "a line above the bar" in text


def test_it_can_be_turned_off(monkeypatch):
    monkeypatch.setenv("PHYSICS_LAB_PROGRESS", "off")
    out, clock = io.StringIO(), Clock()
    with Progress(3, "benchmarks", stream=out, clock=clock) as bar:
        clock.t = 1000
        bar.update(1)
        assert out.getvalue() == ""
        bar.say("  .. a line of the work's own")        # still said: it is not the bar
    assert out.getvalue() == "  .. a line of the work's own\n"
