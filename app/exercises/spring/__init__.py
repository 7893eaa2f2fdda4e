"""The `spring` exercise: its grader (grader.py: EXERCISE) and its live scene
(scene.py: SCENE), side by side."""
