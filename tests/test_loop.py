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


# ----- the runner's step times: bounded memory (issue 14) ----------------------------------------
def test_the_median_of_step_times_is_kept_in_bounded_memory_and_stays_right():
    """SceneRunner kept every step's wall time for the headless median (~30 bytes a step: +9 MB
    over a ten-minute soak). StreamingMedian keeps the first values exactly, then a histogram:
    its memory does not grow with the run, and its median stays within half a bin (0.25 %)."""
    import tracemalloc

    import numpy as np

    from app.runner import StreamingMedian
    values = np.random.default_rng(4).lognormal(np.log(2e-4), 0.5, 50_000).tolist()
    short = StreamingMedian()
    for v in values[:1001]:
        short.add(v)
    assert short.median() == np.median(values[:1001])          # short runs: exact
    stream = StreamingMedian()
    for v in values[:StreamingMedian.EXACT + 1]:
        stream.add(v)
    tracemalloc.start()
    before = tracemalloc.get_traced_memory()[0]
    for v in values[StreamingMedian.EXACT + 1:]:
        stream.add(v)
    grown = tracemalloc.get_traced_memory()[0] - before
    tracemalloc.stop()
    assert grown < 10_000, grown                 # a list would have grown by ~1.5 MB here
    assert len(stream) == len(values) and stream.exact is None
    assert stream.median() == pytest.approx(np.median(values), rel=0.0025)


def test_a_headless_run_reports_the_median_step_time_from_the_runner():
    from app.headless import summary
    from app.runner import run_scene
    from tests.toy_scenes import Toy
    runner = run_scene(Toy(), 50)
    assert len(runner.step_times) == 50
    assert summary(runner, 1.0)["step_ms"] == pytest.approx(runner.step_times.median() * 1e3,
                                                             abs=1e-6)
    assert summary(run_scene(Toy(), 0), 1.0)["step_ms"] is None
