"""`python -m app exercise grade CLASS_DIR`: a whole class in one command.

CLASS_DIR holds a folder per student, each with the student's NAME.py files (a missing file is
graded as missing: 0 of its checks; a folder with none of them is not graded and is named in one
line, so a scratch folder given by mistake is not taken for a class). Every (student, exercise) is graded in a sandbox of its own
(app/exercises/sandbox.py), JOBS at once, so a student whose files crash, hang or attack loses
only their own results. What it writes (each file to a temporary name, then renamed into place):

  OUT (CLASS_DIR/gradebook.csv)   a row per student and exercise: student, exercise, passed,
                                  checks, verdict (PASS/FAIL), seed; rewritten as each student
                                  is done, so an interrupted run leaves a valid gradebook
  OUT-reports/STUDENT.txt         the student's report: every exercise's checks, hints, output
  OUT-reports/STUDENT.json        the same as data; a run finds it and does not grade that
                                  student again while their files are unchanged (resume)
  OUT-reports/STUDENT.results.json  with --gradescope: Gradescope's autograder format

Ctrl-C stops the run with one line and exit code 130; the same command resumes it.
"""

from __future__ import annotations

import csv
import hashlib
import inspect
import io
import json
import os
import signal
import sys
import threading
import time
from dataclasses import dataclass
from typing import Any, Iterator

from app.exercises import EXERCISES, base
from app.exercises.grade import CHECK_TIMEOUT, Report, grade_many
from app.outputs import one_line, shown

EXIT_INTERRUPTED = 130
FIELDS = ("student", "exercise", "passed", "checks", "verdict", "seed")


def reports_folder(out: str) -> str:
    stem, _ = os.path.splitext(out)
    return stem + "-reports"


def students_in(class_dir: str, out: str) -> list[str]:
    """The student folders: every sub-folder but hidden ones and the grader's own reports."""
    own = os.path.realpath(reports_folder(out))
    return sorted(d for d in os.listdir(class_dir)
                  if not d.startswith(".") and os.path.isdir(os.path.join(class_dir, d))
                  and os.path.realpath(os.path.join(class_dir, d)) != own)


def exercise_files() -> list[str]:
    """The file names a student's folder may hold: NAME.py for every exercise."""
    return [f"{e.name}.py" for e in EXERCISES]


def without_answers(class_dir: str, students: list[str]) -> list[str]:
    """The folders that hold none of the exercise files: not graded, named in one line (a
    scratch folder such as /tmp is not a class; `grade` refuses a folder where all are so)."""
    names = exercise_files()
    return [s for s in students
            if not any(os.path.isfile(os.path.join(class_dir, s, n)) for n in names)]


def out_among_inputs(class_dir: str, out: str, students: list[str]) -> str | None:
    """The one-line refusal of a gradebook `out` inside a student's folder (it is an input: once,
    --out class/s1/verlet.py replaced s1's answer with the gradebook); None if it is not."""
    real_out = os.path.realpath(out)
    for student in students:
        inside = os.path.realpath(os.path.join(class_dir, student))
        if real_out == inside or real_out.startswith(inside + os.sep):
            return (f"--out {shown(out)} is in the folder of student {shown(student)}, which is "
                    "graded (an input); accepted: a file outside the students' folders (default "
                    "CLASS_DIR/gradebook.csv)")
    return None


def usage_problem(folder: str, out: str, check_output_path) -> str | None:
    """The one-line refusal of `grade FOLDER --out OUT` before anything is graded or written,
    or None. `check_output_path` is the lab's check of an output option (app.cli_checks)."""
    if not folder.strip():
        return "grade needs a class folder, e.g. exercise grade class2026/"
    if not os.path.isdir(folder):
        return (f"grade: {shown(folder)} is not a folder; accepted: a folder holding a folder "
                "per student")
    if os.path.isdir(out):
        return f"--out {shown(out)} is a folder; accepted: a CSV file name"
    students = students_in(folder, out)
    problem = check_output_path(out, "--out") or out_among_inputs(folder, out, students)
    if problem:
        return problem
    if not students:
        return (f"grade: {shown(folder)} holds no student folder; accepted: a folder holding a "
                "folder per student (each with NAME.py files)")
    if len(without_answers(folder, students)) == len(students):
        return (f"grade: none of the {len(students)} folders in {shown(folder)} holds an exercise "
                "file (e.g. verlet.py); accepted: a folder holding a folder per student, each "
                "with NAME.py files (python -m app exercise list)")
    return None


