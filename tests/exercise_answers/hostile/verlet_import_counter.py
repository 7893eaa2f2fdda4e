"""Hostile (right answer): counts its imports in the file named by LAB_TEST_COUNT_FILE (a file
that slept 9 s at import was once imported again for every check: 56 s). Imported once per
exercise now."""
import os

if os.environ.get("LAB_TEST_COUNT_FILE"):
    with open(os.environ["LAB_TEST_COUNT_FILE"], "a") as f:
        f.write("imported\n")


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x.copy()
