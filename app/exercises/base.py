"""What an exercise is, and the two halves of a check.

An exercise is a name, the slide it comes from, the functions the student writes, the lab's own
code that answers it (the reference) and its checks. A check has two halves that run in two
processes (app/exercises/grade.py):

  measure(module) -> raw values     in the CHILD, the process that imported the student's file:
                                    it calls their functions on a small system and returns what
                                    came back, as plain data (numbers, lists, short text): the
                                    positions their step produced, the forces their function
                                    summed, the metrics the lab's scene read off the world their
                                    builder made. No verdict here.
  judge(raw) -> Result              in the PARENT, the grader's own process: it reads the raw
                                    values (untrusted: `Raw` refuses anything malformed), does
                                    the physics (errors, orders, energies) and decides PASS or
                                    FAIL with the number measured, the bound and a hint.

So nothing the student's code does in its process can change a verdict: it can only change what
its functions return. A wrong shape or type is a `BadAnswer` (raised by measure, reported with its
message); `array_of` also notes what came back (float32, NaN) for the hint.
"""

from __future__ import annotations

import math
import secrets
import zlib
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any, Callable

import numpy as np

Student = Any    # the module being graded (or the reference's namespace): its functions by name


class BadAnswer(Exception):
    """The student's function returned something the check cannot use (the message says what)."""


class Malformed(Exception):
    """Raw values that are not what the check's measure sends: a forged or damaged frame."""


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
    name: str                                   # short, e.g. "free fall"
    measure: Callable[[Any], dict[str, Any]]    # in the child: student -> raw values
    judge: Callable[["Raw"], Result]            # in the parent: raw values -> verdict


@dataclass(frozen=True)
class Exercise:
    name: str                                  # exercises/<name>.py, `exercise check <name>`
    title: str
    slide: str                                 # the lecture slide it comes from
    functions: tuple[str, ...]                 # what the student writes
    reference: Callable[[], SimpleNamespace]   # the lab's own answer (imported when asked for)
    checks: tuple[Check, ...] = field(default=())


# ----- the seed of the random cases -------------------------------------------------------------
# Every check that draws random inputs draws them from `cases_rng(name)`: the run's SEED (a new one
# each run, printed with the verdict; `--seed N` repeats it) and the check's name. The grader sets
# SEED (set_seed) before it starts a child; the child is forked from it, so the child's measure
# and the parent's judge draw the very same inputs, and the judge never reads them from the child.
SEED = 0
SEED_BITS = 32


def new_seed() -> int:
    return secrets.randbits(SEED_BITS)


def set_seed(seed: int | None) -> int:
    """Use `seed` (None: a new one) for the random cases from now on; returns it."""
    global SEED
    SEED = new_seed() if seed is None else int(seed)
    return SEED


def cases_rng(name: str) -> np.random.Generator:
    """The generator of one check's random cases: the same in the child and in the parent."""
    return np.random.default_rng([SEED, zlib.crc32(name.encode())])


EPS = float(np.finfo(float).eps)


def rounding(scale: float, ops: float = 1.0, safety: float = 64.0) -> float:
    """The tolerance for comparing with the reference: the rounding its own float64 arithmetic may
    carry, eps x the size of the numbers it combines (`scale`) x the operations in sequence
    (`ops`), times a safety factor (another order of the same sums rounds differently: a right
    answer that adds in another order lands within it, a wrong term does not)."""
    return safety * EPS * max(scale, 1e-300) * max(ops, 1.0)


