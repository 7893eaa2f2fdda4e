"""The particle dance: both neighbour methods find the same pairs and forces, the pair forces keep
momentum, drag takes energy out, effects that are off do nothing, bad input is refused."""

import json
import math

import numpy as np
import pygame
import pytest

import app.physics.neighbours as nb
import app.physics.particle_dance as pd
from app.__main__ import main
from app.draw.dance_draw import COLORS, DRAWERS
from app.draw.view import View
from app.physics.neighbours import all_pairs, grid_pairs, grid_shape
from app.physics.particle_dance import PairForce, PairRule, reflect_into_box, rule_matrix
from app.physics.particles import ParticleSystem
from app.scene import InputEvent, ParamError
from scenes.particle_dance import ParticleDanceScene

BOX = (960.0, 720.0)


def scene(**settings) -> ParticleDanceScene:
    return ParticleDanceScene(settings)


def run(s: ParticleDanceScene, steps: int) -> ParticleDanceScene:
    for _ in range(steps):
        s.advance()
    return s


def tricky_state(n: int, cutoff: float, seed: int) -> np.ndarray:
    """Random positions plus particles exactly on cell borders, in corners, on the box's edges,
    and pairs exactly at the cut-off (along an axis and along a 3-4-5 diagonal)."""
    rng = np.random.default_rng(seed)
    x = rng.uniform(0.0, 1.0, (n, 2)) * BOX
    nx, ny = grid_shape(BOX, cutoff)
    cw, ch = BOX[0] / nx, BOX[1] / ny
    R = cutoff
    special = [(cw, ch), (2 * cw, ch), (cw, 2 * ch), (0.0, 0.0), (BOX[0], BOX[1]), (BOX[0], 0.0),
               (3 * cw, 5 * ch), (3 * cw + R, 5 * ch),                    # exactly R apart
               (6 * cw, 2 * ch), (6 * cw + 0.6 * R, 2 * ch + 0.8 * R),    # 3-4-5: R apart
               (7 * cw - 1e-9, 3 * ch), (7 * cw, 3 * ch + R - 1e-9)]      # just inside R
    x[:len(special)] = special
    return x


def forces(x: np.ndarray, method: str, cutoff: float, species: np.ndarray) -> tuple:
    rule = PairRule(rule_matrix("random", 3, np.random.default_rng(5)), cutoff, 300.0, 1000.0)
    force = PairForce(rule, species, BOX, method)
    ps = ParticleSystem(x, np.zeros_like(x), 1.0, [force])
    return ps.force(ps.x, ps.v).copy(), force


def crowd_state(n: int, cutoff: float, seed: int, radius: float) -> np.ndarray:
    """The tricky state with most particles gathered into a disk of `radius` around a cell
    corner (radius 0: every one of them exactly at that point), the rest spread out."""
    x = tricky_state(n, cutoff, seed)
    rng = np.random.default_rng(seed + 10)
    nx, ny = grid_shape(BOX, cutoff)
    corner = np.array([5 * BOX[0] / nx, 4 * BOX[1] / ny])
    r = radius * np.sqrt(rng.uniform(0.0, 1.0, n - 100))
    a = rng.uniform(0.0, 2 * np.pi, n - 100)
    x[100:] = corner + np.column_stack((r * np.cos(a), r * np.sin(a)))
    return x


def outside_state(n: int, cutoff: float, seed: int) -> np.ndarray:
    """Walls off: a third of the particles beyond the box's edges (clamped into border cells)."""
    x = tricky_state(n, cutoff, seed)
    x[::3] = np.random.default_rng(seed).uniform(-300.0, 1300.0, (len(x[::3]), 2))
    return x


STATES = {"spread": lambda n, R, seed: tricky_state(n, R, seed),
          "crowd": lambda n, R, seed: crowd_state(n, R, seed, 1.5 * R),
          "one point": lambda n, R, seed: crowd_state(n, R, seed, 0.0),
          "outside the box": outside_state}


def same_pairs(a_i, a_j, g_i, g_j) -> bool:
    """The two methods found the same unordered pairs, each once."""
    pairs = lambda i, j: set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))
    found = pairs(g_i, g_j)
    return pairs(a_i, a_j) == found and len(found) == len(g_i) and (g_i != g_j).all()


