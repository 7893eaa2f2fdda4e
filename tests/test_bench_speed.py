"""The benchmarks of issue 28 run quickly and report what they promise (no timing is asserted:
speed belongs to `python -m app bench`)."""

import math

import pytest

from app.bench import Report


def test_bench_frames_times_physics_drawing_and_the_whole_frame(tmp_path):
    from app.bench.frames import BUDGET_MS, run
    result = run(Report(str(tmp_path), quick=True))
    assert len(result["cases"]) == 6 and result["size"] == [1920, 1080]
    for case in result["cases"]:
        assert case["budget_ms"] == BUDGET_MS[case["panes"]]
        parts = case["physics_ms"] + case["draw_ms"]
        assert all(math.isfinite(case[k]) and case[k] >= 0 for k in
                   ("physics_ms", "draw_ms", "frame_ms", "frame_spread_ms"))
        assert case["frame_ms"] >= 0.5 * parts          # medians of sums, roughly the sum
        assert case["in_time"] == (case["frame_ms"] <= case["budget_ms"])


def test_the_pymunk_cost_table_compares_every_pymunk_scene_with_a_bare_loop(tmp_path):
    from app.bench.pymunk_cost import run
    result = run(Report(str(tmp_path), quick=True))
    names = " ".join(s["scene"] for s in result["scenes"])
    for scene in ("falling_balls", "newtons_cradle", "pivoting_l", "double_pendulum", "asleep"):
        assert scene in names
    assert all(s["ratio"] == s["lab_ms"] / s["bare_ms"] > 0 for s in result["scenes"])
    # each round's own lab/bare, its pair measured side by side: as many as rounds, all positive,
    # and the 'rounds' column's middle half of them
    for s in result["scenes"]:
        each = s["ratio_rounds"]
        assert len(each) == s["rounds"] and min(each) > 0
        assert min(each) <= s["ratio_q1"] <= s["ratio_q3"] <= max(each)
    # the scenes whose balls come and go, also over a long run (blocks taking turns): the total
    # times' ratio, the lab's own cost a step, one ratio a block
    runs = {s["scene"].split()[0]: s.get("long_run") for s in result["scenes"]}
    assert set(k for k, v in runs.items() if v) == {"falling_balls", "pivoting_l"}
    for name in ("falling_balls", "pivoting_l"):
        r = runs[name]
        assert r["steps"] == 60 and len(r["block_ratios"]) == r["steps"] // r["block"] == 2
        assert r["ratio"] == pytest.approx(r["lab_ms"] / r["bare_ms"])
        assert r["own_us"] == pytest.approx((r["lab_ms"] - r["bare_ms"]) * 1e3)
        assert min(r["block_ratios"]) > 0 and r["lab_ms"] > 0 and r["bare_ms"] > 0
    # one verdict: those two by their long run, the others by the table; the double pendulum
    # with its ghost (a second simulation, not bookkeeping) named, not judged
    from app.bench.pymunk_cost import GHOST_ON
    verdict = result["verdict"]
    judged = {s["scene"]: (s["long_run"]["ratio"] if "long_run" in s else s["ratio"])
              for s in result["scenes"] if s["scene"] != GHOST_ON}
    assert verdict["not_judged"] == [GHOST_ON] and GHOST_ON in verdict["sentence"]
    assert {name for name, _, _ in verdict["not_within"]} == {
        name for name, ratio in judged.items() if ratio > 1.5}
    assert verdict["met"] == (not verdict["not_within"])
    assert ("NOT met" in verdict["sentence"]) == (not verdict["met"])


def test_the_cloth_is_compared_with_c_when_a_compiler_is_there(tmp_path):
    from app.bench import cloth_c
    result = cloth_c.run(Report(str(tmp_path), quick=True))
    assert [e["n"] for e in result["sizes"]] == [32, 64]
    if cloth_c.compiler() is None:
        assert "numpy_vs_scalar_32" not in result
    else:
        assert result["numpy_vs_scalar_32"] > 0 and result["numpy_vs_simd_64"] > 0


def test_the_c_step_is_the_cloths_step():
    """The C reference solves the same rods: one step from the same state lands where the
    cloth's own step does (to float32 rounding)."""
    import numpy as np
    import tempfile
    from app.bench import cloth_c
    cc = cloth_c.compiler()
    if cc is None:
        return
    with tempfile.TemporaryDirectory() as tmp:
        libs = cloth_c.build(cc, tmp)
        for lib in libs.values():
            cloth = cloth_c.make_cloth(16)
            step = cloth_c.c_stepper(lib, cloth, 1 / 60)
            step()
            cloth.step(1 / 60)
            x_c = step.keep[0]
            assert np.allclose(x_c, cloth.x, atol=1e-2)


def test_the_largest_mass_spring_cloth_table_runs(tmp_path):
    from app.bench.mass_spring_big import run
    result = run(Report(str(tmp_path), quick=True))
    assert [e["n"] for e in result["sizes"]] == [32, 64]
    assert result["limited_by"] in ("the CG solve", "the forces and the matrix")


