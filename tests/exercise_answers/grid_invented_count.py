"""Wrong (fails 'pair tests'): the right pairs by testing every pair, and an invented count of
tests between the pairs found and the grid's bound."""
import numpy as np


def grid_pairs(x, cutoff, box):
    d = x[:, None, :] - x[None, :, :]
    close = np.einsum("ijk,ijk->ij", d, d) < cutoff * cutoff
    i, j = np.nonzero(np.triu(close, 1))
    return i, j, 3 * len(i) + 17
