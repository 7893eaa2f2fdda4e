"""Student exercises: the registry (ONE explicit list) and the grader.

Each exercise is a starter module in exercises/ (the function to write, with the slide's formula)
and a grader module here that names its reference answer (the lab's own code) and its checks.
Adding an exercise: write exercises/NAME.py, write app/exercises/NAME.py with an `EXERCISE`, add
it to EXERCISES below; `python -m app exercise check NAME --reference` must pass.
"""

from __future__ import annotations

from app.exercises import (constraints, double_pendulum, newtons_cradle, pivoting_l, rk4,
                           solver_interface, spring, verlet)
from app.exercises.base import Check, Exercise, Result

EXERCISES: list[Exercise] = [
    verlet.EXERCISE,
    constraints.EXERCISE,
    spring.EXERCISE,
    rk4.EXERCISE,
    solver_interface.EXERCISE,
    newtons_cradle.EXERCISE,
    double_pendulum.EXERCISE,
    pivoting_l.EXERCISE,
]


def exercise_names() -> list[str]:
    return [e.name for e in EXERCISES]


def get_exercise(name: str) -> Exercise | None:
    return next((e for e in EXERCISES if e.name == name), None)


__all__ = ["EXERCISES", "Exercise", "Check", "Result", "exercise_names", "get_exercise"]
