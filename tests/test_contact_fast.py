"""The cloth's fast contact paths find what the plain ones find: the fused tunnelling test and
projection (app/physics/cloth_contact.py, tunnelling.through_one) against swept() + project(),
and the self-collision grid against all pairs. Seeded random states; cheap (well under 1 s)."""

import itertools

import numpy as np
import pytest

from app.physics import rods_compiled
from app.physics.cloth import Cloth
from app.physics.cloth_contact import ContactState, close_pairs, self_collide
from app.physics import cloth_obstacles
from app.physics.cloth_obstacles import tunnel_and_project
from app.physics.neighbours import Scratch, all_pairs, fine_pairs
from app.physics.obstacles import Box, Circle, Segment, floor, project
from app.physics.tunnelling import swept, through_one
from scenes.cloth import ClothScene

SHAPES = [Circle(0.0, 0.0, 30.0), Box(5.0, -3.0, 40.0, 6.0, 0.35), Segment(-40, 10, 35, -5, 2.0)]


def random_paths(seed, n=4000):
    """Paths of every length (0.01 to 200 px) and direction around the shapes: a few hundred
    go through one, cut a corner, slide along a face or end past its middle."""
    rng = np.random.default_rng(seed)
    a = rng.uniform(-80, 80, (n, 2))
    length = 10 ** rng.uniform(-2, 2.3, n)
    angle = rng.uniform(0, 2 * np.pi, n)
    b = a + length[:, None] * np.column_stack((np.cos(angle), np.sin(angle)))
    return a, b


@pytest.mark.parametrize("ob", SHAPES, ids=lambda ob: ob.kind)
def test_through_one_finds_what_swept_finds(ob):
    tolerance = 1.0
    for seed in range(3):
        a, b = random_paths(seed)
        sw = swept([ob], a, b, tolerance, past_middle=True)
        d1, n1x, n1y = ob.distance_xy(b[:, 0], b[:, 1])
        back, t, nx, ny, through = through_one(ob, a[:, 0], a[:, 1], b[:, 0] - a[:, 0],
                                               b[:, 1] - a[:, 1], d1, n1x, n1y, tolerance)
        expected = np.flatnonzero(sw.mask | sw.deep)
        assert expected.size > 20 and sw.count > 5          # the test has cases to check
        assert np.array_equal(np.sort(back), expected) and through == sw.count
        entry = a[back] + t[:, None] * (b[back] - a[back])
        assert np.allclose(entry, sw.entry[back], atol=1e-9)
        # the normal given with the entry: the outward normal just outside that point
        _, ox, oy = ob.distance_xy(entry[:, 0] + 1e-6 * nx, entry[:, 1] + 1e-6 * ny)
        assert np.allclose(np.hypot(nx, ny), 1.0) and np.allclose(ox, nx, atol=1e-4) and \
            np.allclose(oy, ny, atol=1e-4)


def reference(obstacles, start, x, movable, margin, tolerance):
    """The plain pipeline: every path through an obstacle put back where it entered (swept),
    then every particle projected (project)."""
    sw = swept(obstacles, start.T, x, tolerance, movable, past_middle=True)
    back = sw.mask | sw.deep
    x[back] = sw.entry[back]
    return project(obstacles, x, margin, movable), sw.count


