"""Hostile: stops its own process (SIGSTOP) in the step: the check must end at its time limit."""
import os
import signal


def verlet_step(x, x_prev, a, h, drag):
    os.kill(os.getpid(), signal.SIGSTOP)
