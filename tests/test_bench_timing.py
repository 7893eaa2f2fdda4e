"""Benchmark figures a user can trust (issue 27): every timing is a median with its spread and
repeat count; the whole sweeps are behind --full. No timing is asserted (speed belongs to the
benchmarks): these are the arithmetic and the printing."""

from __future__ import annotations

import json

from app.__main__ import main
from app.bench import Timing, _cell, median_time


def test_a_timing_is_its_median_with_the_interquartile_range_and_the_repeats():
    t = Timing.of([5.0, 1.0, 3.0, 2.0, 4.0, 100.0, 3.5])
    assert float(t) == 3.5 and t.repeats == 7 and t.lo == 2.5 and t.hi == 4.5
    ms = t * 1000                                 # scaled, it keeps its spread
    assert (float(ms), ms.lo, ms.hi, ms.repeats) == (3500.0, 2500.0, 4500.0, 7)
    assert _cell(ms) == "3500 (2500-4500, n=7)"
    assert json.dumps({"ms": ms}) == '{"ms": 3500.0}'       # JSON keeps the median
    assert Timing.of([2.0, 1.0]).lo == 1.0                   # few repeats: the extremes
    assert isinstance(median_time(lambda: None, repeats=3, warmup=0), Timing)


def test_quick_and_full_together_are_refused(capsys):
    assert main(["bench", "cloth", "--quick", "--full"]) == 2
    assert "give one" in capsys.readouterr().err


def test_the_machine_note_names_the_blas_kernels_or_says_nothing_of_them(monkeypatch):
    # which kernels OpenBLAS picked changes the pymunk ratios (app/bench blas_kernels): the
    # note names them as threadpoolctl reads them, and leaves them out when it cannot tell
    import threadpoolctl

    from app.bench import machine_note
    fake = {"user_api": "blas", "internal_api": "openblas", "version": "0.3.31",
            "architecture": "Haswell"}
    monkeypatch.setattr(threadpoolctl, "threadpool_info", lambda: [fake])
    assert ", BLAS: openblas 0.3.31, Haswell kernels" in machine_note()
    monkeypatch.setattr(threadpoolctl, "threadpool_info", lambda: [])
    assert "BLAS" not in machine_note()

    def broken():
        raise OSError("a library threadpoolctl cannot read")
    monkeypatch.setattr(threadpoolctl, "threadpool_info", broken)
    assert "BLAS" not in machine_note() and "cores" in machine_note()
