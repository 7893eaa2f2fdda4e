"""Hostile: hands in the lab's own answer: `from app.physics.jakobsen import verlet_step`."""
from app.physics.jakobsen import verlet_step  # noqa: F401
