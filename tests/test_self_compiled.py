"""The compiled self-collision pass (kernel=numba, app/physics/self_compiled.py) against the NumPy
pass it stands in for: the same pairs, and the same positions after it, on seeded random clouds
of every kind. Skipped where numba is missing (tests/test_cloth_kernel.py checks the refusal)."""

import numpy as np
import pytest

from app.physics import rods_compiled
from app.physics.cloth import Cloth
from app.physics.cloth_contact import close_ij, joined_table, self_collide
from app.physics.neighbours import all_pairs, fine_stencil
from app.physics.obstacles import floor

needs_numba = pytest.mark.skipif(not rods_compiled.available(), reason="numba not installed")


def pair_set(i, j):
    return set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))


def squeezed(seed: int, rows: int, cols: int, squeeze: float, dtype, sets: set,
             weights: str, on_floor: bool) -> Cloth:
    """A cloth squeezed to `squeeze` of its size and jittered by a spacing (layers on layers:
    hundreds of pairs), its weights all 1 ("even"), some pinned and one grabbed ("mixed"),
    with a floor through its middle (the obstacles projected before each sweep) or none."""
    rng = np.random.default_rng(seed)
    c = Cloth(rows, cols, 8.0, (100.0, 100.0), "none", sets | {"self_collision"}, dtype)
    x = c.x.reshape(2, -1)
    mid = x.mean(1, keepdims=True)
    x[...] = mid + (x - mid) * squeeze + rng.uniform(-4, 4, x.shape)
    c.contact.self_distance = 6.4
    if weights == "mixed":
        w = c.w.reshape(-1)
        w[rng.choice(w.size, w.size // 8, replace=False)] = 0.0       # pinned
        w[rng.integers(w.size)] = 0.25                                 # grabbed (heavier)
        c.update_weights()
    if on_floor:
        c.set_effects(c.on | {"collisions"})
        c.set_obstacles([floor(float(mid[1, 0]), label="floor")])
    return c


@needs_numba
def test_the_compiled_pass_moves_random_clouds_as_the_numpy_pass_does():
    """Seeded random cases (sizes, squeezes, float32 and float64, rod sets, pinned and grabbed
    particles, a floor or none): the compiled pass finds the NumPy pass's pairs and leaves the
    positions where it does, to 1e-4 px (the NumPy pass's own float32 rounding is ~3e-5 px
    here), one pass from the same state. The seed and case are in the message."""
    rng = np.random.default_rng(2711)
    for case in range(24):
        rows, cols = (int(v) for v in rng.integers(3, 20, 2))
        squeeze = float(rng.uniform(0.15, 0.6))
        dtype = (np.float32, np.float64)[case % 2]
        sets = [{"shear"}, {"shear", "bending"}, set()][case % 3]
        weights = ("even", "mixed")[case // 2 % 2]
        made = [squeezed(case, rows, cols, squeeze, dtype, sets, weights, case % 5 == 0)
                for _ in range(2)]
        a, b = made
        b.kernel = "numba"
        pairs = len(close_ij(a, 6.4, "grid")[0])
        self_collide(a, 1 / 60)
        self_collide(b, 1 / 60)
        msg = (2711, case, rows, cols, weights)
        assert a.contact.self_pairs == b.contact.self_pairs == pairs, msg
        assert np.abs(a.x - b.x).max() < 1e-4, msg
    assert pairs > 0


@needs_numba
def test_the_compiled_search_is_exact_with_more_rows_than_fine_grid_makes(monkeypatch):
    """The search's path for stencils of more than three rows (fine_grid makes three; here
    cells a third as high, eight rows): all pairs' pairs closer than the cut-off, less the
    joined ones, on seeded random clouds."""
    from app.physics import self_compiled

    real_grid = self_compiled.fine_grid

    def thin_rows(xs, ys, cutoff):
        lo_x, lo_y, cell_w, cell_h, nx, ny, _, clamped = real_grid(xs, ys, cutoff)
        cell_h /= 3
        reach = fine_stencil(cutoff, cell_w, cell_h)
        return lo_x, lo_y, cell_w, cell_h, nx, 3 * ny + 3, reach, clamped

    monkeypatch.setattr(self_compiled, "fine_grid", thin_rows)
    rng = np.random.default_rng(2712)
    for case in range(12):
        dtype = (np.float32, np.float64)[case % 2]
        c = squeezed(case, 12, 14, float(rng.uniform(0.15, 0.6)), dtype, {"shear"}, "even", False)
        x = c.x.reshape(2, -1)
        grid = thin_rows(x[0], x[1], 6.4)
        assert len(grid[6]) > 3, grid[6]                     # the path under test
        i, j, tests = self_compiled.find_pairs(x[0], x[1], 6.4, joined_table(c),
                                               self_compiled.Buffers(x.shape[1]))
        bi, bj, _ = close_ij(c, 6.4, "all_pairs")
        assert pair_set(i, j) == pair_set(bi, bj) and len(i) == len(bi) > 0, (2712, case)
        assert tests >= len(i)
    assert len(all_pairs(x.T, 6.4)[0]) > len(bi)      # (and joined pairs were left out)
