"""Wrong (fails 'pair tests'): the right pairs, found by testing all pairs: n (n - 1) / 2 tests,
the cost the grid exists to avoid."""
import numpy as np


def grid_pairs(x, cutoff, box):
    n = len(x)
    i, j = np.triu_indices(n, 1)
    d = x[j] - x[i]
    close = np.einsum("ij,ij->i", d, d) < cutoff * cutoff
    return i[close], j[close], len(i)
