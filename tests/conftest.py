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
from hypothesis import settings  # noqa: E402

settings.register_profile("lab", derandomize=True, database=None)
settings.load_profile("lab")
