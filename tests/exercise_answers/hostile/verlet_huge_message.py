"""Hostile: raises an exception with a 20 MB message in its step (once the HUD asked pygame for
a surface that size: 'Out of memory'). The message is cut to a readable size everywhere."""


def verlet_step(x, x_prev, a, h, drag):
    raise ValueError("no " * 7_000_000)
