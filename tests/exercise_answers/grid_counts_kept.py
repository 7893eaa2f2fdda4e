"""Wrong (fails 'pair tests'): tests counts only the pairs kept, not every distance computed (the
right pairs, from a grid; vectorised: every pair of particles in neighbouring cells is a
candidate)."""
import numpy as np


def grid_pairs(x, cutoff, box):
    w, h = box
    nx, ny = max(int(w // cutoff), 1), max(int(h // cutoff), 1)
    cx = np.clip((x[:, 0] * nx / w).astype(int), 0, nx - 1)
    cy = np.clip((x[:, 1] * ny / h).astype(int), 0, ny - 1)
    i, j = np.triu_indices(len(x), 1)
    near = (np.abs(cx[i] - cx[j]) <= 1) & (np.abs(cy[i] - cy[j]) <= 1)
    i, j = i[near], j[near]
    keep = np.linalg.norm(x[i] - x[j], axis=1) < cutoff
    return i[keep], j[keep], int(keep.sum())             # the slip: only the pairs kept