@pytest.mark.parametrize("cutoff", [40.0, 37.0, 10.0, 80.0])
@pytest.mark.parametrize("seed", [0, 1])
def test_all_pairs_and_grid_give_the_same_pairs_and_forces(cutoff, seed):
    x = tricky_state(700, cutoff, seed)
    species = np.random.default_rng(seed).integers(0, 3, len(x))
    a_i, a_j, a_tests = all_pairs(x, cutoff)
    g_i, g_j, g_tests = grid_pairs(x, cutoff, BOX)
    pairs = lambda i, j: set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))
    assert same_pairs(a_i, a_j, g_i, g_j)
    for p, q in ((6, 7), (8, 9), (10, 11)):       # at R (up to rounding), just inside R
        d = x[q] - x[p]
        assert ((p, q) in pairs(a_i, a_j)) == (d @ d < cutoff * cutoff)
    assert (10, 11) in pairs(a_i, a_j)
    if cutoff == 40.0:                             # cells exactly 40 px: this pair is exactly R apart
        assert (6, 7) not in pairs(a_i, a_j) and np.hypot(*(x[7] - x[6])) == cutoff
    assert a_tests == 700 * 699 // 2 and g_tests < a_tests
    f_all, _ = forces(x, "all_pairs", cutoff, species)
    f_grid, _ = forces(x, "grid", cutoff, species)
    scale = np.abs(f_all).max()
    assert scale > 0
    np.testing.assert_allclose(f_grid, f_all, rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("state", ["crowd", "one point", "outside the box"])
@pytest.mark.parametrize("cutoff", [40.0, 23.0])
def test_the_methods_agree_in_crowds_and_outside_the_box(state, cutoff):
    """Crowded (hundreds per cell: the grid's candidates come in many blocks), everyone at one
    point (r = 0: no NaN) and beyond the walls: the same pairs, the same forces, and the grid
    never tests more pairs than all pairs."""
    n = 600
    x = STATES[state](n, cutoff, 3)
    species = np.random.default_rng(3).integers(0, 3, n)
    a_i, a_j, a_tests = all_pairs(x, cutoff)
    g_i, g_j, g_tests = grid_pairs(x, cutoff, BOX)
    assert same_pairs(a_i, a_j, g_i, g_j)
    assert g_tests <= a_tests == n * (n - 1) // 2
    if state == "one point":                       # the 500 at the point: every pair of them
        assert len(g_i) >= (n - 100) * (n - 101) // 2
    assert len(g_i) > 0
    if state == "crowd":                           # more candidates than one block holds
        assert g_tests > 4 * nb.GRID_BLOCK
    f_all, _ = forces(x, "all_pairs", cutoff, species)
    f_grid, force = forces(x, "grid", cutoff, species)
    assert np.isfinite(f_grid).all() and force.tests == g_tests and force.pairs == len(g_i)
    scale = np.abs(f_all).max()
    assert scale > 0
    np.testing.assert_allclose(f_grid, f_all, rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("method", ["all_pairs", "grid"])
def test_pair_blocks_hand_out_each_pair_once_with_its_separation(method):
    x = crowd_state(500, 40.0, 2, 60.0)
    blocks = list(nb.all_pair_blocks(x, 40.0) if method == "all_pairs"
                  else nb.grid_pair_blocks(x, 40.0, BOX))
    assert len(blocks) > 1                         # the crowd needs several blocks
    i = np.concatenate([b.i for b in blocks])
    j = np.concatenate([b.j for b in blocks])
    assert len(set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))) == len(i)
    for b in blocks:                               # d = x_j - x_i exactly as the force needs it
        np.testing.assert_array_equal(b.dx, x[b.j, 0] - x[b.i, 0])
        np.testing.assert_array_equal(b.dy, x[b.j, 1] - x[b.i, 1])
        np.testing.assert_array_equal(b.r2, b.dx * b.dx + b.dy * b.dy)
        assert (b.r2 < 40.0 * 40.0).all()


def test_the_grid_tests_far_fewer_pairs_at_large_n():
    s = run(scene(particles=3000), 3)
    grid = s.metrics()["pair_tests"]
    s.set("neighbour_method", "all_pairs")
    run(s, 1)
    assert s.metrics()["pair_tests"] == 3000 * 2999 // 2
    assert grid < s.metrics()["pair_tests"] / 30