def test_an_interrupted_compile_leaves_no_linker_behind(tmp_path):
    # once (hostile run, seed 27): Ctrl-C during `bench cloth` left cc's collect2 and ld running
    # after the lab had exited; the compiler now runs in a group of its own, ended whole
    import signal
    import time
    import pytest
    from app.bench.cloth_c import compile_c
    pidfile = tmp_path / "grandchild"
    fake_cc = tmp_path / "cc"
    fake_cc.write_text(f"#!/bin/sh\nsleep 30 &\necho $! > {pidfile}\nwait\n")
    fake_cc.chmod(0o755)

    def ctrl_c(sig, frame):
        raise KeyboardInterrupt
    before = signal.signal(signal.SIGALRM, ctrl_c)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        with pytest.raises(KeyboardInterrupt):
            compile_c([str(fake_cc)])
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, before)
    pid = int(pidfile.read_text())
    for _ in range(100):              # killed at once; reaped by init soon after
        try:
            with open(f"/proc/{pid}/stat") as f:
                if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                    break
        except FileNotFoundError:
            break
        time.sleep(0.02)
    else:
        pytest.fail("the compiler's child outlived the interrupted compile")


def test_the_bare_pymunk_loop_holds_the_labs_bodies_step_by_step():
    """`bench pymunk`'s yardstick: the bare loop replays the balls the lab adds and removes, at
    the same substeps, so its space holds the same bodies at the very same places (the same
    operations in the same order: pymunk is deterministic) after every step."""
    import numpy as np
    from app.bench.bare_pymunk import Replay, record
    from app.bench.bare_pymunk import counts as bare_counts
    from app.pymunk_reader import _StateReader
    from scenes import get_scene

    for name, settings in (("falling_balls", {"spawn_rate": 20}),
                           ("pivoting_l", {"spawn_rate": 20})):
        def build():
            return get_scene(name)(settings)
        schedule = record(build, 240)
        lab, bare = build(), Replay(build(), schedule)
        added, removed = bare_counts(schedule)
        assert added >= 40 and removed >= 3, (name, added, removed)
        read_lab, read_bare = _StateReader(), _StateReader()
        counts = set()
        for _ in range(240):
            lab.advance()
            bare.run(1)
            ids_lab, rows_lab = read_lab.read(lab.space)
            ids_bare, rows_bare = read_bare.read(bare.space)
            assert len(lab.space.bodies) == len(bare.space.bodies)
            assert len(ids_lab) == len(ids_bare)
            assert np.array_equal(rows_lab, rows_bare)
            counts.add(len(lab.balls))
        assert len(counts) > 10          # balls came and went while they were compared


def test_the_bare_loop_numbers_each_ball_once_over_a_long_run():
    """record() numbers each ball by the id of its Body. A ball removed and freed left its id to
    the next new Body, which took over its number: from then on a recorded removal named
    another ball, and the replay removed the wrong one or failed (KeyError within 1,200 steps
    of either scene before the fix). The bodies are held while recording; after a long run
    the bare space still holds the lab's bodies at the lab's places."""
    import numpy as np
    from app.bench.bare_pymunk import Replay, record
    from app.bench.bare_pymunk import counts as bare_counts
    from app.pymunk_reader import _StateReader
    from scenes import get_scene

    for name in ("falling_balls", "pivoting_l"):
        def build():
            return get_scene(name)({"spawn_rate": 20})
        schedule = record(build, 1200)
        assert bare_counts(schedule)[1] >= 20, name       # many balls left, many ids freed
        lab, bare = build(), Replay(build(), schedule)
        for _ in range(1200):
            lab.advance()
            bare.run(1)
        rows_lab = _StateReader().read(lab.space)[1]
        rows_bare = _StateReader().read(bare.space)[1]
        assert rows_lab.shape == rows_bare.shape and np.array_equal(rows_lab, rows_bare), name


def test_the_instruction_counts_say_so_when_valgrind_is_missing(tmp_path, monkeypatch):
    import shutil

    from app.bench import pymunk_ir
    from app.bench.pymunk_ir import instructions
    assert pymunk_ir.collected("==1== Events    : Ir\n==1== Collected : 12345\n") == 12345
    with pytest.raises(RuntimeError, match="no count"):
        pymunk_ir.collected("valgrind: command not found")
    monkeypatch.setattr(shutil, "which", lambda tool: None)
    said = []
    report = Report(str(tmp_path), full=True)
    report.say = said.append
    out = instructions(report, ["pymunk_cost's first case"])
    assert out.startswith("not measured: valgrind and callgrind_control not found")
    assert "not measured" in said[-1]


