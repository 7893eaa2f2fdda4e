"""Hostile: kills its own process group from the step (the grader's too, when the child shared
it). The child has a group of its own: each check fails with 'killed by signal 9'."""
import os
import signal


def verlet_step(x, x_prev, a, h, drag):
    os.killpg(os.getpgrp(), signal.SIGKILL)
