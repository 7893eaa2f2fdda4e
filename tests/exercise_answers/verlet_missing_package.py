"""Wrong (does not import): imports a package that is not installed."""
import numpy_but_faster_xyz


def verlet_step(x, x_prev, a, h, drag):
    return 2 * x - x_prev + a * h * h, x
