"""Hostile: starts a background process at import (once it outlived the check and `... | cat`
waited for it); its step does nothing. The grader ends the child's whole process group."""
import os
import subprocess

_sleeper = subprocess.Popen(["sleep", "60"])
if os.environ.get("LAB_TEST_PID_FILE"):
    with open(os.environ["LAB_TEST_PID_FILE"], "w") as f:
        f.write(str(_sleeper.pid))


def verlet_step(x, x_prev, a, h, drag):
    return x.copy(), x.copy()
