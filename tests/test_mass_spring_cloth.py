"""The mass-spring cloth: its forces and Jacobians, Baraff-Witkin's implicit step, the explicit
limit it predicts, its materials, its effects and its command line."""

import json
import math

import numpy as np
import pytest

from app.physics.integrators import INTEGRATORS
from app.physics.blender_cloth import MATERIALS, material_settings, spring_constants
from app.physics.mass_spring import MassSpringCloth, implicit_euler
from app.physics.mass_spring_stability import (marginal, predicted_limit, symplectic_limit,
                                               top_mode)
from app.physics.spring_forces import SpringDamping, SpringSet
from app.scene import ParamError
from scenes.mass_spring_cloth import JOULE, MassSpringClothScene


def small_cloth(rows=4, cols=5, material="denim", pins="top", on=None, spacing=16.0):
    c = MassSpringCloth(rows, cols, spacing, (50.0, 50.0), pins)
    c.material = material_settings(material)
    if on is not None:
        c.on = set(on)
    c.configure()
    return c


def springs_and_damping(c):
    """The raw force objects of a cloth (unwrapped from their stopwatches)."""
    return [f.force for f in c.ps.forces if isinstance(f.force, (SpringSet, SpringDamping))]


def test_material_values_map_blender_units_as_the_docstring_says():
    k = spring_constants(material_settings("leather"), 16.0)
    assert k["k_tension"] == pytest.approx(9.174e4 * 80 / 16, rel=1e-3)
    assert k["density"] == pytest.approx(0.4 / 256)
    # a particle's weight strains a spring as much as in Blender: m g / (k r) = 0.00981 m / S
    m, g, r = 0.4, 900.0, 16.0
    assert m * g / (k["k_tension"] * r) == pytest.approx(0.00981 * m / 80, rel=1e-9)


@pytest.mark.parametrize("branch", ["tension", "compression"])
def test_force_and_both_jacobians_match_finite_differences(branch):
    rng = np.random.default_rng(3)
    c = small_cloth(3, 4, on={"damping", "shear", "bending"})
    c.material["compression"] = 7.0             # tension and compression stiffness differ
    c.configure()
    ps = c.ps
    scale = 1.04 if branch == "tension" else 0.96   # every spring stretched / every one shorter
    x = c.rest_x * scale + rng.normal(0, 0.05, c.rest_x.shape)
    v = rng.normal(0, 20.0, x.shape)
    length = [np.linalg.norm(x.reshape(3, 4, 2)[f.a] - x.reshape(3, 4, 2)[f.b], axis=-1) / f.rest
              for s in ("structural", "shear", "bending") for f in c.sets[s].families]
    assert all(((l > 1) if branch == "tension" else (l < 1)).all() for l in length)
    ps.inv_mass[:] = 1.0 / ps.mass                  # no pins: every row is checked
    forces = springs_and_damping(c)

    def f_at(xx, vv):
        f = np.zeros_like(xx)
        for force in forces:
            force.accumulate(ps, xx, vv, f)
        return f

    w = rng.normal(size=x.shape)
    eps = 1e-6
    fd_x = (f_at(x + eps * w, v) - f_at(x - eps * w, v)) / (2 * eps)
    fd_v = (f_at(x, v + eps * w) - f_at(x, v - eps * w)) / (2 * eps)
    jx, jv = np.zeros_like(x), np.zeros_like(x)
    for force in forces:
        dx, dv = force.jacobian(ps, x, v)
        for add, out in ((dx, jx), (dv, jv)):
            if add is not None:
                add(w, out)
    assert np.abs(jx - fd_x).max() / np.abs(fd_x).max() < 1e-5
    assert np.abs(jv - fd_v).max() / np.abs(fd_v).max() < 1e-5
    # and the force itself is the slide's formula, spring by spring
    fam = c.sets["structural"].families[0]
    X, V = x.reshape(3, 4, 2), v.reshape(3, 4, 2)
    l = X[fam.a][0, 0] - X[fam.b][0, 0]
    tau = math.sqrt(256 * 0.00981 / 900)              # the docstring's Blender time unit
    ks = 256 / tau ** 2 * (40 if branch == "tension" else 7) / 16
    kd = 25 / tau
    u = l / np.linalg.norm(l)
    fa = -(ks * (np.linalg.norm(l) - 16) + kd * (V[fam.a][0, 0] - V[fam.b][0, 0]) @ u) * u
    one = SpringSet("one", [fam], 3, 4, *(c.constants["k_tension"], c.constants["k_compression"]))
    only = np.zeros_like(x)
    one.accumulate(ps, x, v, only)
    SpringDamping([(fam, c.constants["kd"])], 3, 4).accumulate(ps, x, v, only)
    assert np.allclose(only.reshape(3, 4, 2)[0, 0], fa, rtol=1e-9)


