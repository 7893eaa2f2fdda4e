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