@pytest.mark.parametrize("ob", SHAPES[:2] + [floor(40.0)], ids=lambda ob: ob.kind)
def test_fused_tunnelling_and_projection_match_the_plain_pipeline(ob):
    for seed in range(3):
        a, b = random_paths(10 + seed)
        movable = np.random.default_rng(seed).uniform(size=len(a)) > 0.1
        b[~movable] = a[~movable]
        x_ref, x_new = b.copy(), b.copy()
        contacts, count = reference([ob], a.T.copy(), x_ref, movable, 0.25, 1.0)
        st = ContactState(obstacles=[ob])
        fused = tunnel_and_project(st, a.T.copy(), x_new, movable).full()
        assert contacts.count > 100 and st.tunneled == count
        assert np.array_equal(fused.mask, contacts.mask)
        # put back: on the surface where the path entered, then pushed out to the margin (the
        # plain pipeline measures the normal again at the entry point: in float64 that point
        # can sit within 1e-12 px outside, where Box.distance_xy's normal is shorter than 1)
        sw = swept([ob], a, b, 1.0, movable, past_middle=True)
        back = sw.mask | sw.deep
        assert np.allclose(ob.distance(x_new[back, 0], x_new[back, 1]), 0.25, atol=1e-9)
        assert np.all(np.hypot(*(x_new[back] - sw.entry[back]).T) < 0.25 + 1e-9)
        same = ~back
        assert np.allclose(x_new[same], x_ref[same], atol=1e-9)
        assert np.allclose(fused.depth[same], contacts.depth[same], atol=1e-9)
        assert np.allclose(fused.normal[same], contacts.normal[same], atol=1e-9)


@pytest.mark.parametrize("longest", [2.0, 5.0])
def test_the_tunnelling_test_skipped_for_short_paths_changes_nothing(longest, monkeypatch):
    """The pass skips an obstacle's tunnelling test when no path of the substep can be long
    enough (cloth_obstacles._paths_too_short), counting what the obstacles before it moved a
    particle (the ball pushes particles out by up to its radius, into the box it overlaps):
    the same positions and contacts as with the test never skipped."""
    obstacles = [Circle(0.0, 0.0, 30.0), Box(30.0, 0.0, 20.0, 10.0, 0.2), floor(8.0)]
    rng = np.random.default_rng(3)
    a = rng.uniform((-35, -20), (55, 12), (3000, 2)).astype(np.float32)
    angle = rng.uniform(0, 2 * np.pi, len(a))
    step = rng.uniform(0, longest / np.sqrt(2), len(a))[:, None]
    b = (a + step * np.column_stack((np.cos(angle), np.sin(angle)))).astype(np.float32)
    movable = rng.uniform(size=len(a)) > 0.1
    runs = []
    for skipping in (True, False):
        if not skipping:
            monkeypatch.setattr(cloth_obstacles, "_paths_too_short", lambda *args: False)
        st, x = ContactState(obstacles=obstacles), b.copy()
        runs.append((x, tunnel_and_project(st, a.T.copy(), x, movable).full(), st.tunneled))
    (x1, c1, t1), (x2, c2, t2) = runs
    assert c1.count > 500 and t1 == t2 and np.array_equal(x1, x2)
    for mine, theirs in ((c1.mask, c2.mask), (c1.depth, c2.depth), (c1.normal, c2.normal)):
        assert np.array_equal(mine, theirs)


def test_a_particle_pushed_by_two_obstacles_is_listed_once_as_project_gives_it():
    """Where two obstacles overlap, a particle pushed out of the first may land in the second:
    the pass lists it once, its pushes added up and the second's normal, as project() does;
    the positions come out the same to the last bit (short paths: no tunnelling)."""
    obstacles = [Circle(0.0, 0.0, 30.0), Box(10.0, 0.0, 30.0, 12.0, 0.3), floor(12.0)]
    rng = np.random.default_rng(5)           # (all within both boxes: candidates of both)
    a = rng.uniform((-18, -17), (28, 17), (3000, 2)).astype(np.float32)
    b = (a + rng.uniform(-0.4, 0.4, a.shape)).astype(np.float32)
    movable = rng.uniform(size=len(a)) > 0.1
    x_ref, x_new = b.copy(), b.copy()
    contacts = project(obstacles, x_ref, 0.25, movable)
    listed = tunnel_and_project(ContactState(obstacles=obstacles), a.T.copy(), x_new, movable)
    twice = sum(np.count_nonzero(project([ob], b.copy(), 0.25, movable).mask) for ob in obstacles)
    assert twice > contacts.count + 20 and listed.count == contacts.count
    full = listed.full()
    assert np.array_equal(x_new, x_ref) and np.array_equal(full.mask, contacts.mask)
    for mine, theirs in ((full.depth, contacts.depth), (full.normal, contacts.normal),
                         (full.index, contacts.index)):
        assert np.array_equal(mine, theirs)


