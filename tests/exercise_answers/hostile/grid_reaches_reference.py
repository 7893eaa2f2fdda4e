"""Hostile (issue 23): hands in the lab's own grid_pairs, found three ways (once each passed):
exec'ing app/physics/neighbours.py from the repository, importlib, and the frames of the grader's
stack. None reaches it in the sandbox (the repository is unreadable; the harness holds a stub):
the file says so on its output, and its own answer (no pairs) fails."""
import importlib
import sys
from pathlib import Path

import numpy as np

_found = None
try:
    _ns = {"__name__": "stolen"}
    _src = Path(__file__).resolve().parents[3] / "app" / "physics" / "neighbours.py"
    exec(compile(_src.read_text(), str(_src), "exec"), _ns)
    _found = _ns["grid_pairs"]
    print("EXEC got it")
except Exception as _e:
    print(f"exec refused: {type(_e).__name__}")
try:
    _mod = importlib.import_module("app.physics.neighbours")
    _mod.grid_pairs(np.zeros((2, 2)), 10.0, (100.0, 100.0))
    _found = _found or _mod.grid_pairs
    print("IMPORTLIB got it")
    del _mod
except Exception as _e:
    print(f"importlib refused: {type(_e).__name__}")
_frame = sys._getframe()
while _frame is not None:
    _g = _frame.f_globals.get("grid_pairs")
    if callable(_g):
        try:
            _g(np.zeros((2, 2)), 10.0, (100.0, 100.0))
            _found = _found or _g
            print("FRAMES got it")
        except Exception as _e:
            print(f"frames refused: {type(_e).__name__}")
    _frame = _frame.f_back
_mod = _g = None


def grid_pairs(x, cutoff, box):
    if _found is not None:
        return _found(x, cutoff, box)
    return np.zeros(0, dtype=int), np.zeros(0, dtype=int), 0