def fingerprint(folder: str) -> str:
    """A hash of the student's exercise files as they are now (a changed file: graded again)."""
    h = hashlib.sha256()
    for e in EXERCISES:
        path = os.path.join(folder, f"{e.name}.py")
        h.update(e.name.encode())
        try:
            if os.path.isfile(path):
                with open(path, "rb") as f:
                    h.update(f.read(1 << 21))
        except OSError:
            h.update(b"unreadable")
    return h.hexdigest()


def write_atomic(path: str, text: str, what: str = "the grading report") -> None:
    """Write `text` to a temporary file beside `path`, then rename it into place
    (app/outputs.py): a full disk is one line (OutputError, exit code 2) and leaves the old file
    whole and no temporary file behind."""
    from app.outputs import atomic_write
    with atomic_write(path, "w", what, newline="", allow_empty=True) as f:
        f.write(text)


@dataclass
class Result:
    """One student's grades: what the gradebook and the reports are made from."""
    student: str
    seed: int | None
    fingerprint: str
    exercises: list[dict[str, Any]]          # Report.to_json() each
    text: str                                # the readable report

    def rows(self) -> list[dict[str, Any]]:
        out = []
        for r in self.exercises:
            n = sum(c["passed"] for c in r["checks"])
            out.append({"student": self.student, "exercise": r["exercise"], "passed": n,
                        "checks": len(r["checks"]), "verdict": "PASS" if r["passed"] else "FAIL",
                        "seed": "" if self.seed is None else self.seed})
        return out

    def gradescope(self, sandbox_line: str) -> dict[str, Any]:
        """Gradescope's results.json: a point per check."""
        tests = []
        for r in self.exercises:
            for c in r["checks"]:
                lines = [f"measured {c['measured'] or '-'}; needed {c['bound']}"]
                lines += [t for t in (c["error"], c["hint"] and f"hint: {c['hint']}") if t]
                tests.append({"name": f"{r['exercise']}: {c['name']}",
                              "score": 1 if c["passed"] else 0, "max_score": 1,
                              "status": "passed" if c["passed"] else "failed",
                              "output": "\n".join(lines)})
        seed = "" if self.seed is None else f" (seed {self.seed}: --seed {self.seed} repeats it)"
        return {"score": sum(t["score"] for t in tests), "max_score": len(tests),
                "output": f"{sandbox_line}{seed}", "tests": tests}


def as_result(student: str, seed: int | None, fp: str, reports: list[Report]) -> Result:
    text = []
    for r in reports:
        if r.output_bytes:
            text.append(r.output_text())
        text.append(r.text())
    return Result(student, seed, fp, [r.to_json() for r in reports], "\n\n".join(text) + "\n")


