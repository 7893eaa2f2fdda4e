"""The registry: every scene of the lab, in menu order (explicit, so adding a scene is one line).

Each entry is a Scene subclass (see app/scene.py). The window's menu, `--list`, `--scene all`,
the smoke tests and the benchmarks all read this list.
"""

from __future__ import annotations

from pathlib import Path
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
from scenes.sandbox import SandboxScene
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


# The shipped scene files (a teacher's own experiments are files like these: docs/experiments.md),
# in menu order, by their path from the repository's root. They are read when first asked for
# (file_scenes), not at import.
ROOT = Path(__file__).resolve().parent.parent
SCENE_FILES: list[str] = [
    "scenes/files/seesaw.toml",
    "scenes/files/pendulum_wave.toml",
    "scenes/files/galton_board.toml",
    "scenes/files/chain_bridge.toml",
    "scenes/files/car_on_slope.toml",
    "scenes/files/cradle_unequal.toml",
    "scenes/files/curtain.toml",
    "scenes/files/tablecloth.toml",
    "scenes/files/trampoline.toml",
    "scenes/files/falling_balls.toml",
    "scenes/files/pivoting_l.toml",
    "scenes/files/newtons_cradle.toml",
    "scenes/files/double_pendulum.toml",
]
_file_classes: list[type[Scene]] | None = None


def file_scenes() -> list[type[Scene]]:
    """The shipped scene files as Scene classes (read once), named by their paths."""
    global _file_classes
    if _file_classes is None:
        from app.scenefile.scene import scene_class
        _file_classes = [scene_class(str(ROOT / rel), name=rel) for rel in SCENE_FILES]
    return list(_file_classes)


# Beside the registry in the menu and --list, before the files: the sandbox, where a scene file
# is drawn with the mouse (not in SCENES: it is a tool, not a lecture scene; its own tests are
# tests/test_scenefiles.py's).
TOOLS: list[type[Scene]] = [SandboxScene]


def menu_scenes() -> list[type[Scene]]:
    """What the window's menu and --list show: the registry, the sandbox, the shipped files."""
    return SCENES + TOOLS + file_scenes()


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
    if name.endswith(".toml"):
        return file_scene(name)
    return next((s for s in SCENES + TOOLS if s.name == name), None)


def file_scene(path: str) -> type[Scene]:
    """The scene in the file at `path` (a shipped one also by its path from the repository's
    root, from any folder). Raises app.scenefile.load.SceneFileError if it is not accepted."""
    from app.scenefile.scene import scene_class
    if path in SCENE_FILES and not Path(path).is_file():
        return next(c for c in file_scenes() if c.name == path)
    return scene_class(path)
