"""Hostile (bounded): forks 10 children at import, each forking one more, all sleeping for a
minute; each appends its pid to LAB_TEST_PID_FILE. Its step is right: every check passes, and
the grader must leave none of the 20 processes behind."""
import os
import time


def _note() -> None:
    if os.environ.get("LAB_TEST_PID_FILE"):
        with open(os.environ["LAB_TEST_PID_FILE"], "a") as f:
            f.write(f"{os.getpid()}\n")


for _ in range(10):
    if os.fork() == 0:
        os.fork()
        _note()
        time.sleep(60)
        os._exit(0)


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
