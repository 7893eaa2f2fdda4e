"""What an exercise is: a name, the slide it comes from, the functions the student writes, the
lab's own code that answers it (the reference), and the checks that grade an answer.

A check is a function `run(module) -> Result`: it calls the student's functions (attributes of
`module`) on a small system, measures one physical fact and says whether it holds. It raises
nothing on a wrong answer (a wrong number is a Result with passed=False); an exception raised by
the student's code propagates and the grader (app/exercises/grade.py) reports it with their file
and line. `BadAnswer` is for answers of the wrong kind (a wrong shape, not a pymunk body, ...).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any, Callable

import numpy as np


Student = Any    # the module being graded (or the reference's namespace): its functions by name


class BadAnswer(Exception):
    """The student's function returned something the check cannot use (the message says what)."""


@dataclass(frozen=True)
class Result:
    """One check's outcome: the number measured and the bound it needed, both as short text,
    and on a fail a hint naming the likely mistake."""

    passed: bool
    measured: str
    bound: str
    hint: str = ""


@dataclass(frozen=True)
class Check:
    name: str                                  # short, e.g. "free fall"
    run: Callable[[Any], Result]


@dataclass(frozen=True)
class Exercise:
    name: str                                  # exercises/<name>.py, `exercise check <name>`
    title: str
    slide: str                                 # the lecture slide it comes from
    functions: tuple[str, ...]                 # what the student writes
    reference: Callable[[], SimpleNamespace]   # the lab's own answer (imported when asked for)
    checks: tuple[Check, ...] = field(default=())


def within(value: float, target: float, tol: float) -> bool:
    return bool(np.isfinite(value)) and abs(value - target) <= tol


def array_of(value: Any, shape: tuple[int, ...], what: str) -> np.ndarray:
    """`value` as a float array of `shape`, or BadAnswer naming what came back."""
    if value is None:       # NumPy would make it a NaN of shape (): say what happened instead
        raise BadAnswer(f"{what} returned None; expected an array of shape {shape} (no return "
                        "statement? changing an array in place does not return it)")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise BadAnswer(f"{what} returned {type(value).__name__}; expected an array of shape "
                        f"{shape}") from None
    if arr.shape != shape:
        raise BadAnswer(f"{what} returned shape {arr.shape}; expected {shape}")
    return arr


def order(errors: list[float]) -> float:
    """Measured order from errors at h, h/2, h/4, ...: log2 of the last ratio (the finest pair,
    closest to the asymptotic rate). NaN if an error is 0 or not finite."""
    e1, e2 = errors[-2], errors[-1]
    if not (np.isfinite(e1) and np.isfinite(e2)) or e1 <= 0 or e2 <= 0:
        return float("nan")
    return float(np.log2(e1 / e2))


def fmt(x: float) -> str:
    return "NaN" if x != x else f"{x:.3g}"
