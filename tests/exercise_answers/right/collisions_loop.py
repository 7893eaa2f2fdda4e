"""Right: both functions as plain loops over the particles with math.hypot, the surface point
placed as c + r n (not x + depth n), friction as the travel kept (1 - share) v_t."""
import math

import numpy as np


def push_out(x, w, center, radius):
    depth = np.zeros(len(x))
    cx, cy = float(center[0]), float(center[1])
    for i in range(len(x)):
        dx, dy = x[i, 0] - cx, x[i, 1] - cy
        d = math.hypot(dx, dy)
        if w[i] == 0 or d >= radius:
            continue
        nx, ny = (dx / d, dy / d) if d > 0 else (0.0, -1.0)
        x[i, 0], x[i, 1] = cx + radius * nx, cy + radius * ny
        depth[i] = radius - d
    return depth


def friction(x, x_prev, center, depth, mu):
    for i in range(len(x)):
        if depth[i] <= 0:
            continue
        dx, dy = x[i, 0] - center[0], x[i, 1] - center[1]
        d = math.hypot(dx, dy)
        nx, ny = dx / d, dy / d
        vx, vy = x[i, 0] - x_prev[i, 0], x[i, 1] - x_prev[i, 1]
        along = vx * nx + vy * ny
        tx, ty = vx - along * nx, vy - along * ny
        speed = math.hypot(tx, ty)
        keep = 0.0 if speed <= mu * depth[i] else 1.0 - mu * depth[i] / speed
        x[i, 0] -= (1.0 - keep) * tx
        x[i, 1] -= (1.0 - keep) * ty
