"""The fixed-timestep clock: accumulator, frame cap, pause, single step, slow motion keeps dt."""

import pytest

from app.loop import SLOW_MOTION, FixedStepClock

DT = 1 / 60


def test_accumulator_runs_whole_steps_and_keeps_the_remainder():
    clock = FixedStepClock()
    assert clock.steps_for_frame(DT * 2.5, DT) == 2
    assert clock.accumulator == pytest.approx(DT * 0.5)
    assert clock.steps_for_frame(DT * 0.6, DT) == 1      # 0.5 + 0.6 = 1.1 steps
    assert clock.accumulator == pytest.approx(DT * 0.1)


def test_real_time_is_followed_over_many_uneven_frames():
    clock = FixedStepClock()
    frames = [0.010, 0.023, 0.017, 0.005, 0.030] * 40
    steps = sum(clock.steps_for_frame(f, DT) for f in frames)
    assert steps == int(sum(frames) / DT + 1e-9)


def test_frame_cap_drops_the_backlog_instead_of_spiralling():
    clock = FixedStepClock(max_steps_per_frame=8)
    assert clock.steps_for_frame(2.0, DT) == 8          # a 2 s hitch asks for 120 steps
    assert clock.accumulator == 0.0
    assert clock.dropped_steps == 112
    assert clock.steps_for_frame(DT, DT) == 1           # and the next frame is normal again


def test_pause_runs_nothing_and_single_step_runs_exactly_one():
    clock = FixedStepClock()
    clock.toggle_pause()
    assert clock.steps_for_frame(1.0, DT) == 0
    clock.single_step()
    assert clock.steps_for_frame(1.0, DT) == 1
    assert clock.steps_for_frame(1.0, DT) == 0
    clock.toggle_pause()
    assert clock.steps_for_frame(DT, DT) == 1


def test_single_step_while_running_pauses():
    clock = FixedStepClock()
    clock.single_step()
    assert clock.paused
    assert [clock.steps_for_frame(0.5, DT) for _ in range(3)] == [1, 0, 0]


@pytest.mark.parametrize("index", range(len(SLOW_MOTION)))
def test_slow_motion_scales_simulated_time_not_dt(index):
    clock = FixedStepClock()
    for _ in range(index):
        clock.slower()
    assert clock.slow_motion == SLOW_MOTION[index]
    steps = sum(clock.steps_for_frame(DT, DT) for _ in range(240))
    assert steps == pytest.approx(240 * SLOW_MOTION[index], abs=1)


def test_slow_motion_stops_at_both_ends():
    clock = FixedStepClock()
    for _ in range(10):
        clock.slower()
    assert clock.slow_motion == 0.125
    for _ in range(10):
        clock.faster()
    assert clock.slow_motion == 1.0
