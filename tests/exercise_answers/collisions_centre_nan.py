"""Wrong (fails 'a particle at the centre'): divides by |x - c| without a guard: the particle
at the centre becomes NaN."""
import numpy as np


def push_out(x, w, center, radius):
    off = x - center
    d = np.linalg.norm(off, axis=1)
    n = off / d[:, None]
    inside = (d < radius) & (w > 0)
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
