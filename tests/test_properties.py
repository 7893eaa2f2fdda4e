"""Property-based tests (hypothesis) of the shell's boundaries: whatever a user types or a file
holds, the answer is a value in range or a one-line refusal, never a crash."""

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from app.headless import InputFileError, parse_events
from app.loop import FixedStepClock
from app.scene import Param, ParamError

PARAMS = [Param("n", 5, int, 1, 100), Param("x", 0.5, float, -2.0, 3.5),
          Param("mode", "a", str, choices=("a", "b")), Param("flag", True, bool)]
anything = st.one_of(st.text(max_size=20), st.integers(), st.floats(allow_nan=True),
                     st.booleans(), st.none(), st.lists(st.integers(), max_size=2))


@settings(max_examples=150, deadline=None)
@given(prm=st.sampled_from(PARAMS), value=anything)
def test_a_param_gives_a_value_in_range_or_a_one_line_refusal(prm, value):
    try:
        parsed = prm.parse(value)
    except ParamError as e:
        assert "\n" not in str(e) and prm.name in str(e) and "accepted" in str(e)
        return
    if prm.kind in (int, float):
        assert isinstance(parsed, prm.kind) and not isinstance(parsed, bool)
        assert math.isfinite(parsed) and prm.lo <= parsed <= prm.hi
    elif prm.choices:
        assert parsed in prm.choices
    else:
        assert isinstance(parsed, bool)


json_value = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(), st.floats(), st.text(max_size=8)),
    lambda inner: st.one_of(st.lists(inner, max_size=3),
                            st.dictionaries(st.sampled_from(["t", "type", "pos", "button", "key"]),
                                            inner, max_size=5)),
    max_leaves=12)
event = st.fixed_dictionaries({
    "t": st.one_of(st.floats(), st.integers(-1, 5), st.text(max_size=3)),
    "type": st.sampled_from(["mouse_down", "mouse_up", "mouse_move", "key_down", "key_up", "x"]),
}, optional={"pos": st.lists(st.one_of(st.floats(), st.integers()), max_size=3),
             "button": st.one_of(st.integers(-1, 4), st.booleans(), st.text(max_size=2)),
             "key": st.one_of(st.text(max_size=3), st.integers())})


@settings(max_examples=150, deadline=None)
@given(data=st.one_of(json_value, st.lists(event, max_size=4)))
def test_any_input_document_gives_sorted_valid_events_or_a_one_line_refusal(data):
    try:
        events = parse_events(data, "test")
    except InputFileError as e:
        assert "\n" not in str(e)
        return
    assert [e.t for e in events] == sorted(e.t for e in events)
    for e in events:
        assert math.isfinite(e.t) and e.t >= 0
        if e.kind.startswith("mouse"):
            assert all(math.isfinite(v) for v in e.pos)
        else:
            assert e.key


@settings(max_examples=100, deadline=None)
@given(frames=st.lists(st.floats(0, 2.0), max_size=60), hertz=st.integers(1, 1000),
       cap=st.integers(1, 16))
def test_the_clock_never_exceeds_its_cap_and_never_loses_track(frames, hertz, cap):
    dt = 1.0 / hertz
    clock = FixedStepClock(max_steps_per_frame=cap)
    run = capped = 0
    for f in frames:
        dropped_before = clock.dropped_steps
        n = clock.steps_for_frame(f, dt)
        run += n
        capped += clock.dropped_steps > dropped_before
        assert 0 <= n <= cap
        assert -1e-9 <= clock.accumulator < dt + 1e-9
    # Real time is simulated or still waiting in the accumulator, except what the cap dropped:
    # at most the dropped whole steps plus the fraction of a step of each capped frame.
    lost = sum(frames) - (run * dt + clock.accumulator)
    assert -1e-6 <= lost <= (clock.dropped_steps + capped) * dt + 1e-6
    if capped == 0:
        assert abs(lost) <= 1e-6
