"""Hostile (issue 23): SIGTERMs its parent, the grader's process group and every process it can
see (once: the grader ended with exit 143 and no report); its step is right. Landlock's signal
scope and the PID namespace keep every signal inside its sandbox: the grader reports 6/6."""
import os
import signal

for _target in (os.getppid(), -os.getpgid(0), int(os.environ.get("LAB_TEST_VICTIM", "0")),
                int(os.environ.get("LAB_TEST_GRADER", "0"))):
    try:
        if _target:
            os.kill(_target, signal.SIGTERM)
    except OSError as _e:
        print(f"refused {_target}: {type(_e).__name__}")
_victim = os.environ.get("LAB_TEST_VICTIM")
if _victim:
    try:
        os.killpg(os.getpgid(int(_victim)), signal.SIGTERM)
    except OSError as _e:
        print(f"refused group of {_victim}: {type(_e).__name__}")


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
