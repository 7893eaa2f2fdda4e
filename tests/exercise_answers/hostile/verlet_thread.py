"""Hostile: starts a non-daemon thread at import that never ends (Python waits for such a thread
at exit: it once hung the grader with no output, and the live scene too); its step does nothing."""
import threading
import time


def _forever():
    while True:
        time.sleep(0.05)


threading.Thread(target=_forever).start()


def verlet_step(x, x_prev, a, h, drag):
    return x.copy(), x.copy()
