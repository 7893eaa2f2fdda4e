"""Hostile (issue 23): a double-forked setsid daemon that sleeps a minute (once it outlived the
check: a new session escapes a process-group kill); its step is right. The child's PID
namespace ends with it: the kernel kills the daemon too."""
import os
import time

if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        time.sleep(60)
    os._exit(0)
time.sleep(0.2)


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
