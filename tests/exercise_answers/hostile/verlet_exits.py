"""Wrong (every check fails, the grader goes on): ends the process, as a library abort would."""
import os


def verlet_step(x, x_prev, a, h, drag):
    os._exit(3)
