"""The `pivoting_l` exercise: its grader (grader.py: EXERCISE) and its scene (scene.py: SCENE)."""