def crumpled_cloth(seed, n=24):
    """A cloth squeezed to a third and jittered (the crumpled start), float32 like the app's."""
    rng = np.random.default_rng(seed)
    c = Cloth(n, n, 8.0, (100.0, 100.0), "none", {"shear"})
    x = c.x.reshape(2, -1)
    mid = x.mean(1, keepdims=True)
    x[...] = mid + (x - mid) / 3 + rng.uniform(-8 / 3, 8 / 3, x.shape)
    return c


def pair_set(i, j):
    return set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))


def test_self_collision_grid_finds_exactly_the_pairs_all_pairs_finds():
    for seed in range(3):
        c = crumpled_cloth(seed)
        for distance, least in ((6.4, 1000), (2.0, 30)):
            grid = close_pairs(c, distance, "grid")
            brute = close_pairs(c, distance, "all_pairs")
            assert len(grid[0]) > least
            assert pair_set(grid[0], grid[1]) == pair_set(brute[0], brute[1])


def test_the_fine_grid_finds_exactly_all_pairs_pairs_in_crowds_lines_and_spread_out_boxes():
    """neighbours.fine_pairs (cells R/8 x R/2, a stencil trimmed to the circle, candidates in
    blocks, work arrays reused between calls) against all_pairs: crowds (a block's runs longer
    than a block), a line (one row of cells), a spread-out box (cells grown), points on cell
    borders (integer coordinates), and a second call reusing the same work arrays."""
    rng = np.random.default_rng(7)
    clouds = {"crowd": rng.normal(0, 3, (2, 400)), "line": np.stack([np.linspace(0, 600, 500),
                                                                     np.zeros(500)]),
              "spread": rng.uniform(0, 2000, (2, 800)), "uniform": rng.uniform(0, 100, (2, 600)),
              "lattice": np.stack(np.meshgrid(np.arange(24.0), np.arange(24.0))).reshape(2, -1)}
    scratch = Scratch()
    for (name, x), dtype in itertools.product(clouds.items(), (np.float32, np.float64)):
        x = x.astype(dtype)                         # (a float64 cloth: its own rounding)
        for cutoff in (6.4, 1.0):
            i, j, tests = fine_pairs(x[0], x[1], cutoff, scratch)
            bi, bj, all_tests = all_pairs(x.T, cutoff)
            assert pair_set(i, j) == pair_set(bi, bj) and len(i) == len(bi), (name, cutoff)
            assert np.all(i != j) and tests <= all_tests
    assert len(fine_pairs(*clouds["crowd"].astype(np.float32), 6.4, scratch)[0]) > 5000


def test_the_fine_grid_matches_all_pairs_on_random_clouds_of_every_kind():
    """fine_pairs against all_pairs on 240 clouds drawn at random (seeded, the seed printed):
    1 to 300 points, float32 or float64, cut-offs 0.005 to 100, spread out, crowded, all at
    one point, far from the origin, on a lattice of the cut-off, long and thin, and a pair
    a hair inside the cut-off; the same work arrays for all, as in a run."""
    seed = 20261126
    print("seed", seed)
    rng, scratch = np.random.default_rng(seed), Scratch()
    for case in range(240):
        n = int(rng.choice([1, 2, 3, 30, 300]))
        cutoff = float(rng.choice([0.01, 1.0, 6.4, 50.0]) * rng.uniform(0.5, 2))
        kind = case % 6
        x = [rng.uniform(0, 100, (n, 2)), rng.normal(0, cutoff, (n, 2)),
             np.repeat(rng.uniform(0, 10, (1, 2)), n, 0), rng.uniform(0, 1e4, (n, 2)) + 1e5,
             np.round(rng.uniform(0, 50, (n, 2)) / cutoff) * cutoff,
             rng.uniform(-1e3, 1e3, (n, 2)) * [1, 1e-3]][kind]
        x = x.astype(rng.choice([np.float32, np.float64]))
        if kind == 5 and n > 1:
            x[1] = x[0] + np.array([cutoff, 0], x.dtype) * (1 - 1e-7)
        i, j, _ = fine_pairs(np.ascontiguousarray(x[:, 0]), np.ascontiguousarray(x[:, 1]),
                             cutoff, scratch)
        bi, bj, _ = all_pairs(x, cutoff)
        assert pair_set(i, j) == pair_set(bi, bj) and len(i) == len(bi), (seed, case)
        assert np.all(i != j), (seed, case)


