"""Right, and slow: its first step waits 0.6 s (a machine that loads it, a slow first call).
tests/test_exercises_hostile.py times it against a limit taken from the reference's time."""
import time

_first = [True]


def verlet_step(x, x_prev, a, h, drag):
    if _first[0]:
        _first[0] = False
        time.sleep(0.6)
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