@pytest.mark.slow
def test_the_instruction_counts_of_a_case_are_exact_and_the_labs_larger(tmp_path):
    from app.bench import pymunk_ir
    if pymunk_ir.available():
        pytest.skip(pymunk_ir.available())
    label = "newtons_cradle (default)"
    (_, lab, bare), = pymunk_ir.per_step([label], steps=20)
    assert lab > bare > 0
    assert pymunk_ir.count(label, "bare", 20) == pymunk_ir.count(label, "bare", 20)  # exact


def test_the_at_the_line_sentence_says_a_middle_half_only_of_enough_rounds():
    # the 'rounds' column is Timing.of's quartiles, the smallest and largest of fewer than 4
    # values: --quick's 2 rounds (or 3) have no middle half to name
    from app.bench import Timing
    from app.bench.pymunk_cost import at_the_line
    for few in ([1.4, 1.6, 1.5], [1.6, 1.4]):
        t = Timing.of(few)
        assert (t.lo, t.hi) == (1.4, 1.6)
    t = Timing.of([1.1, 1.9, 1.3, 1.4, 1.5, 1.6, 1.7, 1.2, 1.8])
    assert (t.lo, t.hi) == pytest.approx((1.3, 1.7))
    for rounds in (2, 3):
        few = at_the_line(["pivoting_l"], rounds)
        assert "middle half" not in few and "interquartile" not in few
        assert "smallest and largest" in few and "pivoting_l" in few
    assert "middle half" in at_the_line(["pivoting_l"], 9)


def test_the_goal_verdict_says_what_a_reader_could_misread():
    """The verdict's sentence names a ratio just over the goal with the digits that show it over
    (1.504, not '1.50' against a goal of 1.5), names the scenes judged by the table whose rounds
    lie on both sides of the goal (another run may judge them otherwise), and says how long the
    long run was (60 steps with --quick, not the 40 s of LONG_STEPS)."""
    from app.bench.pymunk_cost import goal_verdict
    rows = [{"scene": "pile", "ratio": 1.504, "ratio_q1": 1.26, "ratio_q3": 1.79},
            {"scene": "cradle", "ratio": 1.41, "ratio_q1": 1.30, "ratio_q3": 1.62},
            {"scene": "calm", "ratio": 1.2, "ratio_q1": 1.1, "ratio_q3": 1.3},
            {"scene": "balls", "ratio": 1.2, "ratio_q1": 1.1, "ratio_q3": 1.3,
             "long_run": {"ratio": 1.8, "steps": 60}}]
    verdict = goal_verdict(rows)
    said = verdict["sentence"]
    assert not verdict["met"] and [n for n, _, _ in verdict["not_within"]] == ["pile", "balls"]
    assert "pile 1.504" in said and "1.50 " not in said
    assert [n for n, _ in verdict["at_the_line"]] == ["pile", "cradle"]
    assert "at the line" in said.lower() and "cradle" in said and "calm" not in said
    assert "60 steps" in said
    from app.bench.pymunk_cost import GHOST_ON
    ghost = goal_verdict(rows[2:3] + [{"scene": GHOST_ON, "ratio": 3.2, "ratio_q1": 3.1,
                                       "ratio_q3": 3.3}])
    assert ghost["met"] and ghost["not_within"] == [] and ghost["not_judged"] == [GHOST_ON]
    assert ghost["sentence"].startswith("Goal, the lab's step at most 1.5 x")
    assert "MET" in ghost["sentence"] and "second simulation" in ghost["sentence"]


def test_each_rounds_timed_blocks_start_after_the_garbage_of_the_rounds_before_is_collected(
        monkeypatch):
    """side_by_side collects the garbage of earlier rounds (their scenes and spaces: a full
    collection of four falling_balls scenes took 9-11 ms) before a round's two builds (whose
    steps warm the caches again), so no timed block pays for the harness's own garbage. The
    order of the collections, the builds and the clock's reads is recorded, round by round, and
    the last round's pair is garbage by the collection (weak references to it are dead)."""
    from app.bench import pymunk_cost as pc
    from scenes import get_scene

    import weakref

    order, built, alive = [], [], []

    def build():
        order.append("build")
        scene = get_scene("falling_balls")({"spawn_rate": 20})
        built.append(weakref.ref(scene))
        return scene

    def collect(*args):
        real_collect(*args)
        order.append("collect")
        alive.append(sum(ref() is not None for ref in built))

    schedule = pc.record(build, pc.WARM + 2 * 3)
    order.clear()
    real_clock, real_collect = pc.time.process_time, pc.gc.collect
    monkeypatch.setattr(pc.time, "process_time", lambda: order.append("clock") or real_clock())
    monkeypatch.setattr(pc.gc, "collect", collect)
    pc.side_by_side(build, schedule, 3, 2, 3)
    rounds = "".join("b" if o == "build" else "c" if o == "collect" else "t" for o in order)
    assert rounds == ("c" + "bb" + "t" * 8) * 3, rounds
    assert alive == [0, 0, 0], alive          # every scene built before a collection is gone