def test_the_fine_grid_lists_the_same_pairs_in_blocks_and_with_int64_runs(monkeypatch):
    """fine_pairs hands out its candidates in blocks of whole runs (one block up to FINE_BLOCK
    candidates) and each run's (owner, first) as two int32s (int64 above HALF_LIMIT
    candidates): many small blocks and int64 runs give the very same pairs, in the same order
    (the order the sweeps sum them in), on the crumpled cloth and on a crowd."""
    from app.physics import neighbours
    rng = np.random.default_rng(11)
    x = crumpled_cloth(0).x.reshape(2, -1)
    clouds = [(x[0].copy(), x[1].copy(), 6.4),
              (*rng.normal(0, 3, (2, 300)).astype(np.float32), 6.4)]
    plain = [tuple(a.copy() for a in fine_pairs(*cloud)[:2]) for cloud in clouds]
    assert len(plain[0][0]) > 1000 and len(plain[1][0]) > 5000
    for block, limit in ((64, 1 << 31), (1 << 16, 0), (1000, 0)):
        monkeypatch.setattr(neighbours, "FINE_BLOCK", block)
        monkeypatch.setattr(neighbours, "HALF_LIMIT", limit)
        for cloud, (i, j) in zip(clouds, plain):
            bi, bj, _ = fine_pairs(*cloud)
            assert np.array_equal(bi, i) and np.array_equal(bj, j), (block, limit)


def test_a_long_thin_box_keeps_the_grid_small_and_exact():
    """One point flung 1e8 to 1e30 px away from a row or a column of others (a blown-up cloth
    lying flat): the same pairs as all pairs, and the cells' counts stay under a MB (growing
    the cells alike on both sides left ~sqrt(length) cells along it: 86 GB at 1e20 px, a
    MemoryError that ended the step)."""
    rng = np.random.default_rng(7)
    for far in (1e8, 1e15, 1e20, 1e30):
        for axis in (0, 1):
            x = rng.normal(0, 6.4, (300, 2))
            x[:, 1 - axis] = 3.0
            x[0, axis] = far
            scratch = Scratch()
            i, j, _ = fine_pairs(np.ascontiguousarray(x[:, 0]), np.ascontiguousarray(x[:, 1]),
                                 6.4, scratch)
            with np.errstate(over="ignore"):
                bi, bj, _ = all_pairs(x, 6.4)
            assert pair_set(i, j) == pair_set(bi, bj) and len(i) == len(bi) > 0, (far, axis)
            assert scratch.arrays["stop"].nbytes < 1e6, (far, axis)      # (the counts)


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_a_cloth_with_one_particle_flung_far_keeps_its_fine_grid(kernel):
    """One particle 1e20 px away from a hanging cloth: the search runs on the rest's own fine
    grid (the far one in a border cell), not on cells grown to cover 1e20 px, where every
    particle shared one cell and all pairs were tested (before that, a MemoryError from the
    counts); the same pairs as all pairs, and the scene steps on."""
    if kernel == "numba" and not rods_compiled.available():
        pytest.skip("numba not installed")
    from app.physics import self_compiled
    from app.physics.cloth_contact import close_ij, joined_table
    scene = ClothScene({"rows": 32, "cols": 32, "self_collision": True, "kernel": kernel})
    for _ in range(30):
        scene.advance()
    c = scene.cloth
    d = c.contact.self_distance
    before = close_ij(c, d, "grid")[2]
    c.x[0, 3, 3] = 1e20
    with np.errstate(over="ignore"):        # (1e20 squared overflows float32: inf, not close)
        if kernel == "numpy":
            i, j, tests = close_ij(c, d, "grid")
        else:
            i, j, tests = self_compiled.find_pairs(*c.x.reshape(2, -1), d, joined_table(c),
                                                   self_compiled.Buffers(c.rows * c.cols))
        bi, bj, _ = close_ij(c, d, "all_pairs")
    assert pair_set(i, j) == pair_set(bi, bj) and len(i) == len(bi)
    assert tests <= 2 * before, (tests, before)           # (all pairs: 523,776)
    with np.errstate(all="ignore"):
        scene.advance()                                   # (its rods drag a few more far)


