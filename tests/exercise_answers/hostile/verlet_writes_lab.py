"""Hostile (issue 23): appends to the grader's own code on disk (once, a later student's wrong
verlet then went from 3/6 to 6/6), and writes outside its folder; its step is right. The
sandbox (Landlock) refuses both writes: the lab's files stay as they were; every check passes."""
import os
from pathlib import Path

_repo = Path(__file__).resolve().parents[3]
for _target in (_repo / "app" / "exercises" / "verlet" / "grader.py",
                Path(os.environ.get("LAB_TEST_OUTSIDE", "/tmp/lab-test-outside.txt"))):
    try:
        with open(_target, "a") as _f:
            _f.write("\n# written by a student's file\n")
        print(f"WROTE {_target}")
    except OSError as _e:
        print(f"refused {_target}: {type(_e).__name__}")


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
