"""Wrong (fails 'friction only where touching'): friction as a drag on the sliding, mu of it,
on every particle, whether it touches the circle or not."""
import numpy as np


def push_out(x, w, center, radius):
    off = x - center
    d = np.linalg.norm(off, axis=1)
    n = np.zeros_like(x)
    n[:] = (0.0, -1.0)
    away = d > 0
    n[away] = off[away] / d[away, None]
    inside = (d < radius) & (w > 0)
    depth = np.where(inside, radius - d, 0.0)
    x[inside] += depth[inside, None] * n[inside]
    return depth


def friction(x, x_prev, center, depth, mu):
    off = x - center
    n = off / np.linalg.norm(off, axis=1)[:, None]
    v = x - x_prev
    vt = v - (v * n).sum(axis=1)[:, None] * n
    x -= mu * vt
