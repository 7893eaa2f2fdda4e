"""Wrong (fails 'random boxes and cut-offs'): the cut-off hard-coded to 40, the value every fixed
check used (the live scene's is 60)."""
import numpy as np


def grid_pairs(x, cutoff, box):
    cutoff = 40.0
    x = np.asarray(x, dtype=float)
    nx, ny = max(1, int(box[0] // cutoff)), max(1, int(box[1] // cutoff))
    cx = np.clip((x[:, 0] * nx / box[0]).astype(int), 0, nx - 1)
    cy = np.clip((x[:, 1] * ny / box[1]).astype(int), 0, ny - 1)
    cell = cy * nx + cx
    order = np.argsort(cell, kind="stable")
    starts = np.searchsorted(cell[order], np.arange(nx * ny + 1))
    found_i, found_j, tests = [], [], 0
    for c in np.unique(cell):
        mine = order[starts[c]:starts[c + 1]]
        y, xx = divmod(int(c), nx)
        for dx, dy in ((0, 0), (1, 0), (-1, 1), (0, 1), (1, 1)):
            ox, oy = xx + dx, y + dy
            if not (0 <= ox < nx and 0 <= oy < ny):
                continue
            other = order[starts[oy * nx + ox]:starts[oy * nx + ox + 1]]
            p, q = np.meshgrid(mine, other, indexing="ij")
            p, q = p.ravel(), q.ravel()
            if (dx, dy) == (0, 0):
                keep = p < q
                p, q = p[keep], q[keep]
            tests += len(p)
            d = x[q] - x[p]
            close = np.einsum("ij,ij->i", d, d) < cutoff * cutoff
            found_i.append(p[close])
            found_j.append(q[close])
    if not found_i:
        return np.zeros(0, int), np.zeros(0, int), 0
    return np.concatenate(found_i), np.concatenate(found_j), tests