def test_pair_forces_are_equal_and_opposite_and_keep_momentum():
    x = tricky_state(500, 40.0, 3)
    f, force = forces(x, "grid", 40.0, np.random.default_rng(3).integers(0, 3, 500))
    assert force.pairs > 100
    assert np.abs(f.sum(axis=0)).max() < 1e-10 * np.abs(f).sum()
    s = scene(walls=False, drag=False)               # pair forces only: momentum stays put
    p0 = s.dance.momentum().copy()
    run(s, 120)
    assert s.dance.pair_force.pairs > 0
    np.testing.assert_allclose(s.dance.momentum(), p0, atol=1e-9 * np.abs(s.dance.ps.v).sum())


def test_force_is_the_slope_of_the_potential_and_energy_holds_at_a_small_step():
    rule = PairRule(np.array([[0.7]]), 40.0, 300.0, 1000.0)
    r = np.linspace(0.5, 45.0, 500)
    a = np.full_like(r, 0.7)
    e = 1e-6
    slope = (rule.potential(r + e, a) - rule.potential(r - e, a)) / (2 * e)
    np.testing.assert_allclose(slope, rule.magnitude(r, a), atol=1e-5)
    assert (rule.magnitude(r[r >= 40.0], a[r >= 40.0]) == 0).all()
    # the module docstring's F(r), piece by piece, for either sign of A (b = 12, R = 40)
    for like in (0.7, -0.4):
        a = np.full_like(r, like)
        docstring = np.where(r < 12.0, 1000.0 * (r / 12.0 - 1.0),
                             np.where(r < 40.0, like * 300.0 * (1 - np.abs(2 * r - 52.0) / 28.0), 0.0))
        np.testing.assert_allclose(rule.magnitude(r, a), docstring, rtol=1e-12, atol=1e-9)

    def drift(hertz):                                # relative change of KE + PE over 2 s
        d = scene(drag=False, hertz=hertz).dance
        e0 = d.kinetic_energy() + d.potential_energy()
        for _ in range(2 * hertz):
            d.step(1.0 / hertz)
        return abs(d.kinetic_energy() + d.potential_energy() - e0) / d.kinetic_energy()

    small, large = drift(240), drift(60)
    assert small < 0.02 and large > 2 * small        # the kinks' energy error shrinks with h


def test_drag_takes_out_kinetic_energy():
    s = scene(interaction=False)                     # drag and walls only: v' = (1 - k h) v
    ke0 = s.dance.kinetic_energy()
    run(s, 60)
    assert s.dance.kinetic_energy() == pytest.approx(ke0 * (1 - 1.0 / 60) ** 120, rel=1e-9)
    s = run(scene(), 60)                             # with the pair forces: the dance settles
    ke1 = s.dance.kinetic_energy()
    run(s, 480)
    assert s.dance.kinetic_energy() < ke1 / 20


def test_effects_that_are_off_do_no_work(monkeypatch):
    calls = {"find_pairs": 0, "walls": 0, "drag": 0}
    find, reflect = pd.PairForce.pair_blocks, pd.reflect_into_box

    def counting_find(*args):
        calls["find_pairs"] += 1
        return find(*args)

    def counting_reflect(*args):
        calls["walls"] += 1
        return reflect(*args)

    monkeypatch.setattr(pd.PairForce, "pair_blocks", counting_find)
    monkeypatch.setattr(pd, "reflect_into_box", counting_reflect)
    s = scene(interaction=False, drag=False, walls=False)
    drag_accumulate = s.dance.drag.accumulate

    def counting_drag(*args):
        calls["drag"] += 1
        return drag_accumulate(*args)

    s.dance.drag.accumulate = counting_drag
    x0 = s.dance.ps.x.copy()
    run(s, 10)
    assert calls == {"find_pairs": 0, "walls": 0, "drag": 0}
    assert s.dance.ps.forces == [] and s.metrics()["pair_tests"] == 0 and s.effect_costs() == {}
    np.testing.assert_allclose(s.dance.ps.x, x0 + 10 / 60 * s.dance.ps.v)   # free flight
    for name in ("interaction", "drag", "walls"):
        s.set(name, True)
    run(s, 10)
    assert calls == {"find_pairs": 10, "walls": 10, "drag": 10}
    assert set(s.effect_costs()) == {"interaction", "drag", "walls"}


