"""Hostile: loops for ever at import. The import is stopped at the time limit and the checks
are not run."""
while True:
    pass


def verlet_step(x, x_prev, a, h, drag):
    return x, x
