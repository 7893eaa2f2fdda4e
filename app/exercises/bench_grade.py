"""`python -m app.exercises.bench_grade [--quick] [--json]`: the time to grade a class with
`exercise grade --jobs 2` (a benchmark beside the grader: app/bench sits below app/exercises
and does not import it).

It makes STUDENTS students' folders (3 with --quick) from the answers the tests keep
(tests/exercise_answers/: right answers, wrong ones, and a hostile file for every tenth
student's verlet), each student a different mix, every exercise's file present, and grades them
exactly as `python -m app exercise grade CLASS --jobs 2` does (each file in a sandbox of its
own). It reports the wall time, the time per student and per file, and the CPU time of the
sandboxed children (their startup, Python and NumPy, is most of a short check's cost). The
figure depends on the machine and its load: it is measured here, never asserted in a test.
"""

from __future__ import annotations

import contextlib
import io
import os
import resource
import tempfile
import time
from pathlib import Path
from typing import Any

from app.bench import Report

STUDENTS = 30
JOBS = 2
ANSWERS = Path(__file__).resolve().parents[2] / "tests" / "exercise_answers"
OUT = "bench-results"
PREFIX = {"verlet": "verlet_", "constraints": "constraints_", "spring": "spring_",
          "rk4": "rk4_", "solver_interface": "solver_", "implicit_spring": "implicit_",
          "neighbour_grid": "grid_", "newtons_cradle": "cradle_",
          "double_pendulum": "pendulum_", "pivoting_l": "l_", "collisions": "collisions_"}
HOSTILE = ("verlet_kills_grader", "verlet_daemon", "verlet_fork_flood")


def make_class(folder: Path, students: int) -> int:
    """Write the students' folders; return the number of files."""
    from app.exercises import NAMES
    files = 0
    for k in range(students):
        student = folder / f"student{k:03d}"
        student.mkdir(parents=True)
        for name in NAMES:
            right = sorted((ANSWERS / "right").glob(f"{name}_*.py"))
            wrong = sorted(ANSWERS.glob(f"{PREFIX[name]}*.py"))
            pool = right + wrong
            source = pool[k % len(pool)]
            if name == "verlet" and k % 10 == 9:
                source = ANSWERS / "hostile" / f"{HOSTILE[(k // 10) % len(HOSTILE)]}.py"
            (student / f"{name}.py").write_text(source.read_text())
            files += 1
    return files


def run(report: Report) -> dict[str, Any]:
    from app.exercises.classroom import grade_class
    students = 3 if report.quick else STUDENTS
    with tempfile.TemporaryDirectory(prefix="bench-grade-") as tmp:
        folder = Path(tmp) / "class"
        files = make_class(folder, students)
        report.progress(f"grading {students} students ({files} files) with --jobs {JOBS} ...")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        with contextlib.redirect_stderr(io.StringIO()):
            code = grade_class(str(folder), JOBS)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        rows = (folder / "gradebook.csv").read_text().splitlines()[1:]
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    passed = sum(r.endswith(",PASS,") or ",PASS," in r for r in rows)
    out = {"students": students, "files": files, "jobs": JOBS, "wall_seconds": round(wall, 2),
           "seconds_per_student": round(wall / students, 3),
           "seconds_per_file": round(wall / files, 3), "children_cpu_seconds": round(cpu, 2),
           "rows": len(rows), "rows_pass": passed, "exit_code": code,
           "load_average": os.getloadavg()[0] if hasattr(os, "getloadavg") else None}
    report.table(f"grading a class: exercise grade --jobs {JOBS}",
                 ["students", "files", "wall s", "s/student", "s/file", "children CPU s",
                  "rows (PASS)", "load"],
                 [[students, files, f"{wall:.1f}", f"{wall / students:.2f}",
                   f"{wall / files:.3f}", f"{cpu:.1f}", f"{len(rows)} ({passed})",
                   f"{out['load_average']:.1f}" if out["load_average"] is not None else "-"]])
    return out


def main(argv: list[str] | None = None) -> int:
    import argparse
    import json
    import sys
    p = argparse.ArgumentParser(prog="python -m app.exercises.bench_grade",
                                description="the time to grade 30 students with --jobs 2")
    p.add_argument("--quick", action="store_true", help="3 students (a smoke run)")
    p.add_argument("--json", action="store_true", help="the numbers as JSON on stdout")
    args = p.parse_args(argv)
    from app.bench import machine_note
    report = Report(OUT, args.json, args.quick)
    report.say(machine_note())
    out = run(report)
    if args.json:
        print(json.dumps(out, indent=1))
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