def test_one_implicit_step_matches_a_dense_solve_of_the_same_system():
    rng = np.random.default_rng(5)
    c = small_cloth(4, 4, pins="corners", on={"gravity", "air", "damping", "shear", "bending"})
    ps = c.ps
    ps.x = c.rest_x * 1.03 + rng.normal(0, 0.05, c.rest_x.shape)   # all springs stretched
    ps.v = rng.normal(0, 30.0, ps.x.shape) * ps.free
    x0, v0, h, n = ps.x.copy(), ps.v.copy(), 1 / 60, ps.x.size
    f0 = ps.force(x0, v0).ravel().copy()
    forces = [f.force for f in ps.forces]

    def force(xx, vv):
        f = np.zeros((16, 2))
        for fo in forces:
            fo.accumulate(ps, xx.reshape(16, 2), vv.reshape(16, 2), f)
        return f.ravel()
    # dense Jacobians by central differences of the forces (exact: every spring is stretched);
    # the damping force's x-derivative is left out, as Baraff & Witkin (and the solver) do
    eps = 1e-6
    K, D = np.zeros((n, n)), np.zeros((n, n))
    undamped = [fo for fo in forces if not isinstance(fo, SpringDamping)]
    for j in range(n):
        e = np.zeros(n)
        e[j] = eps
        K[:, j] = (sum_force(undamped, ps, x0.ravel() + e, v0.ravel())
                   - sum_force(undamped, ps, x0.ravel() - e, v0.ravel())) / (2 * eps)
        D[:, j] = (force(x0.ravel(), v0.ravel() + e)
                   - force(x0.ravel(), v0.ravel() - e)) / (2 * eps)
    M = np.diag(np.repeat(ps.mass, 2))
    free = np.repeat(ps.free[:, 0], 2).astype(bool)
    A = M - h * D - h * h * K
    b = h * (f0 + h * K @ v0.ravel())
    dv = np.zeros(n)
    dv[free] = np.linalg.solve(A[np.ix_(free, free)], b[free])
    ps.cg_tolerance = 1e-12
    implicit_euler(ps, h)
    assert np.allclose(ps.v.ravel(), v0.ravel() + dv, rtol=1e-7, atol=1e-7)
    assert np.allclose(ps.x.ravel(), x0.ravel() + h * (v0.ravel() + dv), rtol=1e-9, atol=1e-9)


def sum_force(forces, ps, x, v):
    f = np.zeros((ps.n, 2))
    for fo in forces:
        fo.accumulate(ps, x.reshape(-1, 2), v.reshape(-1, 2), f)
    return f.ravel()


def test_a_damped_hanging_cloth_settles_and_its_forces_balance():
    c = small_cloth(6, 6, material="denim", pins="top")
    c.ps.cg_tolerance = 1e-8
    for _ in range(180):                         # 3 s at 60 Hz
        c.step(1 / 60, "implicit_euler")
    assert c.kinetic_energy() < 1e-6 * float(c.ps.mass.sum()) * 900 * 16   # << m g spacing
    f = c.ps.force(c.ps.x, np.zeros_like(c.ps.v)) * c.ps.free
    weight = c.ps.mass[:, None] * 900
    assert np.abs(f).max() < 1e-4 * weight.max()
    assert c.pinned_drift() == 0.0


def conservative_scene(hertz: int, nudge: float = 0.3):
    """A silk cloth with no damping, air or gravity, particles nudged: only springs act."""
    s = MassSpringClothScene({"material": "silk", "rows": 6, "cols": 6, "gravity": False,
                              "air": False, "damping": False, "pins": "corners",
                              "integrator": "symplectic_euler", "hertz": hertz})
    ps = s.cloth.ps
    ps.x = ps.x + np.random.default_rng(2).normal(0, nudge, ps.x.shape) * ps.free
    s._estimate_mode(iterations=200)
    return s