def test_lmb_pulls_and_rmb_pushes_the_particles_near_the_cursor():
    centre = (480.0, 360.0)

    def mean_distance_after(button):
        s = scene(interaction=False, seed=4)
        near = np.hypot(*(s.dance.ps.x - centre).T) < 100.0
        s.handle_event(InputEvent("mouse_down", centre, button))
        run(s, 30)
        d = np.hypot(*(s.dance.ps.x[near] - centre).T).mean()
        s.handle_event(InputEvent("mouse_up", centre, button))
        assert s.dance.mouse is None and len(s.dance.ps.forces) == 1        # drag only again
        return d

    s = scene(interaction=False, seed=4)
    start = np.hypot(*(s.dance.ps.x[np.hypot(*(s.dance.ps.x - centre).T) < 100.0] - centre).T).mean()
    assert mean_distance_after(1) < 0.7 * start
    assert mean_distance_after(3) > 1.3 * start
    s = scene()                                      # the pull follows the mouse
    s.handle_event(InputEvent("mouse_down", centre, 1))
    s.handle_event(InputEvent("mouse_move", (100.0, 100.0)))
    assert tuple(s.dance.mouse.point) == (100.0, 100.0)
    s.handle_event(InputEvent("mouse_move", (float("nan"), 1e300)))     # no NaN reaches the force
    assert np.isfinite(s.dance.mouse.point).all()
    run(s, 5)
    assert s.is_finite()


def test_walls_fold_any_position_back_into_the_box():
    x = np.array([[-2500.0, 10.0], [970.0, 730.0], [5000.0, -1.0], [480.0, 360.0]])
    v = np.ones_like(x)
    reflect_into_box(x, v, BOX)
    assert ((x >= 0) & (x <= BOX)).all()
    # -2500: mirrored at 0, 960, 0 (3 times); 5000: 5 times; 970, 730 and -1: once
    np.testing.assert_allclose(x, [[580.0, 10.0], [950.0, 710.0], [760.0, 1.0], [480.0, 360.0]])
    np.testing.assert_array_equal(v, [[-1, 1], [-1, -1], [-1, -1], [1, 1]])   # odd: flipped


def test_same_seed_same_hash_and_the_methods_switch_live():
    events = [InputEvent("mouse_down", (300.0, 300.0), 1), InputEvent("mouse_move", (400.0, 300.0))]

    def hashed(seed, method="grid"):
        s = scene(seed=seed, neighbour_method=method)
        run(s, 20)
        for e in events:
            s.handle_event(e)
        return run(s, 20).state_hash()

    assert hashed(1) == hashed(1)
    assert hashed(1) != hashed(2)
    s = run(scene(), 10)
    assert not s.set("neighbour_method", "all_pairs")          # live, no rebuild
    run(s, 1)
    assert s.metrics()["neighbour_method"] == "all_pairs" and s.steps == 11


def test_hud_and_legend_draw_and_say_what_the_method_costs():
    s = run(scene(species=6), 5)
    s.handle_event(InputEvent("mouse_down", (200.0, 200.0), 3))
    surface = pygame.Surface(s.world_size)
    s.draw(surface, View())
    key = s.color_key                                     # the rule matrix, in the HUD
    matrix = s.dance.pair_force.rule.matrix
    assert len(key) == 6 and [c for c, _ in key] == COLORS[:6]
    for (_, text), row in zip(key, matrix):               # every non-zero entry, with its sign
        assert sum(f"{a:+.1f}" in text for a in row if a != 0) == np.count_nonzero(row)
    text = "\n".join(s.hud_lines())
    assert "grid:" in text and "pair tests/step" in text and "ms/step" in text
    assert "mouse" in s.effect_costs()
    s.set("interaction", False)
    assert s.color_key == ()


@pytest.mark.parametrize("key,value", [("neighbour_method", "kd_tree"), ("particles", 1),
                                       ("particles", 5001), ("cutoff", float("nan")),
                                       ("species", 7), ("rules", "chaos"), ("drag_coef", -1)])
