"""Wrong (fails 'on the cell borders'): nx = ceil(w / R): cells narrower than the cut-off."""
import numpy as np


def grid_pairs(x: np.ndarray, cutoff: float,
               box: tuple[float, float]) -> tuple[np.ndarray, np.ndarray, int]:
    w, h = box
    import math
    nx, ny = math.ceil(w / cutoff), math.ceil(h / cutoff)
    cx = np.clip((x[:, 0] * nx / w).astype(int), 0, nx - 1)
    cy = np.clip((x[:, 1] * ny / h).astype(int), 0, ny - 1)
    cells = {}
    for k in range(len(x)):
        cells.setdefault((cx[k], cy[k]), []).append(k)
    I, J = [], []
    tests = 0
    for (ci, cj), members in cells.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                other = cells.get((ci + dx, cj + dy), [])
                for p in members:
                    for q in other:
                        if q <= p:
                            continue
                        tests += 1
                        if np.linalg.norm(x[p] - x[q]) < cutoff:
                            I.append(p); J.append(q)
    return np.array(I, dtype=int), np.array(J, dtype=int), tests