def test_symplectic_euler_is_bounded_below_the_predicted_limit_and_blows_up_above_it():
    probe = conservative_scene(60)
    limit = probe.explicit_limit()
    assert limit == pytest.approx(2.0 / probe.omega_max)          # no damping: 2/omega_max
    assert predicted_limit("symplectic_euler", probe.omega_max, 0.0) == pytest.approx(limit)
    below = conservative_scene(math.ceil(1 / (0.8 * limit)))
    e0 = below.cloth.energy()
    energies = []
    for _ in range(1500):
        below.advance()
        energies.append(below.cloth.energy())
    assert below.is_finite()
    # symplectic Euler's energy swings (by 1/(1 - (omega h / 2)^2) at omega h = 1.6) but does
    # not grow: the second half of the run reaches no higher than the first
    assert max(energies) < 5 * e0
    assert max(energies[750:]) < 1.05 * max(energies[:750])
    above = conservative_scene(math.floor(1 / (1.2 * limit)))
    for _ in range(1500):
        above.advance()
        if not above.is_finite():
            break
    assert not above.is_finite(), "1.2x past the predicted limit, symplectic Euler must blow up"


@pytest.mark.parametrize("factor, bounded", [(0.98, True), (1.03, False)])
def test_the_undamped_limit_is_two_over_omega_max_as_measured(factor, bounded):
    """Silk with spring damping and air off: nothing damps the top mode, so the limit the HUD
    shows is the undamped one, 2/omega_max (top_mode's `undamped`, the case it alone decides).
    Measured on the cloth nudged by 0.01 px (the linear regime; nudged by 0.3 px its own
    deformation lowers the limit to ~0.8x, see test_symplectic_euler_is_bounded_below...): 0.98x
    stays bounded for 2000 steps, 1.03x blows up. (Once nothing checked this: the cap could have
    read 2.2/omega_max and the suite stayed green.)"""
    scene = conservative_scene(60, nudge=0.01)
    limit = scene.explicit_limit()
    assert scene.mode_damping <= 1e-9 * scene.omega_max
    c, h = scene.cloth, factor * limit
    e0 = c.energy()
    energies = []
    for _ in range(2000):
        c.step(h, "symplectic_euler")
        if not c.is_sane():
            break
        energies.append(c.energy())
    if bounded:
        assert c.is_sane() and max(energies) < 50 * e0
        assert max(energies[1000:]) < 1.05 * max(energies[:1000])        # no growth
    else:
        assert not c.is_sane() or max(energies) > 1e6 * e0


def test_the_predicted_limits_match_the_theory_of_each_integrator():
    for omega, c in ((1000.0, 0.0), (1000.0, 300.0)):
        assert predicted_limit("symplectic_euler", omega, c) == pytest.approx(
            symplectic_limit(omega, c), rel=1e-9)
    assert predicted_limit("verlet", 1000.0, 0.0) == pytest.approx(2e-3, rel=1e-9)
    assert predicted_limit("rk4", 1000.0, 0.0) == pytest.approx(2 * math.sqrt(2) / 1000, rel=1e-9)
    assert predicted_limit("euler", 1000.0, 0.0) is None
    assert predicted_limit("midpoint", 1000.0, 0.0) is None
    assert predicted_limit("euler", 1000.0, 300.0) == pytest.approx(300 / (1000 ** 2), rel=1e-6)
    assert predicted_limit("implicit_euler", 1000.0, 0.0) == math.inf


@pytest.mark.parametrize("material", list(MATERIALS))
def test_every_material_with_every_integrator_inside_its_limit_runs_10_s(material):
    # a 3x3 cloth of 600 px cells: omega_max ~ spacing^-1.5 is low, so 10 s take few steps
    c = small_cloth(3, 3, material=material, pins="top", spacing=600.0)
    start = c.copy_state()
    omega, damp, _ = top_mode(c.ps, 200)
    for name in INTEGRATORS:
        c.restore_state(start)
        limit = predicted_limit(name, omega, damp)
        if limit is None:       # no stable step at all: only for a method that always gains
            assert name in ("euler", "midpoint") and MATERIALS[material].spring_damping == 0
            continue            # energy, on silk (air drag alone is too weak to beat that)
        h = min(0.5 * limit, 1 / 15)
        steps = math.ceil(10.0 / h)
        for _ in range(steps):
            c.step(h, name)
        assert c.is_sane(), (material, name)


