"""What the pymunk exercises' measures share: run the exercise's scene, built by the student's
function, for some seconds (in the grader's child) so the judge can read the scene's metrics."""

from __future__ import annotations

from typing import Any, Callable

from app.scene import Scene


def run_scene(name: str, module: Any, seconds: float, settings: dict | None = None,
              watch: Callable[[Scene], None] | None = None) -> Scene:
    """Build the exercise scene `name` with the student's module and advance it `seconds` of
    simulated time; `watch(scene)` is called after every step (to record a largest value).
    A student's exception comes out as SceneError with their file and line."""
    from app.exercises import scene_class
    from app.exercises.live import bind
    scene = bind(scene_class(name), student=module)(settings or {})
    for _ in range(round(seconds / scene.dt)):
        scene.advance()
        if watch is not None:
            watch(scene)
    return scene
