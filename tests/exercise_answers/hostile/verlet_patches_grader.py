"""Hostile: patches the grader from inside (once: 5/5 with a step that does nothing, the verdict
being computed in the student's process): every Result passes, every check's measure returns a
claim of success. The verdicts are the parent's now: all fail. (It reaches the grader through
sys.modules, keeping no name of the lab's in its module: a plain `import app...` is refused.)"""
import sys


def _patch():
    base, grade = sys.modules["app.exercises.base"], sys.modules["app.exercises.grade"]
    real = base.Result
    base.Result = lambda passed, *a, **k: real(True, *a, **k)
    grade.Result = base.Result
    for check in sys.modules["app.exercises"].get_exercise("verlet").checks:
        object.__setattr__(check, "measure", lambda m: {"passed": True})


_patch()


def verlet_step(x, x_prev, a, h, drag):
    return x.copy(), x.copy()