def test_bad_values_are_refused(key, value):
    with pytest.raises(ParamError):
        ParticleDanceScene({key: value})


def test_combinations_that_would_blow_up_or_take_seconds_are_refused():
    with pytest.raises(ParamError, match="drag_coef x h"):
        ParticleDanceScene({"drag_coef": 20.0, "hertz": 10, "repulsion": 0, "attraction": 0})
    with pytest.raises(ParamError, match="omega h"):
        ParticleDanceScene({"hertz": 5})
    with pytest.raises(ParamError, match="neighbour_method=grid"):
        ParticleDanceScene.resolve({"particles": 5000, "neighbour_method": "all_pairs",
                                    "substeps": 20})
    s = scene(particles=5000)                       # fine with the grid...
    with pytest.raises(ParamError):
        s.set("substeps", 20)
        s.set("neighbour_method", "all_pairs")     # ...not all pairs at 20 substeps
    for t in ParticleDanceScene.tries:              # every Try card is accepted
        ParticleDanceScene.resolve(t.settings)


@pytest.mark.parametrize("args,fragment", [
    (["--set", "neighbour_method=octree"], "all_pairs, grid"),
    (["--set", "particles=0"], "2 to 5000"),
    (["--set", "particles=9000"], "2 to 5000"),
    (["--set", "attraction=nan"], "finite"),
])
def test_bad_input_on_the_command_line_is_one_line_and_exit_2(capsys, args, fragment):
    assert main(["--headless", "--scene", "particle_dance", "--steps", "2", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err and "Traceback" not in err


def test_bench_particles_quick_has_the_scaling_table(capsys, tmp_path, png_charts):
    assert main(["bench", "particles", "--quick", "--json", "--out", str(tmp_path)]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = out["scaling"]
    assert {(r["n"], r["method"]) for r in rows} == {(n, m) for n in (100, 300, 1000)
                                                     for m in ("all_pairs", "grid")}
    for r in rows:
        assert set(r) >= {"n", "method", "step_ms", "pair_tests"} and r["step_ms"] > 0
        if r["method"] == "all_pairs":
            assert r["pair_tests"] == r["n"] * (r["n"] - 1) // 2
    assert "grid_wins_from_n" in out and out["frame"]["draw_ms"] > 0
    assert (tmp_path / "particles.png").exists()
    assert all(math.isfinite(r["step_ms"]) for r in rows)
    one_point = out["crowds"][-1]                  # every particle at one point: all pairs
    assert one_point["radius"] == 2.0 and one_point["grid_tests_share"] == 1.0
    assert one_point["pairs_share"] == 1.0 and one_point["grid_ms"] > 0
    assert set(out["drawing"]["ms"]) == set(DRAWERS) and out["drawing"]["used"] in DRAWERS
    assert out["drawing"]["n"] == 5000 and out["drawing"]["screen"] == [1280, 800]
    for b in out["budget"]:                        # the costliest settings the scene accepts
        assert b["estimate_ms"] <= 100.0 and b["step_ms"] > 0
    targets = {t["target"]: t for t in out["targets"]}
    assert len(targets) == 6 and all((t["reason"] is None) == t["met"] for t in targets.values())


def test_pair_tests_do_not_exist_before_the_first_search():
    s = scene()
    assert s.metrics()["pair_tests"] is None and s.metrics()["pairs_interacting"] is None
    run(s, 1)
    assert s.metrics()["pair_tests"] > 0
    assert scene(interaction=False).metrics()["pair_tests"] == 0      # off: no tests, a count


def test_every_way_of_drawing_the_dots_paints_the_same_pixels_inside_the_clip():
    """The sprites (colour key or alpha) and the NumPy stamp draw exactly what one
    pygame.draw.circle per particle draws, and none of them paints outside the clip rectangle
    (the window clips the world to its area; far-off particles must not crash)."""
    from app.draw import dance_draw

    rng = np.random.default_rng(4)
    grid = np.stack(np.meshgrid(np.arange(12, 300, 13), np.arange(10, 200, 13)), -1).reshape(-1, 2)
    x = grid[rng.permutation(len(grid))][:300].astype(float)      # integers, never overlapping
    x[:3] = [[1e9, 5.0], [-1e7, 1e12], [np.nan, 4.0]]            # off any screen
    species = rng.integers(0, 6, len(x))
    pictures = {}
    for name, draw in dance_draw.DRAWERS.items():
        surface = pygame.Surface((320, 220), 0, 32)
        surface.fill((22, 24, 30))
        surface.set_clip(pygame.Rect(40, 30, 200, 150))
        draw(surface, View(), x, species, 6, 4.0)
        surface.set_clip(None)
        pictures[name] = pygame.surfarray.array2d(surface)
    reference = pictures.pop("pygame.draw.circle per particle")
    background = pygame.Surface((1, 1), 0, 32).map_rgb((22, 24, 30))
    outside = np.ones(reference.shape, bool)
    outside[40:240, 30:180] = False
    assert (reference[outside] == background).all() and (reference != background).sum() > 3000
    for name, picture in pictures.items():
        assert (picture == reference).all(), name
    assert dance_draw.USED in dance_draw.DRAWERS


def test_the_step_budget_counts_substeps_and_keeps_a_step_near_the_windows_100_ms():
    """The window waits for a whole step: settings estimated over 0.1 s a step are refused,
    substeps included; the lecture's comparison (all pairs at 5000, one substep) is kept."""
    resolve = ParticleDanceScene.resolve
    resolve({"particles": 5000, "neighbour_method": "all_pairs"})
    resolve({"particles": 5000, "neighbour_method": "grid", "substeps": 8})
    for settings in ({"particles": 5000, "neighbour_method": "all_pairs", "substeps": 2},
                     {"particles": 5000, "neighbour_method": "grid", "substeps": 30},
                     {"particles": 5000, "cutoff": 80.0, "substeps": 5}):
        with pytest.raises(ParamError, match=r"ms per step; accepted: at most 100 ms"):
            resolve(settings)
    for substeps in range(1, 51):                  # every accepted setting: estimated <= 0.1 s
        for method in ("grid", "all_pairs"):
            values = {"particles": 5000, "neighbour_method": method, "substeps": substeps}
            try:
                p, _ = resolve(values)
            except ParamError:
                continue
            assert ParticleDanceScene.step_seconds(p) <= 0.1


def test_the_hud_says_in_words_when_physics_cannot_keep_real_time():
    fast = run(scene(particles=100), 5)
    assert not any("real time" in str(getattr(line, "text", line)) for line in fast.hud_lines())
    slow = run(scene(particles=3000, neighbour_method="all_pairs", hertz=1000), 3)
    text = [str(getattr(line, "text", line)) for line in slow.hud_lines()]
    assert any(t.startswith("too slow for real time:") and "per 1.0 ms step" in t for t in text)
    assert not any("crowded" in t for t in text)
    crowd = scene(particles=600, hertz=1000, walls=False)    # everyone at one point
    crowd.dance.ps.x[:] = (480.0, 360.0)
    run(crowd, 2)
    text = " ".join(str(getattr(line, "text", line)) for line in crowd.hud_lines())
    assert "crowded: 599 neighbours within R each" in text and "(100% of all 179,700)" in text


def test_the_grids_two_runs_are_its_own_cell_and_the_half_stencil():
    """The candidates of `sort_into_cells` (the rest of the own cell and the cell to its right,
    then the three cells below) are exactly the pairs in the same cell or in cells one
    HALF_STENCIL step apart, each once: counted here pair by pair."""
    x = outside_state(300, 40.0, 5)
    x[:120] = crowd_state(120, 40.0, 5, 50.0)[:120]              # some crowded cells too
    nx, ny = grid_shape(BOX, 40.0)
    cx = np.clip(np.floor(x[:, 0] * nx / BOX[0]), 0, nx - 1).astype(int)
    cy = np.clip(np.floor(x[:, 1] * ny / BOX[1]), 0, ny - 1).astype(int)
    steps = set(nb.HALF_STENCIL) | {(-a, -b) for a, b in nb.HALF_STENCIL} | {(0, 0)}
    expected = sum((cx[q] - cx[p], cy[q] - cy[p]) in steps
                   for p in range(len(x)) for q in range(p + 1, len(x)))
    cells = nb.sort_into_cells(x, 40.0, BOX)
    assert cells.tests == expected
    assert grid_pairs(x, 40.0, BOX)[2] == expected
