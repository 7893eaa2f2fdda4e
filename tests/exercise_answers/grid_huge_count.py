"""Wrong (fails every check with a clear message, never the grader's error): the right pairs, and
tests = 10**400, an integer too large for a float."""
import numpy as np


def grid_pairs(x, cutoff, box):
    d = x[:, None, :] - x[None, :, :]
    close = np.einsum("ijk,ijk->ij", d, d) < cutoff * cutoff
    i, j = np.nonzero(np.triu(close, 1))
    return i, j, 10 ** 400
