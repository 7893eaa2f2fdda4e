"""Hostile (bounded): forks 10 children at import, each forking one more, all sleeping for a
minute; each appends its pid to LAB_TEST_PID_FILE (and the import waits, up to 5 s, until all 20
have: on a loaded machine the grader could otherwise end one before it wrote, and the test would
count 19). Its step is right: every check passes, and the grader must leave none of the 20
processes behind."""
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

_file, _wait = os.environ.get("LAB_TEST_PID_FILE"), time.monotonic() + 5.0
while _file and time.monotonic() < _wait and (
        not os.path.exists(_file) or len(open(_file).read().split()) < 20):
    time.sleep(0.01)


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
