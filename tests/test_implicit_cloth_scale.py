"""The implicit cloth at classroom scale (issue 19): the fixed-pattern sparse matrix, the block
Jacobi preconditioner and CG's warm start give the same step as a dense solve of the system the
springs define (to the CG tolerance), with either solver; the direct solver fills in the same
report; the step budget refuses what would freeze the window and names what would fit."""

import numpy as np
import pytest

from app.physics.linear_solve import preconditioned_cg
from app.physics.mass_spring_cost import (FRAME_BUDGET_S, cg_iterations, cloth_spacing,
                                          frame_cost, rest_omega)
from app.physics.spring_forces import block_product
from app.scene import ParamError
from scenes.mass_spring_cloth import MassSpringClothScene


def system_by_slices(ps, h):
    """Implicit Euler's A (as a product, by NumPy slices per spring family: not the sparse
    matrix the solver uses) and b = h (f0 + h K v0), component-major, at the current state."""
    x0, v0 = ps.x, ps.v
    stiff, damp = ps.blocks(x0)
    combined = {}
    for scale, blocks in ((h * h, stiff), (h, damp)):
        for fam, B in blocks:
            combined[id(fam)] = (fam, combined[id(fam)][1] + scale * B
                                 if id(fam) in combined else scale * B)
    system = list(combined.values())
    mass = ps.mass + h * ps.air_drag()

    def A(w):
        return mass * w + block_product(system, w, ps.rows, ps.cols)
    f0 = ps.force(x0, v0).T.copy()
    b = h * (f0 - h * block_product(stiff, np.ascontiguousarray(v0.T), ps.rows, ps.cols))
    return A, b


