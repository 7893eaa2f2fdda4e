"""The `newtons_cradle` exercise: its grader (grader.py: EXERCISE) and its scene (scene.py: SCENE)."""