def test_the_grids_work_arrays_are_given_back_once_a_crowd_has_spread_out():
    """A crowd (1,500 points within a few px: a million candidates) grows the work arrays to
    tens of MB; the next search of a spread-out cloth hands them back (a cloth that was crushed
    once does not keep them for the rest of the run)."""
    scratch = Scratch()
    crowd = np.random.default_rng(0).normal(0, 2, (2, 1500)).astype(np.float32)
    assert fine_pairs(crowd[0], crowd[1], 6.4, scratch)[2] > 1_000_000
    assert sum(a.nbytes for a in scratch.arrays.values()) > 20e6
    grid = (np.stack(np.meshgrid(np.arange(40.0), np.arange(40.0))).reshape(2, -1) * 8)
    fine_pairs(*grid.astype(np.float32), 6.4, scratch)
    assert sum(a.nbytes for a in scratch.arrays.values()) < 5e6


needs_numba = pytest.mark.skipif(not rods_compiled.available(), reason="numba not installed")


@needs_numba
def test_the_compiled_self_collision_finds_the_same_pairs_and_moves_the_same():
    """kernel=numba: the very pairs of the NumPy grid (the same grid: fine_grid), the same
    positions after the pass (to float32 rounding), with every particle free and with some
    pinned or grabbed (their weights read pair by pair), and the HUD names it."""
    from app.physics import self_compiled
    from app.physics.cloth_contact import close_ij, joined_table
    for seed, sets, pinned in ((0, {"shear"}, 0), (1, {"shear", "bending"}, 0),
                               (2, {"shear"}, 40)):
        a, b = crumpled_cloth(seed), crumpled_cloth(seed)
        for c in (a, b):
            c.set_effects(sets | {"self_collision"})
            c.contact.self_distance = 6.4
            if pinned:                          # some pinned (w 0), one grabbed (heavier)
                w = c.w.reshape(-1)
                w[np.random.default_rng(seed).choice(w.size, pinned, replace=False)] = 0.0
                w[7] = 0.25
        i, j, tests = close_ij(a, 6.4, "grid")
        ci, cj, ctests = self_compiled.find_pairs(*b.x.reshape(2, -1), 6.4, joined_table(b),
                                                  self_compiled.Buffers(b.x[0].size))
        assert pair_set(i, j) == pair_set(ci, cj) and len(ci) == len(i) > 1000
        assert ctests == tests
        b.kernel = "numba"
        self_collide(a, 1 / 60)
        self_collide(b, 1 / 60)
        assert a.contact.self_pairs == b.contact.self_pairs == len(i)
        moved = np.abs(a.x - crumpled_cloth(seed).x).max()
        assert moved > 0.5 and np.abs(a.x - b.x).max() < 1e-3
    scene = ClothScene({"rows": 8, "cols": 8, "kernel": "numba", "self_collision": True})
    scene.advance()
    assert "numba kernel (rods, self-collision)" in scene.hud_lines()[0]


