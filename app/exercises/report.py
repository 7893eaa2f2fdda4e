"""What the student reads: a check's report and an exercise's, and the verdict on a check's frame.

`verdict` runs in the grader's process: it hands the raw values a check's child sent back to the
check's judge (app/exercises/base.py) and turns the outcome (or the judge's own failure, or a
malformed value) into a CheckReport. A NaN never passes, whatever the judge compared.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from app.exercises import base
from app.exercises.base import Check, Malformed, Raw, Result, non_finite
from app.exercises.channel import Frame

OUTPUT_SHOWN = 8000         # bytes of a student's output shown; the rest is counted


@dataclass
class CheckReport:
    name: str
    passed: bool
    measured: str = ""
    bound: str = ""
    hint: str = ""
    error: str = ""          # the student's traceback (trimmed), a bad answer, a timeout, ...

    def lines(self) -> list[str]:
        mark = "PASS" if self.passed else "FAIL"
        out = [f"  {mark}  {self.name:<26} measured {self.measured or '-'}; needed {self.bound}"]
        if not self.passed:
            for text in (self.error, self.hint and f"hint: {self.hint}"):
                out += [f"        {line}" for line in text.splitlines() if text]
        return out


OUTPUT_LINE = 300       # characters of one line of the student's output, at most, on stderr


@dataclass
class Report:
    exercise: str
    path: str
    checks: list[CheckReport]
    output: str = ""         # the first OUTPUT_SHOWN bytes of what the student's code printed
    output_bytes: int = 0    # how much it printed in all
    seed: int = field(default_factory=lambda: base.SEED)   # the random cases' (--seed repeats)
    sandbox: str = ""        # the walls the child ran in, and those this machine lacks

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.checks)

    def to_json(self) -> dict[str, Any]:
        return {"exercise": self.exercise, "path": self.path, "passed": self.passed,
                "seed": self.seed, "checks": [asdict(c) for c in self.checks],
                "output_bytes": self.output_bytes, "sandbox": self.sandbox}

    def text(self) -> str:
        n = sum(c.passed for c in self.checks)
        head = (f"{self.exercise}: {self.path}: {n}/{len(self.checks)} checks pass (seed "
                f"{self.seed}: --seed {self.seed} repeats these random cases)")
        top = [self.sandbox] if self.sandbox else []
        return "\n".join(top + [head] + [line for c in self.checks for line in c.lines()])

    def output_text(self) -> str:
        """What the student's code printed, as shown on stderr ('' if nothing)."""
        if not self.output_bytes:
            return ""
        from app.outputs import one_line
        more = self.output_bytes - len(self.output.encode())
        tail = f"\n--- ({more:,} more bytes not shown) ---" if more > 0 else ""
        # each line cut and its control characters escaped: a student's print cannot clear
        # the terminal or fill it with one 8,000-character line
        shown = "\n".join(one_line(line, OUTPUT_LINE) for line in
                          self.output.rstrip().split("\n"))
        return (f"--- output of {self.path} ({self.output_bytes:,} bytes) ---\n"
                f"{shown}{tail}\n--- end of output ---")


def verdict(check: Check, frame: Frame) -> CheckReport:
    """One check's report from its frame: the judge runs here, on the raw values."""
    name, notes = check.name, " ".join(frame.notes)
    if frame.status != "ok":
        measured, bound = {"bad": ("unusable answer", "see the message"),
                           "unwritten": ("not written yet", "a working answer"),
                           "error": ("an exception", "no exception"),
                           "lab": ("the lab's code raised", "no exception")}[frame.status]
        return CheckReport(name, False, measured, bound, notes, frame.error)
    try:
        with np.errstate(all="ignore"):       # a wrong answer's values overflow: the hint says
            r = check.judge(Raw(frame.raw))
        if not isinstance(r, Result):
            raise TypeError(f"the judge returned {type(r).__name__}, not a Result")
    except Malformed as e:
        return CheckReport(name, False, "malformed values", "the values the check sends",
                           error=f"the check's process sent malformed values ({e}): did your "
                           "code write on the grader's channel?")
    except Exception as e:      # noqa: BLE001 - the grader's bug, reported as the grader's
        return CheckReport(name, False, "grader error", "-", error=(
            f"the grader itself failed ({type(e).__name__}: {str(e)[:300]}): a bug in the lab, "
            "not in your code; please report it with your file"))
    passed, hint = bool(r.passed), r.hint
    if passed and non_finite(frame.raw):      # a NaN never passes, whatever a judge compared
        passed = False
        hint = "NaN or inf among the values your code produced: a NaN never passes. " + hint
    if not passed and notes:
        hint = f"{hint} What came back: {notes}" if hint else f"what came back: {notes}"
    return CheckReport(name, passed, str(r.measured), str(r.bound), "" if passed else hint)


def not_run(check: Check, why: str) -> CheckReport:
    return CheckReport(check.name, False, "not run", "the module imports" if "import" in why
                       else "the checks before it", error=why)


__all__ = ["CheckReport", "Report", "verdict", "not_run", "OUTPUT_SHOWN"]
