"""Student exercises: the registry (ONE explicit list), the grader and the exercises' scenes.

Each exercise is a starter module in exercises/ (the function to write, with the slide's formula)
and a package here that holds everything else about it, side by side:

    app/exercises/verlet/grader.py     EXERCISE: the reference answer (the lab's own code) and
                                       the checks (measure in the child, judge in the parent)
    app/exercises/verlet/scene.py      SCENE: `python -m app --scene exercise:verlet`, the
                                       student's function driving the lecture's system beside
                                       the lab's

What they share: base.py (Exercise, Check, Result, Raw), grade.py (the parent: children,
channel, verdicts), child.py (the child's side), channel.py (the untrusted channel), loading.py
(reading a student's file, their traceback), live.py (what every exercise scene does around the
student's code), particle_scene.py (the NumPy exercises' scenes), pymunk_run.py (running a
pymunk exercise's scene for a check), cli.py (`python -m app exercise ...`).

Imports run one way: app/__main__.py -> app/exercises -> scenes/ (the pymunk exercises reuse the
lecture scenes) -> app/ (scene, physics, draw). Nothing in scenes/ or below imports this package;
the command line hands its scene finder to the scene registry (scenes.FINDERS).

Adding an exercise: write exercises/NAME.py, write app/exercises/NAME/{__init__,grader,scene}.py,
add NAME to NAMES below; `python -m app exercise check NAME --reference` must pass.
"""

from __future__ import annotations

import importlib

from app.exercises.base import Check, Exercise, Result

NAMES = ("verlet", "constraints", "spring", "rk4", "solver_interface", "implicit_spring",
         "neighbour_grid", "newtons_cradle", "double_pendulum", "pivoting_l", "collisions")


def _grader(name: str):
    return importlib.import_module(f"app.exercises.{name}.grader")


EXERCISES: list[Exercise] = [_grader(name).EXERCISE for name in NAMES]


def exercise_names() -> list[str]:
    return [e.name for e in EXERCISES]


def get_exercise(name: str) -> Exercise | None:
    return next((e for e in EXERCISES if e.name == name), None)


def scene_class(name: str):
    """The exercise's scene class (imported when asked for: it loads pygame and the lecture
    scene it reuses); None for an unknown name."""
    if name not in NAMES:
        return None
    return importlib.import_module(f"app.exercises.{name}.scene").SCENE


__all__ = ["EXERCISES", "NAMES", "Exercise", "Check", "Result", "exercise_names",
           "get_exercise", "scene_class"]
