"""Wrong (fails 'pair tests'): the box read as (h, w): nx from the height, ny from the width, so
on a wide box the cells past x = h all fall in the last column, far wider than the cut-off. The
pairs are right (candidates are still tested), the tests many times too many. (Vectorised: every
pair of particles in neighbouring cells is a candidate.)"""
import numpy as np


def grid_pairs(x, cutoff, box):
    h, w = box                                       # the slip: box is (w, h)
    nx, ny = max(int(w // cutoff), 1), max(int(h // cutoff), 1)
    cx = np.clip((x[:, 0] * nx / w).astype(int), 0, nx - 1)
    cy = np.clip((x[:, 1] * ny / h).astype(int), 0, ny - 1)
    i, j = np.triu_indices(len(x), 1)
    near = (np.abs(cx[i] - cx[j]) <= 1) & (np.abs(cy[i] - cy[j]) <= 1)
    i, j = i[near], j[near]
    d = np.linalg.norm(x[i] - x[j], axis=1)
    keep = d < cutoff
    return i[keep], j[keep], int(near.sum())