def counted(value: Any, what: str) -> int:
    """A count the student's function returned, as a Python int that fits in float64 without
    loss; BadAnswer naming what came back otherwise (a float with a fraction, NaN, 10**400)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise BadAnswer(f"{what} is a {type(value).__name__}; expected an integer")
    try:
        f = float(value)
    except OverflowError:
        raise BadAnswer(f"{what} is an integer of {len(str(abs(int(value))))} digits: too large "
                        "to be a count of anything here") from None
    if not math.isfinite(f) or f != int(value) or abs(f) > 2 ** 53:
        raise BadAnswer(f"{what} is {value!r:.40}; expected a whole number below 2**53")
    return int(value)


# ----- the child's side: calling the student's functions --------------------------------------
NOTES: dict[str, str] = {}      # what came back, noted once per function per check (the hint)


def array_of(value: Any, shape: tuple[int, ...], what: str) -> np.ndarray:
    """`value` as a float64 array of `shape`, or BadAnswer naming what came back. Notes a float32
    (or other non-float64) result and the first NaN or inf, for the hint."""
    if value is None:       # NumPy would make it a NaN of shape (): say what happened instead
        raise BadAnswer(f"{what} returned None; expected an array of shape {shape} (no return "
                        "statement? changing an array in place does not return it)")
    if isinstance(value, (list, tuple)):    # it converts, but the caller's arithmetic does not
        raise BadAnswer(f"{what} returned a Python {type(value).__name__}, not a NumPy array: "
                        "the caller computes with what you return (x - x_prev, 2 * f), and on "
                        "lists that fails (list - list) or repeats the list (2 * [...]); return "
                        "the array itself (no .tolist(), np.array(...) around a list)")
    dtype = getattr(value, "dtype", None)
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise BadAnswer(f"{what} returned {type(value).__name__}; expected an array of shape "
                        f"{shape}") from None
    if arr.shape != shape:
        flat = arr.size == math.prod(shape) and arr.ndim != len(shape)
        raise BadAnswer(f"{what} returned shape {arr.shape}; expected {shape}"
                        + (" (the same numbers, reshaped: keep the shape you were given; "
                           "ravel/flatten/concatenate change it)" if flat else ""))
    if dtype is not None and np.dtype(dtype) != np.float64 and what not in NOTES:
        kind = np.dtype(dtype).name
        if kind in ("float32", "float16"):
            NOTES[what] = (f"{what} returned {kind} values: about {7 if kind == 'float32' else 3} "
                           "significant digits, too few for these checks; compute in float64 "
                           "(NumPy's default: drop the dtype=np." + kind + ")")
    if not np.isfinite(arr).all() and what + " nan" not in NOTES:
        bad = int((~np.isfinite(arr)).sum())
        NOTES[what + " nan"] = f"{what} returned NaN or inf ({bad} of {arr.size} values)"
    return arr


# ----- the parent's side: reading the raw values -----------------------------------------------
class Raw:
    """The raw values a check's child sent back, as the parent reads them: every accessor checks
    the kind and shape and raises Malformed otherwise (the child's process is the student's)."""

    def __init__(self, values: Any):
        if not isinstance(values, dict):
            raise Malformed("expected a mapping of named values")
        self.values = values

    def _get(self, key: str) -> Any:
        if key not in self.values:
            raise Malformed(f"'{key}' is missing")
        return self.values[key]

    def has(self, key: str) -> bool:
        return key in self.values

    def number(self, key: str) -> float:
        v = self._get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise Malformed(f"'{key}' is not a number")
        try:
            return float(v)
        except OverflowError:          # an integer beyond float64 (10**400)
            raise Malformed(f"'{key}' is a number too large for float64") from None

    def optional(self, key: str) -> float | None:
        """A number, or None where the measurement says 'none yet'."""
        return None if self._get(key) is None else self.number(key)

    def integer(self, key: str) -> int:
        v = self._get(key)
        if isinstance(v, bool) or not isinstance(v, int):
            raise Malformed(f"'{key}' is not an integer")
        if abs(v) > 2 ** 63:            # every count a check sends fits in 64 bits
            raise Malformed(f"'{key}' is an integer too large ({len(str(abs(v)))} digits)")
        return v

    def flag(self, key: str) -> bool:
        v = self._get(key)
        if not isinstance(v, bool):
            raise Malformed(f"'{key}' is not true or false")
        return v

    def text(self, key: str) -> str:
        v = self._get(key)
        if not isinstance(v, str):
            raise Malformed(f"'{key}' is not text")
        return v

    def array(self, key: str, shape: tuple[int | None, ...] | None = None,
              dtype: type = float) -> np.ndarray:
        """A list of numbers (nested for more dimensions) as an array; `shape` may hold None for
        'any length'."""
        v = self._get(key)
        try:
            arr = np.asarray(v, dtype=dtype)
        except (TypeError, ValueError, OverflowError):
            raise Malformed(f"'{key}' is not an array of numbers") from None
        if arr.dtype == object:
            raise Malformed(f"'{key}' is not an array of numbers")
        if shape is not None and (arr.ndim != len(shape) or any(
                want is not None and got != want for got, want in zip(arr.shape, shape))):
            raise Malformed(f"'{key}' has shape {arr.shape}, not {shape}")
        return arr

    def texts(self, key: str) -> list[str]:
        v = self._get(key)
        if not isinstance(v, list) or not all(isinstance(t, str) for t in v):
            raise Malformed(f"'{key}' is not a list of text")
        return v


def non_finite(value: Any) -> bool:
    """True if a raw value holds a NaN or an infinity anywhere (a NaN never passes a check)."""
    if isinstance(value, float):
        return not math.isfinite(value)
    if isinstance(value, dict):
        return any(non_finite(v) for v in value.values())
    if isinstance(value, list):
        return any(non_finite(v) for v in value)
    return False


# ----- small helpers for judges ------------------------------------------------------------------
def within(value: float, target: float, tol: float) -> bool:
    return bool(np.isfinite(value)) and abs(value - target) <= tol


def order(errors: list[float]) -> float:
    """Measured order from errors at h, h/2, h/4, ...: log2 of the last ratio (the finest pair,
    closest to the asymptotic rate). NaN if an error is 0 or not finite."""
    e1, e2 = errors[-2], errors[-1]
    if not (np.isfinite(e1) and np.isfinite(e2)) or e1 <= 0 or e2 <= 0:
        return float("nan")
    return float(np.log2(e1 / e2))


def fmt(x: float | None) -> str:
    if x is None:
        return "none"
    return "NaN" if x != x else f"{x:.3g}"


def plain(value: Any) -> Any:
    """Raw values as plain data for the channel: arrays to (nested) lists of Python numbers."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value
