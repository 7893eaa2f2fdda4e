"""Hostile (issue 23, bounded): forks up to 1000 sleeping processes at import (a fork bomb that
stops itself), then prints how many it got; its step is right. The child's pids cgroup stops it
at 128 processes and threads (the forks after fail with BlockingIOError), and the PID namespace
ends them all with the check."""
import os
import time

_got = 0
for _ in range(1000):
    try:
        if os.fork() == 0:
            time.sleep(60)
            os._exit(0)
        _got += 1
    except OSError:
        break
print(f"forked {_got}")


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
