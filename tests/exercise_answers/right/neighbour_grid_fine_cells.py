"""Right: cells HALF a cut-off wide, so a pair closer than the cut-off may be two cells apart:
the 5 x 5 block around each cell is searched (fewer candidates than 3 x 3 cells a cut-off
wide). Cells from x // (R/2) in a dict, no clamping needed (x = w just makes one more cell)."""
import numpy as np


def grid_pairs(x, cutoff, box):
    size = cutoff / 2
    cells = {}
    for k, (px, py) in enumerate(x):
        cells.setdefault((int(px // size), int(py // size)), []).append(k)
    I, J, tests = [], [], 0
    for (cx, cy), members in cells.items():
        for dx in range(-2, 3):
            for dy in range(-2, 3):
                for q in cells.get((cx + dx, cy + dy), ()):
                    for p in members:
                        if q > p:
                            tests += 1
                            if np.hypot(*(x[q] - x[p])) < cutoff:
                                I.append(p)
                                J.append(q)
    return np.array(I, dtype=np.int64), np.array(J, dtype=np.int64), tests
