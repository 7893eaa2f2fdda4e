"""The `implicit_spring` exercise: its grader (grader.py: EXERCISE; the usual mistakes its hints
name in hints.py) and its live scene (scene.py: SCENE), side by side."""
