"""Wrong (fails 'inside pushed to the surface'): a loop over the particles whose return sits
inside the loop: only the first particle inside is ever moved."""
import numpy as np


def push_out(x, w, center, radius):
    depth = np.zeros(len(x))
    for i in range(len(x)):
        off = x[i] - center
        d = float(np.hypot(off[0], off[1]))
        if d < radius and w[i] > 0:
            n = off / d if d > 0 else np.array([0.0, -1.0])
            x[i] += (radius - d) * n
            depth[i] = radius - d
            return depth
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
