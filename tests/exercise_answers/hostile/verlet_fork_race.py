"""Hostile (bounded): a chain of forks racing the grader's kill: each process forks its successor
and leaves at once, for 5 s, appending pids to LAB_TEST_PID_FILE; the step loops. The grader's
killpg is atomic with fork (a fork caught by the kill is undone): none may be left."""
import os
import time

if os.fork() == 0:
    end = time.monotonic() + 5.0
    out = os.environ.get("LAB_TEST_PID_FILE")
    while time.monotonic() < end:
        if os.fork() != 0:
            os._exit(0)
        if out:
            with open(out, "a") as f:
                f.write(f"{os.getpid()}\n")
        time.sleep(0.002)
    os._exit(0)


def verlet_step(x, x_prev, a, h, drag):
    while True:
        pass
