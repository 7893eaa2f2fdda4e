"""Hostile: patches the grader from inside (once: 5/5 with a step that does nothing, the verdict
being computed in the student's process): every Result passes, every check's measure returns a
claim of success. The verdicts are the parent's now: all fail."""
import app.exercises.base as base
import app.exercises.grade as grade
from app.exercises import get_exercise

_real = base.Result
base.Result = lambda passed, *a, **k: _real(True, *a, **k)
grade.Result = base.Result
for check in get_exercise("verlet").checks:
    object.__setattr__(check, "measure", lambda m: {"passed": True})


def verlet_step(x, x_prev, a, h, drag):
    return x.copy(), x.copy()