def test_leather_holds_its_shape_where_silk_sags_and_rubber_stretches_most():
    """The scene docstring's comparison: top-edge sag after 1.5 s on the default cloth."""
    sag, stretch = {}, {}
    for material in ("silk", "leather", "rubber"):
        s = MassSpringClothScene({"material": material})
        c = s.cloth
        y0 = c.ps.x[c.cols // 2, 1]                   # the middle of the top row
        for _ in range(90):
            s.advance()
        sag[material] = c.ps.x[c.cols // 2, 1] - y0
        stretch[material] = s.metrics()["max_stretch"]
    assert sag["leather"] < 0.7 * sag["silk"]
    assert sag["rubber"] > 1.3 * sag["silk"] and stretch["rubber"] > 3 * stretch["silk"]


def test_effects_that_are_off_do_no_work():
    s = MassSpringClothScene({"rows": 5, "cols": 5, "shear": False, "bending": False,
                              "wind": False, "damping": False, "air": False})
    for _ in range(3):
        s.advance()
    calls = s.cloth.calls
    assert calls["structural"] > 0 and calls["gravity"] > 0
    assert all(calls.get(k, 0) == 0 for k in ("shear", "bending", "wind", "damping", "air"))
    s.set("shear", True)
    s.set("wind", True)
    s.advance()
    assert calls["shear"] > 0 and calls["wind"] > 0 and calls.get("bending", 0) == 0
    assert set(s.effect_costs()) == {"gravity", "wind", "shear", "structural", "solve"}


def test_a_material_sets_the_sliders_and_a_moved_slider_makes_it_custom():
    s = MassSpringClothScene({"material": "leather"})
    assert s.p["bending_stiffness"] == 150 and s.p["tension"] == 80
    s.set("material", "silk")
    assert s.p["spring_damping"] == 0 and s.p["mass"] == 0.15
    assert s.cloth.constants["kd"] == 0
    s.set("tension", 30)
    assert s.p["material"] == "custom" and s.cloth.material["tension"] == 30
    mixed = MassSpringClothScene({"material": "denim", "tension": 55})
    assert mixed.p["material"] == "custom" and mixed.p["tension"] == 55
    assert mixed.p["bending_stiffness"] == 10          # the rest from denim


def test_an_explicit_blow_up_is_caught_and_implicit_euler_goes_on_at_the_same_step():
    s = MassSpringClothScene({"material": "leather", "integrator": "symplectic_euler"})
    snap = s.snapshot()
    for _ in range(30):
        s.advance()
        if not s.is_finite():
            break
    assert not s.is_finite()
    s.restore(snap)
    s.set("integrator", "implicit_euler")
    for _ in range(60):
        s.advance()
    assert s.is_finite() and s.metrics()["cg_iterations"] > 0
    assert s.metrics()["pinned_drift"] == 0.0


def test_grab_drag_release_locks_and_rmb_unlocks():
    from app.scene import InputEvent
    s = MassSpringClothScene({"rows": 6, "cols": 6, "pins": "corners"})
    c = s.cloth
    target = tuple(c.ps.x[c.cols * 5 + 3])                      # a bottom particle
    s.handle_event(InputEvent("mouse_down", target, 1))
    assert c.grabbed == (5, 3)
    s.handle_event(InputEvent("mouse_move", (target[0] + 80, target[1] + 40)))
    for _ in range(5):
        s.advance()
    assert np.allclose(c.ps.x[c.cols * 5 + 3], (target[0] + 80, target[1] + 40))
    s.handle_event(InputEvent("mouse_up", (target[0] + 80, target[1] + 40), 1))
    assert c.locked[5, 3] and c.grabbed is None
    for _ in range(10):
        s.advance()
    assert s.metrics()["pinned_drift"] == 0.0
    s.handle_event(InputEvent("mouse_down", (target[0] + 80, target[1] + 40), 3))
    assert not c.locked[5, 3]


@pytest.mark.parametrize("setting", ["tension=-1", "compression=nan", "mass=0",
                                     "material=wool", "integrator=leapfrog",
                                     "rows=64", "shear_stiffness=inf"])
def test_bad_input_is_one_line_and_exit_2(setting, capsys):
    from app.__main__ import main
    args = ["--headless", "--scene", "mass_spring_cloth", "--steps", "1", "--set", setting]
    if setting == "rows=64":
        args += ["--set", "cols=64", "--set", "substeps=20"]     # over the step budget
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err


def test_check_combination_refuses_a_step_over_budget():
    with pytest.raises(ParamError, match="too slow for the window"):
        MassSpringClothScene({"rows": 64, "cols": 64, "substeps": 20})


def test_bench_mass_spring_quick_runs_and_has_its_json_keys(tmp_path, capsys, png_charts):
    from app.__main__ import main         # the command line's entry point, in this process
    code = main(["bench", "mass_spring", "--quick", "--json", "--out", str(tmp_path)])
    out, err = capsys.readouterr()
    assert code == 0, err
    data = json.loads(out)
    assert {"large_steps", "step_ms", "implicit_vs_explicit"} <= set(data)
    row = data["large_steps"][0]
    assert {"material", "stiffness_scale", "integrator", "max_stable_h", "predicted_h",
            "margin", "unstable_seen_at_step", "ms_per_sim_second"} <= set(row)
    for r in data["large_steps"]:       # symplectic Euler's own limit is never exceeded
        if r["integrator"] == "symplectic_euler":
            assert r["max_stable_h"] and r["margin"] <= 1.0 and not r["above_prediction"]
            assert r["unstable_seen_at_step"] < r["horizon_steps"] / 2    # growth seen in time
    assert {q["stiffness_scale"] for q in data["implicit_vs_explicit"]} == {1, 100}
    assert set(data["step_ms"]) == set(INTEGRATORS)
    assert list(tmp_path.glob("*.png"))


@pytest.mark.parametrize("scale", [1, 10, 100])
def test_the_predicted_symplectic_limit_is_within_5_percent_of_the_measured_one(scale):
    """The issue's target (10 %), with the bench's own test of stability (bench mass_spring):
    damped, with gravity, every material. A shiver that saturates instead of reaching inf counts
    as unstable (it did not, and the measured limit came out 12-16 % above the prediction); the
    damping rate is top_mode's fixed point (the worst pairing alone was 10 % low at cotton x100)."""
    from app.bench.mass_spring import make_cloth, survives
    for material in MATERIALS:
        omega, damping, _ = top_mode(make_cloth(material, scale, 6).ps, 200)
        h = predicted_limit("symplectic_euler", omega, damping)
        assert survives(material, scale, "symplectic_euler", 0.97 * h, 6, 150), material
        assert not survives(material, scale, "symplectic_euler", 1.05 * h, 6, 150), material


def test_the_try_cards_limits_are_what_they_say():
    """'inside its limit' is below the HUD's damped limit and runs; '60 Hz' is past it."""
    cards = {t.label: t for t in MassSpringClothScene.tries}
    inside = MassSpringClothScene(dict(cards["Leather inside its limit"].settings))
    h = inside.dt / inside.p["substeps"]
    assert h < 0.8 * inside.limit("symplectic_euler")
    for _ in range(20):                 # 400 substeps: at 1.7x the limit it blew up in 24
        inside.advance()
    assert inside.is_finite() and np.abs(inside.cloth.ps.v).max() < 1000.0
    assert inside.metrics()["limit_band"] == "marginal"          # as the card says (0.8x)
    past = MassSpringClothScene(dict(cards["Leather past its limit"].settings))
    assert past.dt > 100 * past.limit("symplectic_euler")
    implicit = MassSpringClothScene(dict(cards["Implicit Euler at 30 Hz"].settings))
    assert 60 < implicit.dt / implicit.limit("symplectic_euler") < 130      # "~90x"
    assert 20 < implicit.dt * implicit.omega_max / 2 < 30                  # "25x 2/omega_max"


def test_implicit_euler_pays_for_its_stability_in_energy_symplectic_euler_does_not():
    """The HUD's energy line: with damping, air and wind off the energy (0 at the start pose)
    should stay 0; implicit Euler's artificial damping takes out most of what the fall releases,
    symplectic Euler inside its limit keeps it within a few per cent."""
    def run(integrator, hertz, substeps):
        s = MassSpringClothScene({"material": "silk", "rows": 6, "cols": 6, "damping": False,
                                  "air": False, "integrator": integrator, "hertz": hertz,
                                  "substeps": substeps})
        assert s.metrics()["cg_iterations"] == (None if integrator == "implicit_euler" else 0)
        for _ in range(hertz):                                        # 1 s
            s.advance()
        c = s.cloth
        released = 900 * float(np.sum(c.ps.mass * c.ps.free[:, 0] * (c.ps.x[:, 1] - c.rest_x[:, 1])))
        return c.energy() / released
    assert run("implicit_euler", 60, 1) < -0.5
    assert abs(run("symplectic_euler", 1000, 2)) < 0.05


def test_the_wind_pushes_on_area_so_silk_flows_where_denim_hangs():
    """The 'silk in the wind' card: the same wind moves light silk several times further."""
    drift = {}
    for material in ("silk", "denim"):
        s = MassSpringClothScene({"material": material, "wind": True, "rows": 8, "cols": 8})
        x0 = s.cloth.ps.x[:, 0].copy()
        for _ in range(60):
            s.advance()
        drift[material] = float(np.abs(s.cloth.ps.x[:, 0] - x0).mean())
    assert drift["silk"] > 3 * drift["denim"]


def test_top_modes_symplectic_limit_is_the_linearised_cloths_own():
    """The step matrix S of symplectic Euler on the linearised cloth (x'' = -M^-1 (K x + D x')),
    built densely on a 6x6 cloth: 4096 steps of it (S^4096) shrink every state just below
    top_mode's limit and blow one up just above it, also where the stiffest and the most damped
    modes differ (cotton x100: the worst pairing alone put the limit 10 % low, this fails)."""
    from app.bench.mass_spring import make_cloth
    from app.physics.spring_forces import block_product
    for material, scale in (("cotton", 100), ("denim", 10), ("rubber", 1)):
        c = make_cloth(material, scale, 6)
        ps = c.ps
        stiff, damp = ps.blocks(ps.x)
        n2 = 2 * ps.n
        E = np.eye(n2).reshape(n2, 2, ps.n)
        K = np.array([block_product(stiff, e, 6, 6).ravel() for e in E]).T
        D = np.array([(block_product(damp, e, 6, 6) + ps.air_drag() * e).ravel() for e in E]).T
        free = np.tile(ps.free[:, 0] > 0, 2)
        K, D = K[np.ix_(free, free)], D[np.ix_(free, free)]
        minv = 1.0 / np.tile(ps.mass, 2)[free][:, None]
        eye = np.eye(len(K))

        def growth(h):          # v' = v - h M^-1 (K x + D v), x' = x + h v'
            avx, avv = -h * minv * K, eye - h * minv * D
            step = np.block([[eye + h * avx, h * avv], [avx, avv]])
            return np.abs(np.linalg.matrix_power(step, 4096)).max()
        omega, damping, _ = top_mode(ps, 60)
        h = symplectic_limit(omega, damping)
        assert growth(0.99 * h) < 1.0 and growth(1.01 * h) > 1e6, (material, scale)


def test_the_hud_writes_a_large_step_ratio_as_a_plain_number():
    """Leather at 60 Hz is 231x symplectic Euler's limit: '231x', not '2.3e+02x'."""
    scene = MassSpringClothScene({"material": "leather", "integrator": "symplectic_euler"})
    where = scene.hud_lines()[0]                         # "leather, symplectic Euler: h = ..."
    assert "e+" not in where and "231x symplectic Euler's limit" in where


def test_an_explicit_blow_up_is_explained_by_the_predicted_limit():
    """Past the limit the shell rolls back and the message names the limit in the scene's own
    terms (issue 8): how far past it the step was and the hertz x substeps that would hold."""
    from app.runner import SceneRunner
    scene = MassSpringClothScene({"material": "leather", "integrator": "symplectic_euler"})
    runner = SceneRunner(scene, rollback=True)
    runner.rebuilt()
    rollback = None
    for _ in range(60):
        rollback = runner.run(1)[1]
        if rollback:
            break
    assert rollback is not None and scene.is_finite() and scene.steps == 0
    pred = scene.limit("symplectic_euler")
    text = rollback.text()
    need = math.ceil(1 / (marginal("symplectic_euler") * pred))   # steps/s, stable band
    assert f"predicted limit ({pred * 1e3:.3g} ms)" in text and "implicit_euler" in text
    assert f"at least {need:,}" in text and "raise hertz)" not in text
    inside = MassSpringClothScene({"material": "leather", "integrator": "symplectic_euler",
                                   "hertz": 1000, "substeps": math.ceil(need / 1000)})
    assert inside.metrics()["limit_band"] == "stable"
    for _ in range(30):                   # the advice holds: inside the limit it runs
        inside.advance()
    assert inside.is_finite()
    assert MassSpringClothScene().blowup_hint() == ""     # implicit Euler: the general advice


def test_a_step_inside_the_limit_shown_at_rest_is_marginal_and_the_advice_never_repeats_it():
    """Cotton with symplectic Euler at 0.96x the limit shown at rest (hertz 60, substeps 28): the
    cloth shears as it falls, its limit drops below the step and it blows up at ~0.5 s. The HUD
    called it 'stable'; now it says MARGINAL before the first step, PAST THE LIMIT once the
    estimate on the moving cloth drops below h, and the advice after the blow-up asks for more
    steps per second than the 1,680 that failed (it asked for 1,616): a step in the stable band."""
    from app.runner import SceneRunner
    scene = MassSpringClothScene({"integrator": "symplectic_euler", "hertz": 60,
                                  "substeps": 28})
    assert 0.95 < scene.dt / 28 / scene.limit("symplectic_euler") < 0.97
    assert scene.metrics()["limit_band"] == "marginal"
    assert any("MARGINAL" in line for line in scene.hud_lines())
    runner = SceneRunner(scene, rollback=True)
    bands, rollback = set(), None
    for _ in range(120):
        rollback = runner.run(1)[1]
        if rollback:
            break
        bands.add(scene.metrics()["limit_band"])
    assert rollback is not None, "0.96x the limit at rest blows up once the cloth shears"
    assert "past the limit" in bands
    pred = scene.limit("symplectic_euler")
    need = math.ceil(1 / (marginal("symplectic_euler") * pred))
    assert pred < scene.watch.rest("symplectic_euler") and need > 60 * 28
    assert f"from 1,680 to at least {need:,}" in rollback.text()
    advised = MassSpringClothScene({"integrator": "symplectic_euler", "hertz": 1000,
                                    "substeps": math.ceil(need / 1000)})
    assert advised.metrics()["limit_band"] == "stable"


def test_the_blow_up_hint_never_asks_for_more_steps_than_the_sliders_reach():
    """A cloth at the sliders' largest stiffness (1e5) needs ~62,000 steps per second with
    symplectic Euler, more than hertz x substeps can give: the hint says so and points at
    implicit Euler instead of an impossible setting."""
    scene = MassSpringClothScene({"material": "custom", "tension": 1e5, "compression": 1e5,
                                  "shear_stiffness": 1e5, "integrator": "symplectic_euler"})
    hint = scene.blowup_hint()
    assert "more than hertz x substeps reach (50,000)" in hint and "implicit_euler" in hint
    assert "at least" not in hint


def test_verlets_energy_is_reported_with_a_centred_velocity_and_does_not_climb():
    """Verlet's own velocity estimate (x' - x)/h + a h/2 made the reported energy of an undamped
    cloth climb (cotton without damping or air, h = 0.5 ms: +2.1 J over 6 s on the default
    cloth); the energy is now taken one step back with the centred velocity (x_n+1 - x_n-1)/2h,
    which swings about 0 instead (within 0.24 J over those 6 s)."""
    s = MassSpringClothScene({"integrator": "verlet", "hertz": 1000, "substeps": 2,
                              "damping": False, "air": False, "rows": 10, "cols": 10})
    c = s.cloth
    centred, forward = [], []
    for _ in range(3000):
        s.advance()
        centred.append(c.energy() / JOULE)
        back, c._verlet_back = c._verlet_back, None     # the estimate it used to report
        forward.append(c.energy() / JOULE)
        c._verlet_back = back
    assert min(forward) >= 0.0 and max(forward) > 2e-4          # above 0 all along, climbing
    assert max(abs(e) for e in centred) < 0.3 * max(forward)
    assert min(centred) < 0.0 < max(centred)                               # swings about 0


def run_from(material, integrator, fraction, fling, seconds=1.5):
    """The default cloth with `integrator` at `fraction` x the limit the HUD shows at the start,
    from rest or flung (the bottom-middle particle dragged 500 px in 0.2 s, then dropped).
    Returns (scene, the band shown at the start, energies after the start or the drop (J)), or
    None if the step needs more steps per second than hertz x substeps reach, or a frame of such
    steps is refused by the scene's budget (leather with midpoint or RK4: ~100-145 ms a frame)."""
    probe = MassSpringClothScene({"material": material, "integrator": integrator})
    limit = probe.limit(integrator)
    if limit is None:
        return None
    need = math.ceil(1.0 / (fraction * limit))
    sub = next((k for k in range(1, 51) if math.ceil(need / k) <= 1000), None)
    if sub is None:
        return None
    try:
        s = MassSpringClothScene({"material": material, "integrator": integrator,
                                  "hertz": math.ceil(need / sub), "substeps": sub})
    except ParamError:      # the window's frame budget refuses it: no one can run this step
        return None
    band = s.metrics()["limit_band"]
    c = s.cloth
    k = (c.rows - 1) * c.cols + c.cols // 2
    x0, y0 = c.ps.x[k]
    from app.scene import InputEvent
    events = [] if not fling else (
        [(0.0, InputEvent("mouse_down", (x0, y0), 1))]
        + [(0.02 * i, InputEvent("mouse_move", (x0 + 30 * i, y0 - 40 * i))) for i in range(1, 11)]
        + [(0.2, InputEvent("mouse_up", (x0 + 300, y0 - 400), 1))])
    energy = []
    while s.time < seconds - 1e-9:
        while events and events[0][0] <= s.time + 1e-9:
            s.handle_event(events.pop(0)[1])
        s.advance()
        if not s.is_finite():
            break
        if not events:
            energy.append(c.energy() / JOULE)
    return s, band, energy


@pytest.mark.slow
@pytest.mark.parametrize("fling", [False, True])
@pytest.mark.parametrize("integrator", [n for n, i in INTEGRATORS.items() if i.explicit])
@pytest.mark.parametrize("material", list(MATERIALS))
def test_a_step_in_the_stable_band_neither_blows_up_nor_gains_energy(material, integrator, fling):
    """The HUD's 'stable' band holds: 0.95 x marginal() x the limit shown at the start, from rest
    and from a fling, 1.5 s: finite, and the energy's peak in the second half of the run no
    higher than in the first (steps beyond 50,000 per second, which the sliders cannot set, and
    settings the frame budget refuses are skipped). 42 runs + 8 skipped."""
    out = run_from(material, integrator, 0.95 * marginal(integrator), fling)
    if out is None:
        pytest.skip("no reachable step (past 50,000 steps a second, or refused by the budget)")
    s, band, energy = out
    assert band == "stable"
    assert s.is_finite(), f"blew up at t = {s.time:.2f} s"
    half = len(energy) // 2
    assert max(energy[half:]) <= max(energy[:half]) + 0.01 * max(abs(e) for e in energy)
    if not fling:      # from rest the energy only falls; forward Euler's own O(h) error gains
        # 1/2 m g^2 h^2 a step while the cloth falls freely: 1e-4 of the energy released here
        assert max(energy) <= 1e-3 * max(abs(e) for e in energy)


def test_rubber_falling_at_half_its_limit_is_stable_and_at_four_fifths_is_not():
    """The band's two sides on the cloth whose limit falls most as it drapes (rubber stretches
    ~60 %: its symplectic Euler limit falls to 0.62x of the rest value): at 0.48x the limit shown
    at the start the HUD says stable and the fall stays calm; at 0.8x it said marginal, and the
    energy climbs above the start's (+4.4e3 J measured by 1.5 s)."""
    s, band, energy = run_from("rubber", "symplectic_euler", 0.48, False, seconds=0.6)
    assert band == "stable" and s.is_finite() and max(energy) <= 1e-9
    s, band, energy = run_from("rubber", "symplectic_euler", 0.8, False, seconds=0.6)
    assert band == "marginal" and (not s.is_finite() or max(energy) > 1.0)


def test_both_step_limits_are_written_in_ms_on_screen():
    """The plot picker and the strip showed step_limit_h as a bare '0.000619' beside
    explicit_limit_h's '0.6191 ms': a step on screen is in ms, both of them."""
    s = MassSpringClothScene({"rows": 6, "cols": 6, "integrator": "symplectic_euler",
                              "hertz": 1000})
    s.step(s.dt)
    m = s.metrics()
    assert m["step_limit_h"] is not None and m["step_limit_h"] < 0.01          # seconds in JSON
    for name in ("explicit_limit_h", "step_limit_h"):
        text = s.shown(name, m[name])
        assert text.endswith(" ms") and abs(float(text.split()[0]) - m[name] * 1e3) \
            <= 1e-3 * m[name] * 1e3, (name, text)


def stiff_corner(tolerance: float):
    """The sliders' stiffest corner (issue 27): tension = compression = 1e5, mass 0.001, 60 Hz,
    a damped cloth from rest, run 1.5 s; its energies (J) over the run and the HUD's lines."""
    from scenes.mass_spring_cloth import JOULE, MassSpringClothScene
    scene = MassSpringClothScene({"tension": 1e5, "compression": 1e5, "mass": 0.001,
                                  "cg_tolerance": tolerance})
    start = scene.cloth.energy() / JOULE
    energies = []
    for _ in range(90):
        scene.advance()
        energies.append(scene.cloth.energy() / JOULE)
    return start, energies, [str(line) for line in scene.hud_lines()]


def test_implicit_euler_at_the_stiffest_corner_drains_energy_solved_exactly_and_says_when_not():
    """Lesson plan 2.3 ("it cannot blow up, and it pays by draining energy") at the sliders'
    stiffest corner: solved exactly (cg_tolerance 1e-10) the cloth never climbs more than
    0.01 J above its start (measured: +0.004 J at the peak) and ends below it; at the default
    cg_tolerance 1e-2 the loose solve adds energy (measured: +0.09 J at 5 s, +3.6 J in one run
    reported), and the HUD says it is the solve, not physics. Bounds and signs, not values:
    the loose run's gain depends on rounding."""
    start, energies, lines = stiff_corner(1e-10)
    assert max(energies) - start < 0.01 and energies[-1] < start, (start, max(energies))
    assert not any("above its start" in line for line in lines), lines
    start, energies, lines = stiff_corner(1e-2)
    if energies[-1] - start > 0.01:                # the loose solve gained: the HUD says why
        assert any("above its start  |  not physics: the solve" in line for line in lines), lines
    else:                                          # it did not gain here: nothing is said
        assert not any("above its start" in line for line in lines), lines
