"""Wrong (fails 'a slow slide sticks'): friction only where depth > 1e-3 px, as a "numerical
guard": a particle that touched only a little is left sliding. At 1000 Hz a cloth resting on a
surface is pushed out only g h^2 = 0.001 px a step, so it would never feel friction."""
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
    touching = depth > 1e-3
    off = x[touching] - center
    n = off / np.linalg.norm(off, axis=1)[:, None]
    v = x[touching] - x_prev[touching]
    vt = v - (v * n).sum(axis=1)[:, None] * n
    speed = np.linalg.norm(vt, axis=1)
    cap = mu * depth[touching]
    slide = speed > cap
    vt[slide] *= (cap[slide] / speed[slide])[:, None]
    x[touching] -= vt
