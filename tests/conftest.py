"""Test set-up: every test runs headless (no window, no sound), from the repository root."""

import os
import sys

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ["SDL_AUDIODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

# Property tests draw the same examples on every run (deterministic suite, no example database).
import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

settings.register_profile("lab", derandomize=True, database=None)
settings.load_profile("lab")


def pytest_configure(config):
    """Compile the lab's sources once, before the workers start (the controller only). Every
    process the suite starts imports them: the xdist workers, each `python -m app` a test runs,
    each sandboxed grader child (its harness copies the compiled files when they exist). Where
    PYTHONDONTWRITEBYTECODE is set (this machine's environment) nothing else writes them, and
    every one of those processes compiled the sources again: the suite on a fresh clone took
    154 s against 132 s with them compiled (2026-11-26). __pycache__/ is in .gitignore."""
    if hasattr(config, "workerinput"):
        return
    import compileall
    import re
    skip = re.compile(r"exercise_answers")      # students' files, some broken on purpose
    for folder in ("app", "scenes", "tests", "exercises", "autograder"):
        path = os.path.join(ROOT, folder)
        if os.path.isdir(path):
            compileall.compile_dir(path, quiet=1, rx=skip)


_DONT_WRITE_BYTECODE = sys.dont_write_bytecode


def pytest_collection(session):
    """While the tests are collected, pytest keeps each test module's rewritten asserts in
    tests/__pycache__ (*-pytest-<version>.pyc, checked against the source's mtime and size, as
    Python's own .pyc): where PYTHONDONTWRITEBYTECODE is set it kept none, and every worker of
    every run rewrote all the test modules again (~2.5 s CPU a worker). Only the collection
    writes: a test's own imports (a student's file in a test's folder) write nothing."""
    sys.dont_write_bytecode = False


def pytest_collection_finish(session):
    sys.dont_write_bytecode = _DONT_WRITE_BYTECODE


@pytest.fixture
def png_charts(monkeypatch):
    """A benchmark's charts written as PNG only, not also as SVG (~0.4 s a chart): for the tests
    of a benchmark's numbers and files; the SVG (size, texts, ids) is tests/test_charts.py's."""
    import app.draw.plot as plot
    monkeypatch.setattr(plot, "FORMATS", ("png",))


def _fsync_checks_the_fd_only(fd):
    """os.fsync's stand-in in the tests: the same OSError for a descriptor that is not open, no
    wait for the disk."""
    os.fstat(fd)


@pytest.fixture(autouse=True)
def no_disk_flush_but_in_the_outputs_tests(request, monkeypatch):
    """Every file the lab writes is flushed to the disk before its rename (app/outputs.py:
    os.fsync; scene files go through it too), ~4 ms each on this machine's disk when quiet and
    longer when other work writes: ~1100 of them in a suite, a worker waiting on the disk ~4.5 s of
    wall time (cProfile, 2026-11-27). No test can see whether the data reached the platters, so
    outside tests/test_outputs.py (the tests of the writes themselves, which keep the real
    fsync) the flush only checks its descriptor; the temporary file, its rename and every
    failure path run as they do for a user. Forked grader children inherit it; the `python -m
    app` processes a test starts do not (they flush)."""
    if request.node.path.name != "test_outputs.py":
        monkeypatch.setattr(os, "fsync", _fsync_checks_the_fd_only)


@pytest.fixture(autouse=True)
def no_display_events_left():
    """No test hands its window's events to the next test of its xdist worker: after each test,
    whatever the display queued and the test did not read is dropped. The display is the
    process's, and a test that only calls its window's methods never reads the queue: the F11
    tests (test_projector.py) left the full-screen round trip's VIDEORESIZE and mouse motions
    queued, and the next test to read the queue (the sandbox panel's type_enter, test_projector's
    and test_projector_room's _pump) handed them to its own window, which laid itself out again
    for 800x600 and rebuilt its panel; the pygame-gui event of the box typed into (queued behind
    them) then named a box no longer in the panel and was dropped. That was the sandbox panel
    test's flake (1 in ~4 full runs, wherever xdist ran it after an F11 test in one worker; the
    pair `tests/test_projector.py::test_f11_goes_full_screen_and_back_to_the_window_size
    tests/test_sandbox_panel.py -n 0` failed every time before)."""
    yield
    pygame = sys.modules.get("pygame")
    if pygame is not None and pygame.display.get_init():
        pygame.event.clear()
