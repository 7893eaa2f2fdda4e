"""Wrong (fails 'pinned never move'): ignores w: pinned particles inside are pushed out too."""
import numpy as np


def push_out(x, w, center, radius):
    off = x - center
    d = np.linalg.norm(off, axis=1)
    n = np.zeros_like(x)
    n[:] = (0.0, -1.0)
    away = d > 0
    n[away] = off[away] / d[away, None]
    inside = d < radius
    depth = np.where(inside, radius - d, 0.0)
    x[inside] += depth[inside, None] * n[inside]
    return depth


def friction(x, x_prev, center, depth, mu):
    touching = depth > 0
    off = x[touching] - center
    n = off / np.linalg.norm(off, axis=1)[:, None]
    v = x[touching] - x_prev[touching]
    vt = v - (v * n).sum(axis=1)[:, None] * n
    speed = np.linalg.norm(vt, axis=1)
    cap = mu * depth[touching]
    slide = speed > cap
    vt[slide] *= (cap[slide] / speed[slide])[:, None]
    x[touching] -= vt
