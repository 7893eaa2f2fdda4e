"""The `collisions` exercise: its grader (grader.py: EXERCISE), the hints its judges give
(hints.py) and its live scene (scene.py: SCENE), side by side."""
