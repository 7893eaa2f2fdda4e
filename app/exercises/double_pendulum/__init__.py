"""The `double_pendulum` exercise: its grader (grader.py: EXERCISE) and its scene (scene.py: SCENE)."""
