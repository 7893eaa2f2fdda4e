"""Double pendulum: pymunk keeps the energy, agrees with the exact solution when the motion is
regular, parts from it when it is chaotic; the reference itself is right; a drag restarts it."""

import math

import numpy as np
import pytest

from app.physics.double_pendulum_ode import DoublePendulumODE
from app.scene import InputEvent, ParamError
from scenes.double_pendulum import PIVOT, DoublePendulumScene


def run(scene: DoublePendulumScene, seconds: float) -> DoublePendulumScene:
    for _ in range(round(seconds * scene.p["hertz"])):
        scene.advance()
    return scene


def test_energy_drift_under_one_percent_over_a_minute_and_chaos_parts_the_two():
    scene = run(DoublePendulumScene(), 60.0)       # the defaults: released high, chaotic
    m = scene.metrics()
    assert m["energy_drift_max"] < 0.01
    assert abs(m["energy_drift"]) < 0.01
    assert m["pin_error"] < 0.5
    # Chaos: the engine and the exact solution part (10 px) within the minute, not at once.
    assert 1.0 < m["divergence_time"] < 60.0
    assert m["reference_divergence"] > 10.0


def test_small_release_stays_with_the_reference_for_ten_seconds():
    scene = DoublePendulumScene({"angle1": 10.0, "angle2": 10.0})
    worst = 0.0
    for _ in range(10 * scene.p["hertz"]):
        scene.advance()
        worst = max(worst, scene.metrics()["reference_divergence"])
    assert worst < 3.0
    assert scene.metrics()["divergence_time"] == -1.0


def test_pymunk_default_soft_pins_bleed_energy():
    scene = run(DoublePendulumScene({"error_bias": (1 - 0.1) ** 60, "reference": False}), 10.0)
    assert scene.metrics()["energy_drift"] < -0.01


def test_reference_keeps_energy_and_matches_the_small_angle_normal_modes():
    # Equal masses and lengths: the slow normal mode has omega^2 = (2 - sqrt 2) g / l and the
    # two angles in the ratio theta2 / theta1 = sqrt 2. Started in it, it stays in it.
    g, l = 900.0, 160.0
    eps = 1e-3
    ode = DoublePendulumODE(l, l, 1.0, 1.0, g, (eps, math.sqrt(2) * eps, 0.0, 0.0))
    e0 = ode.energy()
    omega = math.sqrt((2 - math.sqrt(2)) * g / l)
    period = 2 * math.pi / omega
    ode.advance(period, 2000)
    assert ode.state[0] == pytest.approx(eps, rel=1e-4)
    assert ode.state[1] == pytest.approx(math.sqrt(2) * eps, rel=1e-4)
    assert ode.energy() == pytest.approx(e0, rel=1e-8)
    # A chaotic release keeps its energy to ~1e-9 with the reference's tiny step.
    ode = DoublePendulumODE(l, l, 1.0, 2.0, g, (2.0, 2.5, 0.0, 0.0))
    e0 = ode.energy()
    ode.advance(10.0, 12000)
    assert abs(ode.energy() / e0 - 1) < 1e-8


def test_set_from_cartesian_round_trips():
    ode = DoublePendulumODE(100.0, 80.0, 1.0, 1.0, 900.0, (0.7, -2.1, 1.3, -0.4))
    p1, p2 = ode.positions(PIVOT)
    # velocities by finite differences of the positions (central, tiny h)
    h = 1e-6
    t1, t2, w1, w2 = ode.state
    a = DoublePendulumODE(100.0, 80.0, 1.0, 1.0, 900.0, (t1 + w1 * h, t2 + w2 * h, 0, 0))
    b = DoublePendulumODE(100.0, 80.0, 1.0, 1.0, 900.0, (t1 - w1 * h, t2 - w2 * h, 0, 0))
    v = (a.positions(PIVOT) - b.positions(PIVOT)) / (2 * h)
    copy = DoublePendulumODE(100.0, 80.0, 1.0, 1.0, 900.0)
    copy.set_from_cartesian(PIVOT, p1, v[0], p2, v[1])
    assert np.allclose(copy.state, ode.state, atol=1e-6)


def test_letting_go_after_a_drag_restarts_the_reference():
    scene = run(DoublePendulumScene(), 9.0)
    assert scene.metrics()["divergence_time"] > 0      # they have parted
    tip = scene.bobs[1].position
    scene.handle_event(InputEvent("mouse_down", tuple(tip), 1))
    assert scene.mouse_joint is not None
    for i in range(30):
        scene.handle_event(InputEvent("mouse_move", (tip[0] + i, tip[1] - i)))
        scene.advance()
    scene.handle_event(InputEvent("mouse_up", (tip[0] + 30, tip[1] - 30), 1))
    m = scene.metrics()
    assert m["divergence_time"] == -1.0
    assert m["reference_divergence"] < 0.05     # the pins' length error, no more
    assert m["energy_drift"] == pytest.approx(0.0)
    run(scene, 0.5)
    assert scene.metrics()["reference_divergence"] < 3.0


def test_reference_off_is_not_integrated():
    scene = DoublePendulumScene({"reference": False})
    state = scene.ode.state
    run(scene, 1.0)
    assert scene.ode.state == state
    m = scene.metrics()
    assert m["reference_divergence"] == -1.0 and m["divergence_time"] == -1.0
    scene.set("reference", True)                      # switched on: starts from the engine
    assert scene.metrics()["reference_divergence"] < 0.05