def load_result(path: str, fp: str) -> Result | None:
    """A student's result from an earlier run, if their files have not changed since."""
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        if data.get("fingerprint") != fp or data.get("exercises_graded") != [
                e.name for e in EXERCISES]:
            return None
        return Result(data["student"], data["seed"], fp, data["exercises"], data["text"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def save(result: Result, folder: str, gradescope: bool, sandbox_line: str) -> None:
    stem = os.path.join(folder, result.student)
    write_atomic(stem + ".txt", result.text)
    if gradescope:
        write_atomic(stem + ".results.json", json.dumps(result.gradescope(sandbox_line),
                                                        indent=1))
    write_atomic(stem + ".json", json.dumps({
        "student": result.student, "seed": result.seed, "fingerprint": result.fingerprint,
        "exercises_graded": [e.name for e in EXERCISES], "exercises": result.exercises,
        "text": result.text}))


def gradebook_text(results: list[Result]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, FIELDS, lineterminator="\n")
    w.writeheader()
    for r in sorted(results, key=lambda r: r.student):
        w.writerows(r.rows())
    return buf.getvalue()


class Progress:
    """A bar with the time remaining on a terminal (tqdm); a plain line per student otherwise."""

    def __init__(self, total: int, done: int, students: int):
        self.students, self.finished = students, 0
        self.bar = None
        if sys.stderr.isatty():
            try:
                from tqdm import tqdm
                tqdm.monitor_interval = 0      # no monitor thread: the grader forks
                self.bar = tqdm(total=total, initial=done, unit="file", desc="grading",
                                file=sys.stderr, dynamic_ncols=True)
            except ImportError:
                pass

    def step(self) -> None:
        if self.bar is not None:
            self.bar.update(1)

    def student(self, result: Result, resumed: bool = False) -> None:
        self.finished += 1
        passed = sum(e["passed"] for e in result.exercises)
        line = (f"{one_line(result.student)}: {passed}/{len(result.exercises)} exercises pass"
                f"{' (graded before: files unchanged)' if resumed else ''} "
                f"[{self.finished}/{self.students} students]")
        if self.bar is not None:
            self.bar.write(line, file=sys.stderr)
        else:
            print(line, file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _grade_many(jobs, timeout, parallel, seed) -> Iterator[Report]:
    """grade_many with the run's seed where it takes one (the seed option is another branch's:
    either order of merging works)."""
    if "seed" in inspect.signature(grade_many).parameters:
        return grade_many(jobs, timeout, None, parallel, seed=seed)
    return grade_many(jobs, timeout, None, parallel)


class _CtrlC:
    """Ctrl-C while a class is graded: raised as KeyboardInterrupt and also remembered. Python
    drops a KeyboardInterrupt raised inside some of its own hooks (at a fork: "Exception ignored
    in ..."); the remembered one is raised again at the next student's report."""

    def __init__(self) -> None:
        self.seen = False

    def __call__(self, sig, frame) -> None:
        self.seen = True
        raise KeyboardInterrupt

    def check(self) -> None:
        if self.seen:
            raise KeyboardInterrupt


def _few(names: list[str], most: int = 5) -> str:
    """At most `most` names, then how many more (one line, whatever the class's size)."""
    shown_names = ", ".join(shown(n) for n in names[:most])
    return shown_names + (f" and {len(names) - most} more" if len(names) > most else "")


def grade_class(class_dir: str, jobs: int, out: str | None = None, gradescope: bool = False,
                timeout: float = CHECK_TIMEOUT, seed: int | None = None) -> int:
    """Grade every student of `class_dir`; return 0 (done) or 130 (interrupted: Ctrl-C)."""
    out = out or os.path.join(class_dir, "gradebook.csv")
    ctrl_c = _CtrlC()
    main_thread = threading.current_thread() is threading.main_thread()
    before = signal.signal(signal.SIGINT, ctrl_c) if main_thread else None
    try:
        return _grade_class(class_dir, jobs, out, gradescope, timeout, seed, ctrl_c)
    except KeyboardInterrupt:        # before the first student or after the last: still one line
        print(f"interrupted (in {one_line(out)}); the same command goes on from there",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        if before is not None:
            signal.signal(signal.SIGINT, before)


def _grade_class(class_dir: str, jobs: int, out: str, gradescope: bool, timeout: float,
                 seed: int | None, ctrl_c: _CtrlC) -> int:
    from app.exercises import sandbox
    folder = reports_folder(out)
    os.makedirs(folder, exist_ok=True)
    if seed is None and hasattr(base, "new_seed"):
        seed = base.new_seed()
    folders = students_in(class_dir, out)
    empty = without_answers(class_dir, folders)
    students = sorted(set(folders) - set(empty))
    line = sandbox.protections().line()
    print(line, file=sys.stderr)
    if empty:
        print(f"not graded: {len(empty)} of {len(folders)} folders hold none of the exercise "
              f"files: {_few(empty)}", file=sys.stderr)
    results: dict[str, Result] = {}
    replaced = os.path.exists(out)         # the summary says so (a run that goes on, too)
    todo = []
    for s in students:
        fp = fingerprint(os.path.join(class_dir, s))
        earlier = load_result(os.path.join(folder, f"{s}.json"), fp)
        if earlier is not None:
            results[s] = earlier
        else:
            todo.append((s, fp))
    progress = Progress(len(students) * len(EXERCISES), len(results) * len(EXERCISES),
                        len(students))
    for s in sorted(results):
        progress.student(results[s], resumed=True)
    start = time.monotonic()
    jobs_list = [(e, os.path.join(class_dir, s, f"{e.name}.py")) for s, _ in todo
                 for e in EXERCISES]
    reports = _grade_many(jobs_list, timeout, jobs, seed)
    try:
        for s, fp in todo:
            got = []
            for _ in EXERCISES:
                got.append(next(reports))
                ctrl_c.check()
                progress.step()
            result = as_result(s, seed, fp, got)
            results[s] = result
            save(result, folder, gradescope, line)
            write_atomic(out, gradebook_text(list(results.values())), "the gradebook")
            progress.student(result)
        write_atomic(out, gradebook_text(list(results.values())), "the gradebook")
    except KeyboardInterrupt:
        reports.close()                  # its children and their sandboxes end here
        progress.close()
        print(f"interrupted: {len(results)} of {len(students)} students graded (in "
              f"{one_line(out)}); the same command goes on from there", file=sys.stderr)
        return EXIT_INTERRUPTED
    progress.close()
    print(f"graded {len(students)} students ({len(todo)} now, in "
          f"{time.monotonic() - start:.1f} s with {jobs} at once): {one_line(out)}"
          f"{' (replaced the file that was there)' if replaced else ''}, reports in "
          f"{one_line(folder)}/", file=sys.stderr)
    return 0


__all__ = ["grade_class", "students_in", "reports_folder", "gradebook_text", "FIELDS"]