@needs_numba
def test_the_compiled_search_finds_exactly_the_pairs_all_pairs_finds():
    """Random clouds of every kind (spread, one crowd, every point at one place, far from the
    origin, on a lattice of the cut-off, flat), sizes, cut-offs, precisions and rod tables,
    with pair arrays too short at first: the compiled search's pairs are all pairs' closer
    than the cut-off less the joined ones, each once (seeded; the seed is in the message)."""
    from app.physics import self_compiled
    rng = np.random.default_rng(2611)
    for case in range(120):
        rows, cols = (int(v) for v in rng.choice([1, 2, 3, 7, 16], 2))
        n = rows * cols
        cutoff = float(rng.choice([0.01, 1.0, 6.4, 50.0]) * rng.uniform(0.5, 2))
        kind = case % 6
        x = [rng.uniform(0, 100, (n, 2)), rng.normal(0, cutoff, (n, 2)),
             np.repeat(rng.uniform(0, 10, (1, 2)), n, 0), rng.uniform(0, 1e4, (n, 2)) + 1e5,
             np.round(rng.uniform(0, 50, (n, 2)) / cutoff) * cutoff,
             rng.uniform(-1e3, 1e3, (n, 2)) * (1, 1e-3)][kind]
        x = x.astype(np.float32 if case % 2 else np.float64)
        offsets = {o for o in ((0, 1), (1, 0), (1, 1), (0, 2), (2, 0)) if rng.random() < 0.5}
        offsets = {(dr, dc) for dr, dc in offsets if dr < rows and dc < cols}
        w = 2 * cols                                   # cloth_contact.joined_table's numbering
        reach = (rows - 1) * w + cols - 1
        table = np.zeros(2 * reach + 1, bool)
        for dr, dc in offsets:
            for sr, sc in itertools.product((1, -1), (1, -1)):
                table[reach + sr * dr * w + sc * dc] = True
        row, col = np.divmod(np.arange(n), cols)
        buf = self_compiled.Buffers(n)
        buf.i, buf.j = buf.i[:case % 3], buf.j[:case % 3]        # grown as the search needs
        i, j, tests = self_compiled.find_pairs(
            np.ascontiguousarray(x[:, 0]), np.ascontiguousarray(x[:, 1]), cutoff,
            (row * w + col + reach, row * w + col, table), buf)
        bi, bj, _ = all_pairs(x, cutoff)
        keep = [(abs(int(row[p] - row[q])), abs(int(col[p] - col[q]))) not in offsets
                for p, q in zip(bi, bj)]
        expected = pair_set(bi[keep], bj[keep]) if len(bi) else set()
        assert pair_set(i, j) == expected and len(i) == len(expected), (2611, case)
        assert np.all(i != j) and tests >= len(i), (2611, case)


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_self_collision_on_a_cloth_gone_non_finite_leaves_it_to_the_runner(kernel):
    """A NaN or an inf in the cloth: self-collision finds no pair (before, the grid's box made
    a ValueError that ended the step); the scene reports the state non-finite."""
    if kernel == "numba" and not rods_compiled.available():
        pytest.skip("numba not installed")
    for bad in (np.nan, np.inf):
        scene = ClothScene({"rows": 8, "cols": 8, "self_collision": True, "kernel": kernel})
        scene.advance()
        scene.cloth.x[0, 3, 3] = bad
        with np.errstate(invalid="ignore", over="ignore"):
            scene.advance()
        assert not scene.is_finite()


def test_the_benchs_hanging_state_is_one_a_drag_leaves():
    """bench cloth times collisions on a hanging cloth whose ball and box were dragged up into
    it 2 px a step (app/bench/cloth_contact.py): no rod is stretched past MAX_STRETCH (put there
    at once, one was 23 x its rest length, a particle on the wrong side), nothing is inside an
    obstacle and nothing tunnelled; the obstacles reached their places."""
    from app.bench import cloth_contact as bench
    scene = bench.timed_state("hanging", 10)
    assert bench.longest_rod(scene) <= bench.MAX_STRETCH
    m = scene.metrics()
    assert m["penetration_max"] == 0.0 and m["tunneled"] == 0 and m["contacts"] > 300
    for ob, target in zip(scene.obstacles, bench._targets(scene)):
        assert ob.center == pytest.approx(target)
