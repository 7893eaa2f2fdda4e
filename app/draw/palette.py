"""Colours that mean the same thing everywhere they appear (the integrator lab and the integrator
benchmark's charts draw each integrator in one colour), so they live here, once."""

from __future__ import annotations

Color = tuple[int, int, int]

# one colour per integrator of app/physics/integrators.py (colour-blind-safe where possible)
INTEGRATOR_COLORS: dict[str, Color] = {
    "euler": (230, 97, 76), "symplectic_euler": (250, 150, 60), "verlet": (240, 200, 70),
    "midpoint": (120, 200, 120), "rk4": (86, 180, 233), "implicit_euler": (200, 130, 230)}
