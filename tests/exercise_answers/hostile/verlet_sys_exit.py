"""Wrong (every check fails; the live scene stops with the message): sys.exit in the step."""
import sys


def verlet_step(x, x_prev, a, h, drag):
    sys.exit("giving up")
