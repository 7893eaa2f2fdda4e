"""The `neighbour_grid` exercise: its grader (grader.py: EXERCISE) and its scene (scene.py: SCENE)."""
