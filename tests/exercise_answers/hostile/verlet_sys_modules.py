"""Hostile: replaces modules in sys.modules (numpy's linalg, json, the grader's report and
channel) with junk at import, then gives a right step."""
import sys
import types

for name in ("json", "app.exercises.report", "app.exercises.channel", "numpy.linalg"):
    sys.modules[name] = types.ModuleType(name)


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
