"""The command line's small parts: a parser whose errors are one line (exit 2), the checks of
option values (numbers, seconds, sizes, seeds), `--set KEY=VALUE` pairs, and the dummy video
driver for commands that draw without a window. app/__main__.py builds its parsers from them."""

from __future__ import annotations

import argparse
import math
import os
from typing import NoReturn

from app.clips import MAX_FPS, MAX_WIDTH, MIN_WIDTH
from app.headless import MAX_STEPS
from app.cli_checks import UsageError
from app.outputs import one_line
from app.scene import plain_number, shown_text


class _Parser(argparse.ArgumentParser):
    """argparse, but an error is one line and exit code 2 (no usage block)."""

    def error(self, message: str) -> NoReturn:
        # argparse echoes what it refuses: cut a pasted wall of text to one readable line
        raise UsageError(one_line(message, 300))


def _positive_float(text: str) -> float:
    try:
        if not plain_number(text):      # '1_0', '١': plain ASCII only (docs/reference.md)
            raise ValueError(text)
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not a number in plain ASCII; "
                                         "accepted: seconds > 0")
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not accepted; accepted: a finite "
                                         "number of seconds > 0")
    return value


MAX_TIMEOUT = 3600.0        # seconds: a check's time limit (a larger wait overflows the timer)


def _timeout(text: str) -> float:
    value = _positive_float(text)
    if value > MAX_TIMEOUT:
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not accepted; accepted: seconds "
                                         f"> 0 and at most {MAX_TIMEOUT:g}")
    return value


def _seed(text: str) -> int:
    """--seed: the exercise checks' random cases (a whole number, 0 to 2**32 - 1)."""
    return _int_in(text, 0, 2 ** 32 - 1, "a seed")


def _int_in(text: str, lo: int, hi: int, what: str) -> int:
    try:
        if not plain_number(text):
            raise ValueError(text)
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not an integer in plain ASCII; "
                                         f"accepted: {what} from {lo} to {hi}")
    if not lo <= value <= hi:
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not accepted; accepted: {what} "
                                         f"from {lo} to {hi}")
    return value


def _fps(text: str) -> int:
    return _int_in(text, 1, MAX_FPS, "frames per second")


def _width(text: str) -> int:
    return _int_in(text, MIN_WIDTH, MAX_WIDTH, "a width in pixels")


def _positive_int(text: str) -> int:
    return _int_in(text, 1, MAX_STEPS, "steps")


MIN_WINDOW, MAX_WINDOW = (640, 480), (7680, 4320)     # --size: the smallest and largest window


def _window_size(text: str) -> tuple[int, int]:
    """--size WxH: a window of W by H pixels (e.g. 1920x1080)."""
    accepted = (f"accepted: WIDTHxHEIGHT in pixels, e.g. 1920x1080, from {MIN_WINDOW[0]}x"
                f"{MIN_WINDOW[1]} to {MAX_WINDOW[0]}x{MAX_WINDOW[1]}")
    w, sep, h = text.strip().lower().partition("x")
    if not sep or not (plain_number(w) and plain_number(h) and w.isdigit() and h.isdigit()):
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not a size; {accepted}")
    size = (int(w), int(h))
    if not all(lo <= v <= hi for v, lo, hi in zip(size, MIN_WINDOW, MAX_WINDOW)):
        raise argparse.ArgumentTypeError(f"{shown_text(text)} is not accepted; {accepted}")
    return size


def use_dummy_video() -> None:
    """Headless runs and benchmarks draw off-screen: no window, no sound."""
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    # SDL would turn Ctrl-C into a quit event nobody reads: let Python see it (exit code 130)
    os.environ.setdefault("SDL_NO_SIGNAL_HANDLERS", "1")


def parse_sets(pairs: list[str]) -> dict[str, str]:
    out: dict[str, str] = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise UsageError(f"--set {shown_text(pair)}: expected KEY=VALUE, e.g. --set "
                             "substeps=4")
        if key.strip() in out:
            raise UsageError(f"--set {shown_text(key.strip())} is given twice; give it once")
        out[key.strip()] = value.strip()
    return out
