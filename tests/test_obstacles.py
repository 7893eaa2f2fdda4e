"""Obstacles (app/physics/obstacles.py) against brute-force geometry: signed distances and normals
on random points, projection leaves nothing inside, friction never reverses the sliding, paths
through thin obstacles are found."""

import math

import numpy as np
import pytest

from app.physics.obstacles import (Box, Circle, Contacts, HalfPlane, Segment, coulomb_friction,
                                   floor, nearest, penetration_max, project, verlet_friction)
from app.physics.tunnelling import path_min_distance, swept

RNG_SEED = 24


def shapes():
    return [Circle(300.0, 200.0, 60.0),
            Box(150.0, 320.0, 80.0, 25.0, 0.4),
            Box(420.0, 380.0, 30.0, 50.0, -1.1),
            floor(500.0),
            HalfPlane(50.0, 50.0, 1.0, 2.0),
            Segment(100.0, 120.0, 260.0, 90.0, 3.0),
            Segment(400.0, 100.0, 400.0, 100.0, 10.0)]          # a degenerate one: a dot


def boundary(ob, n=20000):
    """Points densely on the obstacle's surface, from its definition (not from signed_distance),
    and an independent inside test."""
    s = np.linspace(0, 2 * math.pi, n, endpoint=False)
    if isinstance(ob, Circle):
        pts = np.stack([ob.cx + ob.radius * np.cos(s), ob.cy + ob.radius * np.sin(s)], 1)
        inside = lambda p: np.hypot(p[:, 0] - ob.cx, p[:, 1] - ob.cy) < ob.radius
    elif isinstance(ob, Box):
        c = ob.corners()
        t = np.linspace(0, 1, n // 4, endpoint=False)[:, None]
        pts = np.concatenate([c[k] + t * (c[(k + 1) % 4] - c[k]) for k in range(4)])
        ca, sa = math.cos(ob.angle), math.sin(ob.angle)

        def inside(p):
            dx, dy = p[:, 0] - ob.cx, p[:, 1] - ob.cy
            return (np.abs(dx * ca + dy * sa) < ob.half_w) & (np.abs(-dx * sa + dy * ca) < ob.half_h)
    elif isinstance(ob, HalfPlane):
        return None, None
    else:                       # a capsule: its surface is `thickness` px from the core segment
        return None, None
    return pts, inside


def random_points(n=400, seed=RNG_SEED):
    return np.random.default_rng(seed).uniform([-50, -50], [650, 650], (n, 2))


@pytest.mark.parametrize("k", range(7))
def test_signed_distance_matches_brute_force_geometry(k):
    ob = shapes()[k]
    p = random_points()
    d, n = ob.signed_distance(p)
    assert d.shape == (len(p),) and n.shape == (len(p), 2)
    assert np.allclose(np.hypot(n[:, 0], n[:, 1]), 1.0)
    if isinstance(ob, HalfPlane):
        nx, ny = ob.nx, ob.ny
        assert np.allclose(d, (p[:, 0] - ob.px) * nx + (p[:, 1] - ob.py) * ny)
        return
    if isinstance(ob, Segment):     # distance to the core (sampled every < 0.1 px) - thickness
        core = np.stack([np.linspace(ob.ax, ob.bx, 2000), np.linspace(ob.ay, ob.by, 2000)], 1)
        brute = np.sqrt(((p[:, None, :] - core[None]) ** 2).sum(-1)).min(1) - ob.thickness
    else:
        surface, inside = boundary(ob)
        brute = np.sqrt(((p[:, None, :] - surface[None, ::4, :]) ** 2).sum(-1)).min(1)
        brute = np.where(inside(p), -brute, brute)
    assert np.max(np.abs(d - brute)) < 0.5          # the surface sampled every < 0.5 px
    # the normal is the shortest way to the surface: p - d n lies on it
    foot = p - d[:, None] * n
    assert np.max(np.abs(ob.signed_distance(foot)[0])) < 1e-6


def test_nearest_picks_the_smallest_distance_and_penetration_is_the_deepest():
    obs = shapes()[:3]
    p = random_points(300, seed=3)
    d, n, idx = nearest(obs, p)
    each = np.stack([ob.signed_distance(p)[0] for ob in obs])
    assert np.allclose(d, each.min(0)) and np.array_equal(idx, each.argmin(0))
    assert penetration_max(obs, p) == pytest.approx(max(0.0, -each.min()))
    assert penetration_max([], p) == 0.0
    assert penetration_max(obs, p, mask=np.zeros(len(p), bool)) == 0.0


@pytest.mark.parametrize("margin", [0.0, 1.5])
def test_projection_leaves_no_particle_inside(margin):
    obs = [Circle(300.0, 200.0, 60.0), Box(150.0, 380.0, 80.0, 25.0, 0.4), floor(560.0),
           Segment(420.0, 420.0, 600.0, 350.0, 4.0)]           # none overlaps another
    p = random_points(3000, seed=7)
    before = p.copy()
    movable = np.ones(len(p), bool)
    movable[::50] = False
    c = project(obs, p, margin=margin, movable=movable)
    d = nearest(obs, p)[0]
    assert np.all(d[movable] >= margin - 1e-9)
    assert np.array_equal(p[~movable], before[~movable])        # pinned ones stay
    moved = np.hypot(*(p - before).T)
    assert np.allclose(moved[c.mask], c.depth[c.mask]) and np.all(moved[~c.mask] == 0)
    was = nearest(obs, before)[0]
    assert np.array_equal(c.mask, (was < margin) & movable)
    assert c.count > 100 and penetration_max(obs, p, movable) <= 1e-9


def test_projection_writes_through_a_float32_view_of_a_grid():
    x = np.random.default_rng(1).uniform(0, 400, (2, 20, 30)).astype(np.float32)
    ball = Circle(200.0, 200.0, 80.0)
    c = project([ball], x.reshape(2, -1).T)
    assert c.count > 0
    assert ball.signed_distance(x.reshape(2, -1).T)[0].min() > -1e-3   # float32 rounding


def test_friction_never_reverses_tangential_motion_and_removes_at_most_mu_depth():
    rng = np.random.default_rng(5)
    n = 2000
    theta = rng.uniform(0, 2 * math.pi, n)
    normal = np.stack([np.cos(theta), np.sin(theta)], 1)
    motion = rng.normal(0, 3, (n, 2))
    depth = rng.exponential(1.0, n)
    mask = rng.uniform(size=n) < 0.7
    for mu in (0.0, 0.3, 1.0, 5.0):
        x = rng.uniform(0, 100, (n, 2))
        x_prev = x - motion
        verlet_friction(x, x_prev, Contacts(mask, depth, normal, np.zeros(n, int)), mu)
        after = x - x_prev
        along0 = (motion * normal).sum(1)
        along1 = (after * normal).sum(1)
        t0 = motion - along0[:, None] * normal
        t1 = after - along1[:, None] * normal
        assert np.allclose(along0, along1)                       # the normal part is untouched
        assert np.allclose(after[~mask], motion[~mask])          # no contact, no friction
        dot = (t0 * t1).sum(1)
        s0, s1 = np.hypot(*t0.T), np.hypot(*t1.T)
        assert np.all(dot >= -1e-9)                              # never reversed
        assert np.all(s1 <= s0 + 1e-9)
        removed = s0 - s1
        expect = np.where(mask, np.minimum(s0, mu * depth), 0.0)
        assert np.allclose(removed, expect, atol=1e-9)


def test_friction_measures_sliding_relative_to_a_moving_obstacle():
    box = Box(0.0, 10.0, 100.0, 10.0, velocity=(120.0, 0.0))   # moving right at 120 px/s
    x = np.array([[0.0, 0.0]])
    x_prev = np.array([[0.0, 0.0]])                                # the particle at rest
    c = Contacts(np.array([True]), np.array([1.0]), np.array([[0.0, -1.0]]), np.array([0]))
    verlet_friction(x, x_prev, c, mu=10.0, obstacles=[box], h=0.01)
    assert (x - x_prev)[0, 0] == pytest.approx(1.2)     # sticks: carried along at 1.2 px/step


def test_coulomb_friction_on_velocities():
    v = np.array([[3.0, 4.0], [1.0, 0.0]])
    n = np.array([[0.0, -1.0], [0.0, -1.0]])
    dv = coulomb_friction(v, n, np.array([1.0, 1.0]), np.array([True, True]), 0.5)
    assert np.allclose(v + dv, [[2.5, 4.0], [0.5, 0.0]])


def test_paths_through_a_thin_obstacle_are_found_and_others_are_not():
    bar = Segment(0.0, 100.0, 400.0, 100.0, 2.0)
    rng = np.random.default_rng(11)
    p0 = rng.uniform([0, 0], [400, 200], (2000, 2))
    p1 = p0 + rng.normal(0, 60, (2000, 2))
    d0, d1 = bar.signed_distance(p0)[0], bar.signed_distance(p1)[0]
    ok = (d0 > 0) & (d1 > 0)
    p0, p1 = p0[ok], p1[ok]
    sw = swept([bar], p0, p1, tolerance=0.5)
    # brute force: each path sampled at 801 points (every < 0.5 px: d is off by < 0.25 px)
    t = np.linspace(0, 1, 801)
    samples = p0[:, None, :] + t[None, :, None] * (p1 - p0)[:, None, :]
    brute = bar.signed_distance(samples.reshape(-1, 2))[0].reshape(len(p0), -1).min(1)
    dmin, _ = path_min_distance(bar, p0, p1)
    assert np.all(dmin <= brute + 1e-9) and np.max(brute - dmin) < 0.25
    clear = (brute < -0.75) | (brute > -0.25)        # not within sampling of the tolerance
    assert np.array_equal(sw.mask[clear], (brute < -0.5)[clear])
    assert sw.count > 50
    assert np.all(np.abs(bar.signed_distance(sw.entry[sw.mask])[0]) < 1e-3)


def test_an_obstacle_moves_and_reports_its_centre():
    for ob in shapes():
        cx, cy = ob.center
        ob.move_to(cx + 10.0, cy - 5.0)
        assert ob.center == pytest.approx((cx + 10.0, cy - 5.0))
    with pytest.raises(ValueError):
        HalfPlane(0.0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("k", [0, 1, 2, 5])
def test_the_exact_path_tests_agree_with_the_golden_section_search(k):
    from app.physics.tunnelling import dips_below
    ob = shapes()[k]
    rng = np.random.default_rng(k)
    cx, cy = ob.center
    p0 = rng.uniform([cx - 150, cy - 150], [cx + 150, cy + 150], (3000, 2))
    p1 = p0 + rng.normal(0, 80, (3000, 2))
    dmin, _ = path_min_distance(ob, p0, p1)
    for depth in (0.5, 3.0):
        mask, t = dips_below(ob, p0, p1, depth)
        clear = np.abs(dmin + depth) > 1e-6
        assert np.array_equal(mask[clear], (dmin < -depth)[clear])
        q = p0[mask] + t[mask, None] * (p1 - p0)[mask]
        assert np.all(ob.signed_distance(q)[0] < -depth + 1e-9)      # t is a place that deep


def test_a_point_that_crossed_the_middle_of_a_thin_box_goes_back_out_the_side_it_came_from():
    top = Box(0.0, 0.0, 100.0, 5.0)                          # a table top 10 px thick
    start = np.array([[0.0, 20.0, -30.0], [-8.0, -8.0, 8.0]])     # (2, n): above, above, below
    points = np.array([[0.0, 3.0], [20.0, -1.0], [-30.0, -2.0]])  # 3 px deep (past the middle),
    c = project([top], points, 0.25, start=start)                 # 1 px, and 3 px from below
    assert points[0, 1] == pytest.approx(-5.25)              # back out on top, not beneath
    assert points[1, 1] == pytest.approx(-5.25)              # not past the middle: as before
    assert points[2, 1] == pytest.approx(5.25)               # came from below: out below
    assert c.count == 3
    plain = np.array([[0.0, 3.0]])
    project([top], plain, 0.25)                              # without start: the nearer face
    assert plain[0, 1] == pytest.approx(5.25)


@pytest.mark.parametrize("ob", shapes(), ids=lambda ob: ob.kind)
def test_entry_is_where_a_path_from_outside_first_meets_the_surface(ob):
    """Each shape's exact entry against the plain bisection on its signed distance: random
    paths from outside to inside, the same t to the bisection's 1e-9."""
    from app.physics.obstacles import Obstacle
    rng = np.random.default_rng(RNG_SEED)
    a, b = rng.uniform(-50.0, 600.0, (2, 20000, 2))
    d0 = ob.signed_distance(a)[0]
    d1 = ob.signed_distance(b)[0]
    k = (d0 >= 0) & (d1 < 0)
    assert k.sum() > 5
    a, e = a[k], (b - a)[k]
    t = ob.entry(a[:, 0], a[:, 1], e[:, 0], e[:, 1])
    assert np.allclose(t, Obstacle.entry(ob, a[:, 0], a[:, 1], e[:, 0], e[:, 1]), atol=1e-8)
    assert np.abs(ob.signed_distance(a + t[:, None] * e)[0]).max() < 1e-6 * (1 + np.abs(e).max())


@pytest.mark.parametrize("ob", [s for s in shapes() if s.kind != "half_plane"],
                         ids=lambda ob: ob.kind)
def test_no_path_shorter_than_shortest_dip_dips_the_tolerance_deep(ob):
    """shortest_dip is a bound: paths from outside to outside, just shorter than it, anywhere
    around the shape, never reach `tolerance` inside (golden-section search along each)."""
    from app.physics.tunnelling import shortest_dip
    tol = 1.0
    length = 0.999 * shortest_dip(ob, tol)
    rng = np.random.default_rng(RNG_SEED)
    x0, y0, x1, y1 = ob.bounds()
    a = rng.uniform((x0 - 5, y0 - 5), (x1 + 5, y1 + 5), (8000, 2))
    angle = rng.uniform(0, 2 * math.pi, 8000)
    b = a + length * np.column_stack((np.cos(angle), np.sin(angle)))
    out = (ob.signed_distance(a)[0] >= 0) & (ob.signed_distance(b)[0] >= 0)
    dmin, _ = path_min_distance(ob, a[out], b[out])
    assert out.sum() > 500 and dmin.min() > -tol
