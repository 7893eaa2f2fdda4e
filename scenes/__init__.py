"""The registry: every scene of the lab, in menu order (explicit, so adding a scene is one line).

Each entry is a Scene subclass (see app/scene.py). The window's menu, `--list`, `--scene all`,
the smoke tests and the benchmarks all read this list.
"""

from __future__ import annotations

from typing import Callable

from app.scene import Scene
from scenes.cloth import ClothScene
from scenes.cloth_collisions import ClothCollisionsScene
from scenes.double_pendulum import DoublePendulumScene
from scenes.falling_balls import FallingBallsScene
from scenes.integrators import IntegratorsScene
from scenes.mass_spring_cloth import MassSpringClothScene
from scenes.mass_spring_collisions import MassSpringCollisionsScene
from scenes.newtons_cradle import NewtonsCradleScene
from scenes.particle_dance import ParticleDanceScene
from scenes.pivoting_l import PivotingLScene
from scenes.trampoline import TrampolineScene

SCENES: list[type[Scene]] = [
    ClothScene,
    ClothCollisionsScene,
    MassSpringClothScene,
    MassSpringCollisionsScene,
    TrampolineScene,
    FallingBallsScene,
    PivotingLScene,
    NewtonsCradleScene,
    DoublePendulumScene,
    IntegratorsScene,
    ParticleDanceScene,
]


# Scenes found by a prefix, `PREFIX:SPEC`, that are not in the menu: the exercises' scenes
# (`exercise:verlet`). The exercise house (app/exercises) imports the lecture scenes, so this
# registry never imports it; the command line puts its finder here (imports run one way).
FINDERS: dict[str, Callable[[str], "type[Scene] | None"]] = {}


def scene_names() -> list[str]:
    return [s.name for s in SCENES]


def get_scene(name: str) -> type[Scene] | None:
    """The scene class called `name`, or None. `PREFIX:SPEC` asks the finder registered for
    PREFIX (`exercise:NAME` or `exercise:PATH/NAME.py`: an exercise's scene run by the student's
    file; those are not in the menu)."""
    prefix, sep, spec = name.partition(":")
    if sep:
        finder = FINDERS.get(prefix)
        return finder(spec) if finder is not None else None
    return next((s for s in SCENES if s.name == name), None)