def test_two_runs_hash_the_same():
    a = run(DoublePendulumScene(), 2.0)
    b = run(DoublePendulumScene(), 2.0)
    assert a.state_hash() == b.state_hash()


@pytest.mark.parametrize("key,value", [("angle1", 181), ("length1", 0), ("length2", -5),
                                       ("mass1", 0), ("mass2", float("inf")), ("error_bias", -1),
                                       ("ref_substeps", 0), ("trail_seconds", 0),
                                       ("iterations", 0), ("hertz", float("nan"))])
def test_bad_values_are_refused(key, value):
    with pytest.raises(ParamError):
        DoublePendulumScene({key: value})


def test_a_coarse_step_does_not_make_the_reference_coarse():
    # hertz 1 with one RK4 step per physics step would be a 1 s RK4 step: it is bounded to 1 ms.
    assert DoublePendulumODE.steps_for(1.0, 1) == 1000
    assert DoublePendulumODE.steps_for(1 / 120, 10) == 10          # the default: unchanged
    # Once a traceback (math.sin(inf) in the reference): now both stay finite and nothing raises.
    scene = run(DoublePendulumScene({"hertz": 1, "substeps": 1, "mass1": 0.05, "mass2": 20,
                                     "g": 5000, "error_bias": 1}), 8.0)
    assert scene.is_finite() and scene.metrics()["reference_blowup_t"] == -1.0
    scene = run(DoublePendulumScene({"hertz": 1, "ref_substeps": 1}), 5.0)
    assert scene.is_finite() and scene.metrics()["reference_blowup_t"] == -1.0


def test_a_reference_that_blows_up_is_frozen_hidden_and_reported():
    scene = run(DoublePendulumScene(), 0.5)
    scene.ode.state = (1.0, 2.0, 1e200, 1e200)     # a ghost about to overflow (w * w = inf)
    frozen = scene.ode.state
    scene.advance()                                # must not raise
    m = scene.metrics()
    assert m["reference_blowup_t"] == pytest.approx(scene.time)
    assert m["reference_divergence"] == -1.0
    assert scene.ode.state == frozen               # the last finite state, not integrated on
    assert scene.is_finite()                       # the ghost's failure is not the engine's
    assert any("reference blew up at t = " in line for line in scene.hud_lines())
    before = scene.state_hash()
    run(scene, 0.5)                                # the engine runs on
    assert scene.state_hash() != before and scene.is_finite() and scene.ode.state == frozen
    b2 = scene.bobs[1].position                    # a drag and let go restarts the ghost
    scene.handle_event(InputEvent("mouse_down", tuple(b2), 1))
    scene.handle_event(InputEvent("mouse_up", tuple(b2), 1))
    assert scene.metrics()["reference_blowup_t"] == -1.0
    assert scene.metrics()["reference_divergence"] < 0.05


def test_an_overflowing_reference_returns_false_and_keeps_its_state():
    ode = DoublePendulumODE(160, 160, 1.0, 1.0, 900.0, (1.0, 2.0, 1e200, 1e200))
    assert ode.advance(0.01, 10) is False and ode.state == (1.0, 2.0, 1e200, 1e200)
    ode = DoublePendulumODE(160, 160, 1.0, 1.0, 900.0, (1.0, 2.0, 0.0, 0.0))
    assert ode.advance(0.01, 10) is True


def test_changing_g_or_gravity_rebaselines_the_energy():
    scene = run(DoublePendulumScene(), 1.0)
    scene.set("g", 450.0)
    assert abs(scene.metrics()["energy_drift"]) < 1e-9     # at once, before the next step
    run(scene, 1.0)
    assert scene.ode.g == 450.0 and scene.space.gravity == (0.0, 450.0)
    assert abs(scene.metrics()["energy_drift"]) < 0.01
    scene.set("gravity", False)                             # the effect: off = no gravity
    assert scene.space.gravity == (0.0, 0.0)
    assert abs(scene.metrics()["energy_drift"]) < 1e-9
    run(scene, 1.0)
    assert scene.ode.g == 0.0 and abs(scene.metrics()["energy_drift"]) < 0.01
    assert scene.metrics()["energy_drift_max"] < 0.01


def test_a_rollback_while_a_bob_is_held_with_a_huge_state_does_not_raise():
    scene = DoublePendulumScene({})
    snap = scene.snapshot()
    before = scene.state_hash()
    bob = scene.bobs[1]
    scene.handle_event(InputEvent("mouse_down", tuple(bob.position), 1))
    assert scene.mouse_joint is not None
    bob.position = (1e200, 1e200)            # a blown-up state, about to be thrown away
    bob.velocity = (1e300, -1e300)
    scene.restore(snap)                      # no new release from the state thrown away
    assert scene.mouse_joint is None and scene.state_hash() == before and scene.is_finite()
    scene.handle_event(InputEvent("mouse_up", tuple(scene.bobs[1].position), 1))
    scene.advance()
    assert scene.is_finite()


def test_set_from_cartesian_with_huge_numbers_gives_no_exception():
    ode = DoublePendulumODE(100, 100, 1, 1, 900)
    ode.set_from_cartesian((0, 0), (1e200, 1e200), (1e300, 0), (3e200, 1e200), (0, 1e300))
    assert len(ode.state) == 4
