"""Implicit Euler's linear solve never fails silently (issue 14): CG reports how it stopped
(converged, breakdown, iteration cap), the step then takes a dense or sparse direct solve of the
same system (the true linearised step), and the metrics and the HUD say so."""

import numpy as np
import pytest

from app.physics.linear_solve import dense_solve, preconditioned_cg, solve
from app.physics.mass_spring import MassSpringCloth, implicit_euler
from app.physics.blender_cloth import material_settings
from app.physics.cloth_matrix import ClothMatrix
from scenes.integrators import IntegratorsScene
from scenes.mass_spring_cloth import MassSpringClothScene


def matrix_product(matrix):
    return lambda w: (matrix @ w.ravel()).reshape(w.shape)


def test_cg_reports_a_breakdown_and_returns_where_it_stopped():
    """An indefinite A: b is a direction with b.Ab = 0, so CG cannot take its first step. It
    used to return 0 as if solved; now it says so, and the dense fallback gives A^-1 b."""
    A = matrix_product(np.diag([1.0, -1.0]))
    b, free = np.array([[1.0], [1.0]]), np.ones((2, 1))
    x, report = preconditioned_cg(A, b, free)
    assert not report.converged and report.stop == "breakdown" and report.iterations == 0
    assert np.all(x == 0.0) and report.residual == 1.0
    x, report = solve(A, b, free, None, 1e-12, None, ("dense LU", lambda: dense_solve(A, b, free)))
    assert np.allclose(x.ravel(), [1.0, -1.0]) and report.fallback == "dense LU"
    assert report.fallback_residual < 1e-15 and not report.converged      # CG's own verdict
    assert "broke down" in report.words() and "dense LU" in report.words()


def test_cg_reports_its_iteration_cap_and_the_true_residual_of_its_answer():
    rng = np.random.default_rng(2)
    Q, _ = np.linalg.qr(rng.normal(size=(8, 8)))
    matrix = Q @ np.diag(np.logspace(0, 6, 8)) @ Q.T          # SPD, condition 1e6
    A, b, free = matrix_product(matrix), rng.normal(size=(8, 1)), np.ones((8, 1))
    x, report = preconditioned_cg(A, b, free, max_iterations=2)
    assert report.stop == "iteration cap" and report.iterations == 2 and not report.converged
    true = np.linalg.norm(b - matrix @ x) / np.linalg.norm(b)
    assert report.residual == pytest.approx(true, rel=1e-9)
    assert "cap of 2 iterations" in report.words() and "last iterate" in report.words()
    x, report = preconditioned_cg(A, b, free, tolerance=1e-8, max_iterations=200)
    assert report.converged and report.residual <= 1e-8 and report.words() == ""


def test_the_orbit_at_hertz_60_takes_the_true_linearised_step_where_cg_breaks_down():
    """At t = 0.567 s (step 34, 19 px apart) the system is indefinite; CG broke down at once and
    the step was dv = 0, shown as E/E0 = -187.8. Now: flagged, and the dense LU step (about -6.1,
    the value an independent dense solve gives)."""
    scene = IntegratorsScene({"problem": "orbit", "hertz": 60})
    for _ in range(40):
        scene.advance()
    m = scene.metrics()
    assert m["implicit_euler_cg_failures"] >= 1
    assert -7.0 < m["implicit_euler_energy_ratio"] < -5.0
    line = next(line for line in scene.hud_lines() if line.startswith("implicit Euler"))
    assert "broke down" in line and "dense LU" in line and "t = 0.57 s" in line
    calm = IntegratorsScene({"problem": "spring"})
    calm.advance()
    assert calm.metrics()["implicit_euler_cg_converged"] is True
    assert calm.metrics()["implicit_euler_cg_failures"] == 0
    assert len(calm.hud_lines()) == 1


def test_the_cloths_sparse_matrix_is_its_product():
    c = MassSpringCloth(4, 5, 16.0, (50.0, 50.0), "top")
    c.material = material_settings("denim")
    c.on |= {"shear"}
    c.configure()
    ps = c.ps
    ps.x = c.rest_x * 1.02 + np.random.default_rng(1).normal(0, 0.3, ps.x.shape)
    stiff, damp = ps.blocks(ps.x)
    assert [fam for fam, _ in stiff] == [fam for fam, _ in damp]     # every set damped
    blocks = [(fam, B + 0.3 * D) for (fam, B), (_, D) in zip(stiff, damp)]
    mass = np.random.default_rng(2).uniform(1, 2, ps.n)
    w = np.random.default_rng(3).normal(size=(2, ps.n))
    from app.physics.spring_forces import block_product
    expected = mass * w + block_product(blocks, w, 4, 5)
    for storage in ("dia", "csr"):
        matrix = ClothMatrix([fam for fam, _ in blocks], 4, 5, storage)
        for _ in range(2):                      # refreshed in place: the second time the same
            matrix.refresh(mass, blocks)
            assert np.allclose(matrix.product(w), expected, rtol=1e-12, atol=1e-9)
        dense = matrix.matrix.toarray()
        assert np.array_equal(dense, dense.T)                 # symmetric, entry for entry
        assert np.count_nonzero(dense) <= matrix.nonzeros


def test_a_cloth_step_whose_cg_stops_short_is_the_direct_solve_and_says_so():
    """CG capped at 3 iterations cannot reach 1e-10 on a cloth at hertz 1 (uncapped it takes 8):
    the step is the sparse LU's, the same as CG's to 1e-8 (1e-10 sits near this system's
    rounding floor, ~4e-11: a 1e-12 nudge of the start can leave CG just above it), and the
    metrics and the HUD say what happened."""
    def scene(tolerance):
        return MassSpringClothScene({"rows": 6, "cols": 6, "hertz": 1, "cg_tolerance": tolerance})
    capped, exact = scene(1e-10), scene(1e-8)
    capped.cloth.ps.cg_max_iterations = 3
    capped.advance()
    exact.advance()
    m = capped.metrics()
    assert m["cg_converged"] is False and m["cg_failures"] == 1 and m["cg_iterations"] == 3
    assert capped.cloth.ps.solve.fallback == "sparse LU"
    assert capped.cloth.ps.solve.fallback_residual < 1e-10
    assert np.abs(capped.cloth.ps.x - exact.cloth.ps.x).max() < 1e-6
    assert exact.metrics()["cg_converged"] is True and exact.metrics()["cg_failures"] == 0
    line = capped.hud_lines()[-1]
    assert "cap of 3 iterations" in line and "sparse LU" in line
    assert MassSpringClothScene({"integrator": "verlet"}).metrics()["cg_converged"] is None


def test_one_implicit_cloth_step_reports_its_solve():
    c = MassSpringCloth(4, 4, 16.0, (50.0, 50.0), "top")
    c.material = material_settings("cotton")
    c.configure()
    implicit_euler(c.ps, 1 / 60)
    assert c.ps.solve.method == "cg" and c.ps.solve.converged
    assert 0 < c.ps.cg_residual <= c.ps.cg_tolerance and c.ps.cg_iterations > 0