def moving_cloth(n, solver="cg", steps=12, **settings):
    """A denim n x n cloth some steps into its fall, one particle grabbed and pulled aside (a
    moving pin: one more filtered row)."""
    s = MassSpringClothScene({"material": "denim", "rows": n, "cols": n, "solver": solver,
                              **settings})
    for _ in range(steps):
        s.advance()
    c = s.cloth
    c.grab((n // 2, n - 1), tuple(c.ps.x[(n // 2) * n + n - 1] + (25.0, 10.0)))
    return s


def step_dv(scene, solver, tolerance):
    """dv of one implicit step from the scene's current state (restored after)."""
    c = scene.cloth
    snap = c.copy_state()
    c.ps.solver, c.ps.cg_tolerance = solver, tolerance
    v0 = c.ps.v.copy()
    c.step(scene.dt, "implicit_euler")
    dv, report = (c.ps.v - v0).T.copy(), c.ps.solve
    c.restore_state(snap)
    return dv, report


def test_one_implicit_step_at_32x32_is_a_dense_solve_of_the_same_system_with_either_solver():
    s = moving_cloth(32)
    ps, h = s.cloth.ps, s.dt
    ps.x = ps.x.copy()
    s.cloth._place(s.cloth.grabbed, s.cloth.grab_target)       # as step() does first
    A, b = system_by_slices(ps, h)
    n2 = b.size
    dense = np.array([A(e.reshape(b.shape)).ravel() for e in np.eye(n2)]).T
    free = np.tile(ps.free[:, 0], 2) > 0                       # component-major: x's, then y's
    exact = np.zeros(n2)
    exact[free] = np.linalg.solve(dense[np.ix_(free, free)], b.ravel()[free])
    b_norm = np.linalg.norm(b.ravel()[free])
    for solver, tolerance, close in (("direct", 1e-2, 1e-9), ("cg", 1e-10, 1e-7)):
        dv, report = step_dv(s, solver, tolerance)
        assert np.abs(dv.ravel() - exact).max() <= close * np.abs(exact).max(), solver
        assert report.converged and report.fallback is None
    # the scene's own tolerance: CG's answer leaves at most 1e-2 of |b| in the dense system
    dv, report = step_dv(s, "cg", 1e-2)
    residual = np.linalg.norm((b.ravel() - dense @ dv.ravel())[free]) / b_norm
    assert residual <= 1e-2 and residual == pytest.approx(report.residual, rel=1e-6)
    assert report.iterations > 0 and np.all(dv.ravel()[~free] == 0.0)


def test_at_64x64_both_solvers_solve_the_system_the_springs_define():
    s = moving_cloth(64, steps=3)
    ps = s.cloth.ps
    ps.x = ps.x.copy()
    s.cloth._place(s.cloth.grabbed, s.cloth.grab_target)
    A, b = system_by_slices(ps, s.dt)
    free = ps.free.T
    for solver, tolerance, most in (("cg", 1e-2, 1e-2), ("direct", 1e-2, 1e-10)):
        dv, report = step_dv(s, solver, tolerance)
        residual = np.linalg.norm((b - A(dv)) * free) / np.linalg.norm(b * free)
        assert residual <= most, (solver, residual)
        assert report.converged and np.all(dv * (1 - free) == 0.0)


def test_cg_takes_a_first_guess_only_where_it_beats_zero():
    rng = np.random.default_rng(4)
    Q, _ = np.linalg.qr(rng.normal(size=(12, 12)))
    matrix = Q @ np.diag(np.logspace(0, 3, 12)) @ Q.T
    A = lambda w: (matrix @ w.ravel()).reshape(w.shape)              # noqa: E731
    b, free = rng.normal(size=(12, 1)), np.ones((12, 1))
    exact = np.linalg.solve(matrix, b)
    cold, report = preconditioned_cg(A, b, free, tolerance=1e-8, max_iterations=200)
    assert not report.warm and report.iterations > 0 and report.converged
    warm, report = preconditioned_cg(A, b, free, tolerance=1e-8, x0=exact * (1 + 1e-12))
    assert report.warm and report.iterations == 0 and report.residual <= 1e-8
    bad, report = preconditioned_cg(A, b, free, tolerance=1e-8, max_iterations=200,
                                    x0=1e6 * exact)
    assert not report.warm and report.converged                     # it started from 0 instead
    for x in (cold, warm, bad):
        assert np.allclose(x, exact, rtol=1e-5, atol=1e-6)


def test_the_direct_solver_fills_the_same_report_and_the_hud_sets_both_costs_side_by_side():
    s = MassSpringClothScene({"material": "denim", "rows": 12, "cols": 12, "solver": "direct"})
    for _ in range(5):
        s.advance()
    m = s.metrics()
    assert m["solver"] == "direct" and m["cg_iterations"] == 0
    assert m["cg_converged"] is True and m["cg_residual"] < 1e-10 and m["cg_failures"] == 0
    report = s.cloth.ps.solve
    assert report.method == "sparse LU" and report.fill > s.cloth.ps.matrix.nonzeros
    line = next(str(x) for x in s.hud_lines() if str(x).startswith("solve:"))
    assert "direct LU" in line and "ms a step" in line
    assert any("L and U hold" in line for line in s.hud_details())
    s.set("solver", "cg")
    for _ in range(5):
        s.advance()
    line = next(str(x) for x in s.hud_lines() if str(x).startswith("solve:"))
    assert line.startswith("solve: CG") and "direct LU:" in line and "when last used" in line
    assert s.metrics()["cg_iterations"] > 0
    s.set("material", "leather")                        # another cloth: the old costs go
    assert not any("direct LU" in str(x) for x in s.hud_lines())


def test_cg_stopped_by_the_step_budget_says_so_and_takes_no_direct_solve():
    s = MassSpringClothScene({"material": "denim", "rows": 8, "cols": 8, "cg_tolerance": 1e-10})
    s.cloth.ps.budget_iterations = 2
    s.advance()
    report = s.cloth.ps.solve
    assert report.stop == "budget" and report.iterations == 2 and report.fallback is None
    assert s.metrics()["cg_converged"] is False and s.metrics()["cg_failures"] == 1
    assert "all the step's time budget holds" in s.hud_lines()[-1]


def test_a_step_over_the_budget_is_refused_in_one_line_that_names_what_would_fit():
    """The issue's case: accepted before, 2.5-5 s a step (672 CG iterations)."""
    case = {"rows": 64, "cols": 64, "substeps": 9, "tension": 1e5, "compression": 1e5,
            "shear_stiffness": 1e5, "bending_stiffness": 1e5, "mass": 0.001, "hertz": 1000,
            "cg_tolerance": 1e-10}
    with pytest.raises(ParamError) as refused:
        MassSpringClothScene(case)
    text = str(refused.value)
    assert "\n" not in text and "too slow for the window" in text and "would fit" in text
    assert "at most 100 ms a frame" in text and "CG iterations a substep" in text
    assert "at hertz 1000 a frame runs 8 steps" in text
    # the changes it names are accepted
    side = int(text.split("at most ")[-1].split("x")[0])
    values, _ = MassSpringClothScene.resolve({**case, "rows": side, "cols": side})
    assert frame_cost(values, MassSpringClothScene.world_size)[0] <= FRAME_BUDGET_S
    assert "this cloth at hertz 60, 1 substep, solver cg to cg_tolerance 0.01" in text
    MassSpringClothScene({**case, "hertz": 60, "substeps": 1, "cg_tolerance": 1e-2})
    # the targets are accepted, and the direct solver at 64x64 is not
    MassSpringClothScene({"material": "denim", "rows": 64, "cols": 64})
    with pytest.raises(ParamError, match="solver=cg"):
        MassSpringClothScene({"material": "denim", "rows": 64, "cols": 64, "solver": "direct"})
    # from the panel: a slider move that would not fit is refused and changes nothing
    s = MassSpringClothScene({"material": "denim", "rows": 40, "cols": 40})
    with pytest.raises(ParamError, match="substeps <= "):
        s.set("substeps", 40)
    assert s.p["substeps"] == 1
    # hertz counts within a frame: 8 steps of 64x64 at hertz 1000 do not fit, 1 at hertz 60 does
    with pytest.raises(ParamError, match="hertz <= "):
        MassSpringClothScene({"material": "denim", "rows": 64, "cols": 64, "hertz": 1000,
                              "substeps": 2})
    MassSpringClothScene({"material": "denim", "rows": 64, "cols": 64, "hertz": 1000})


def test_the_iteration_estimate_is_not_below_the_iterations_measured_at_16x16():
    """mass_spring_cost's estimate (0.8 of CG's bound, or the grid's) over the first 20 steps
    of a few presets (its docstring: the worst measured was 0.11-0.75 of the bound)."""
    for material, hertz, tolerance in (("cotton", 30, 1e-2), ("leather", 60, 1e-6),
                                       ("rubber", 240, 1e-6), ("denim", 60, 1e-10)):
        s = MassSpringClothScene({"material": material, "rows": 16, "cols": 16,
                                  "hertz": hertz, "cg_tolerance": tolerance})
        h_omega = rest_omega(s.p, cloth_spacing(s.p, s.world_size)) / hertz
        assert h_omega == pytest.approx(s.omega_max / hertz, rel=0.25)    # shear off: lower
        most = 0
        for _ in range(20):
            s.advance()
            most = max(most, s.cloth.ps.cg_iterations)
        assert most <= cg_iterations(h_omega, tolerance, 16, 16), material


def test_the_hud_says_in_words_when_the_physics_cannot_keep_up_with_real_time():
    s = MassSpringClothScene({"material": "denim", "rows": 10, "cols": 10})
    for _ in range(10):
        s.advance()
    # the steps as if they cost nothing: on a loaded machine a real 10x10 step may pass 16.7 ms
    s._costs = {k: 0.0 for k in s._costs}
    s._cost_mark = (s.steps, dict(s.cloth.spent))
    assert not any("not real time" in str(line) for line in s.hud_lines())
    s.effect_costs()
    s.cloth.spent["solve"] += 0.5                       # as if the last step took 0.5 s more
    s.advance()
    line = next(str(x) for x in s.hud_lines() if "not real time" in str(x))
    assert "ms of physics per 16.7 ms step" in line and "would catch up" in line


def test_the_real_time_advice_never_steps_past_the_limit_and_names_the_loops_cap(monkeypatch):
    """'Leather inside its limit' (symplectic Euler at h = 0.05 ms, hertz 1000) said 'fewer
    particles or substeps would catch up': fewer substeps step past leather's 0.064 ms limit, and
    at hertz 1000 the loop's 8 steps a frame hold time to 0.48x real time however cheap a step."""
    monkeypatch.setattr(MassSpringClothScene, "step_ms", lambda self: 3.3)   # as measured
    s = MassSpringClothScene()
    s.apply_card(MassSpringClothScene.find_card("Leather inside its limit"))
    for _ in range(5):
        s.advance()
    words = s.real_time_words()
    assert "substeps" not in words and "implicit_euler at 60 Hz (~" in words
    assert words.endswith("estimated) would keep up")
    assert "the loop's 8 steps a frame" in words and "hold hertz 1000 to 0.48x" in words
    s = MassSpringClothScene({"integrator": "symplectic_euler", "substeps": 50, "hertz": 60})
    for _ in range(5):
        s.advance()
    words = s.real_time_words()                    # 3.3 ms per 16.7 ms step: real time
    assert words == ""
    monkeypatch.setattr(MassSpringClothScene, "step_ms", lambda self: 30.0)
    words = s.real_time_words()
    assert "substeps" not in words and "loop" not in words and "would catch up" in words
    # implicit Euler is offered only where its estimated step fits 1/60 s: not on a 64x64 cloth
    # of stiffness 1e5 and mass 0.001 (~46 ms a step estimated)
    s = MassSpringClothScene({"rows": 64, "cols": 64, "material": "custom", "mass": 0.001,
                              "tension": 1e5, "compression": 1e5, "shear_stiffness": 1e5,
                              "bending_stiffness": 1e5, "integrator": "symplectic_euler",
                              "hertz": 1000})
    for _ in range(5):
        s.advance()
    words = s.real_time_words()
    assert "implicit_euler" not in words and "hertz 480 or less" in words


def test_the_scene_caps_cg_at_what_is_left_of_a_frame_after_the_rest_of_its_step():
    """The cap the scene hands CG (budget_iterations) is what fits a frame: hertz/60 steps of
    `substeps` substeps, each paying its set-up and, with solver=direct, the LU it tried first
    (CG is then the fallback, and LU + CG must fit together)."""
    from app.physics.mass_spring_cost import (LU_POWER, LU_SECONDS, SETUP_FIXED,
                                              SETUP_PER_PARTICLE, iteration_seconds,
                                              steps_per_frame)
    for settings in ({"rows": 40, "cols": 40}, {"rows": 20, "cols": 20, "substeps": 8},
                     {"rows": 24, "cols": 24, "hertz": 480, "substeps": 2},
                     {"rows": 52, "cols": 52, "solver": "direct"}):
        s = MassSpringClothScene({"material": "denim", **settings})
        p, n = s.p, s.p["rows"] * s.p["cols"]
        lu = LU_SECONDS * n ** LU_POWER if p["solver"] == "direct" else 0.0
        substep = (SETUP_FIXED + SETUP_PER_PARTICLE * n + lu
                   + s.cloth.ps.budget_iterations * iteration_seconds(n))
        frame = steps_per_frame(p["hertz"]) * p["substeps"] * substep
        assert 0.8 * FRAME_BUDGET_S <= frame <= FRAME_BUDGET_S, settings


def test_a_first_guess_never_moves_a_fixed_row():
    """A particle grabbed this step had a dv last step: CG's answer keeps its rows at 0 even
    when the guess it keeps has them non-zero."""
    rng = np.random.default_rng(7)
    Q, _ = np.linalg.qr(rng.normal(size=(10, 10)))
    matrix = Q @ np.diag(np.logspace(0, 2, 10)) @ Q.T
    A = lambda w: (matrix @ w.ravel()).reshape(w.shape)              # noqa: E731
    b, free = rng.normal(size=(10, 1)), np.ones((10, 1))
    free[[2, 7]] = 0.0
    keep = free[:, 0] > 0
    exact = np.zeros((10, 1))
    exact[keep, 0] = np.linalg.solve(matrix[np.ix_(keep, keep)], b[keep, 0])
    guess = exact + 5.0 * (1.0 - free)                  # right on the free rows, not the fixed
    x, report = preconditioned_cg(A, b, free, tolerance=1e-10, x0=guess)
    assert report.warm and np.all(x[~keep] == 0.0) and np.allclose(x, exact, atol=1e-8)


def test_a_direct_answer_that_misses_the_tolerance_is_flagged_and_cg_tried():
    """solve_directly checks the LU's answer like CG's: a residual above the tolerance is not
    'converged', and CG's answer is taken where it is better (both say so in the report)."""
    from app.physics.linear_solve import solve_directly
    rng = np.random.default_rng(3)
    matrix = np.diag(np.linspace(1.0, 10.0, 8))
    A = lambda w: (matrix @ w.ravel()).reshape(w.shape)              # noqa: E731
    b, free = rng.normal(size=(8, 1)), np.ones((8, 1))
    exact = np.linalg.solve(matrix, b)
    poor = exact * (1.0 + 1e-3)                          # a residual of ~1e-3
    cg = lambda: preconditioned_cg(A, b, free, tolerance=1e-10)      # noqa: E731
    x, report = solve_directly(A, b, free, "sparse LU", lambda: (poor, 99), 1e-6, cg)
    assert not report.converged and report.stop == "solved" and report.residual > 1e-6
    assert report.fallback == "cg" and report.fallback_residual <= 1e-10
    assert np.allclose(x, exact, rtol=1e-9) and "sparse LU solve left a residual" in report.words()
    x, report = solve_directly(A, b, free, "sparse LU", lambda: (poor, 99), 1e-6)
    assert not report.converged and report.fallback is None and np.array_equal(x, poor)
    x, report = solve_directly(A, b, free, "sparse LU", lambda: (None, None), 1e-6)
    assert not report.converged and report.stop == "failed" and np.all(x == 0.0)


def test_the_first_guess_from_the_last_two_steps_saves_iterations_over_the_last_one_alone():
    """mass_spring's next_dv_guess (2 dv_1 - dv_2) against the last step's dv alone and dv = 0,
    over the first 40 steps of a 24x24 denim cloth's fall (measured: 905, 1129, 1536)."""
    totals = {}
    for mode in ("cold", "last", "extrapolated"):
        s = MassSpringClothScene({"material": "denim", "rows": 24, "cols": 24})
        ps = s.cloth.ps
        if mode != "extrapolated":
            ps.next_dv_guess = (lambda: None) if mode == "cold" else (lambda: ps.last_dv)
        totals[mode] = 0
        for _ in range(40):
            s.advance()
            totals[mode] += ps.cg_iterations
    assert totals["extrapolated"] <= 0.9 * totals["last"] <= 0.9 * 0.85 * totals["cold"], totals


def test_cg_whose_running_residual_alone_meets_the_tolerance_is_not_converged():
    """Near the rounding floor CG's running residual keeps falling while the true one stalls
    (a condition number of 1e8: the true one stays ~1e-9): the report checks the true one."""
    rng = np.random.default_rng(0)
    Q, _ = np.linalg.qr(rng.normal(size=(40, 40)))
    matrix = Q @ np.diag(np.logspace(0, 8, 40)) @ Q.T
    matrix = 0.5 * (matrix + matrix.T)
    A = lambda w: (matrix @ w.ravel()).reshape(w.shape)              # noqa: E731
    b = rng.normal(size=(40, 1))
    x, report = preconditioned_cg(A, b, np.ones((40, 1)), tolerance=1e-14, max_iterations=4000)
    assert report.stop == "rounding" and not report.converged and report.residual > 1e-12
    assert "running residual only" in report.words()


def test_the_solve_details_do_not_say_never_factored_when_the_sparse_lu_took_the_step():
    s = MassSpringClothScene({"rows": 6, "cols": 6, "hertz": 1, "cg_tolerance": 1e-10})
    s.cloth.ps.cg_max_iterations = 3                    # CG stops short: the sparse LU steps
    s.advance()
    assert s.cloth.ps.solve.fallback == "sparse LU"
    line = next(x for x in s.hud_details() if x.startswith("CG (block Jacobi"))
    assert "never factored" not in line and "sparse LU" in line
    s.cloth.ps.cg_max_iterations = None
    s.advance()
    assert s.cloth.ps.solve.fallback is None
    assert "never factored" in next(x for x in s.hud_details() if x.startswith("CG (block"))


def test_the_lu_factors_fill_in_as_the_docstrings_say_at_64x64():
    """scenes/mass_spring_cloth.py and cloth_matrix.py: 11x A's non-zeros at 64x64, 8x with
    shear on (measured 11.0-11.3 and 8.3)."""
    for shear, low, high in ((False, 10.0, 12.0), (True, 7.5, 8.9)):
        s = MassSpringClothScene({"material": "denim", "rows": 64, "cols": 64, "shear": shear})
        for _ in range(3):
            s.advance()
        ps = s.cloth.ps
        _, fill = ps.matrix.factorize(ps.free[:, 0] > 0)
        assert low <= fill / ps.matrix.nonzeros <= high, (shear, fill / ps.matrix.nonzeros)
