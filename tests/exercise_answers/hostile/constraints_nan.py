"""Hostile (to the live scene): returns NaN positions (once a traceback from the lab's own
metrics code, not the student's error). The grader fails it with 'NaN'; the scene survives."""
import numpy as np


def satisfy_rods(x, a, b, rest, w, iterations):
    return np.full_like(np.asarray(x, dtype=float), np.nan)
