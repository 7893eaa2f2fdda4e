"""The `solver_interface` exercise: its grader (grader.py: EXERCISE) and its scene (scene.py: SCENE)."""
