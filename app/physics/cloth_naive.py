"""The Verlet cloth the way the lecture's slide writes it: one Python object per particle, one per
rod, and nested loops. It is the benchmark's baseline ("what does vectorising buy?"), not used by
the app.

It runs the same algorithm as app.physics.cloth in the same order (same Verlet step, same rods,
same weights, rods solved in the same order), only one particle and one rod at a time, in
float64: the results agree to rounding, not bit for bit (the vectorised code groups some
operations differently). Keep it as
plain as the slide:

    for p in particles:            # verlet()
        if not p.locked: p.pos += p.pos - p.old + a * h^2 ...
    for i in range(ITERATE):       # satisfyConstraints()
        for c in constraints: ...
"""

from __future__ import annotations

import math

from app.physics.cloth import PIN_CHOICES
from app.physics.rods import EPS, solve_order


class Particle:
    __slots__ = ("x", "y", "old_x", "old_y", "inv_mass")

    def __init__(self, x: float, y: float, inv_mass: float = 1.0):
        self.x, self.y = x, y
        self.old_x, self.old_y = x, y
        self.inv_mass = inv_mass


class Rod:
    __slots__ = ("p1", "p2", "rest")

    def __init__(self, p1: Particle, p2: Particle, rest: float):
        self.p1, self.p2, self.rest = p1, p2, rest


class NaiveCloth:
    """rows x cols particles, rods of the named sets ('structural', 'shear', 'bending')."""

    def __init__(self, rows: int, cols: int, spacing: float, origin: tuple[float, float] = (0, 0),
                 pins: str = "top", sets: tuple[str, ...] = ("structural",)):
        assert pins in PIN_CHOICES
        self.iterations = 10
        self.gravity = 980.0
        self.drag = 0.01
        self.grid = [[Particle(origin[0] + c * spacing, origin[1] + r * spacing)
                      for c in range(cols)] for r in range(rows)]
        pinned = {"top": [(0, c) for c in range(cols)], "corners": [(0, 0), (0, cols - 1)],
                  "none": []}[pins]
        for r, c in pinned:
            self.grid[r][c].inv_mass = 0.0
        rest = {"structural": spacing, "shear": spacing * math.sqrt(2.0), "bending": 2 * spacing}
        self.rods = [Rod(self.grid[r1][c1], self.grid[r2][c2], rest[name])
                     for (r1, c1), (r2, c2), name in solve_order(rows, cols, sets)]

    def step(self, h: float) -> None:
        self.verlet(h)
        for _ in range(self.iterations):
            self.satisfy_constraints()

    def verlet(self, h: float) -> None:
        keep = (1.0 - self.drag) ** (h * 60.0)      # drag = velocity lost per 1/60 s
        ay = self.gravity * h * h
        for row in self.grid:
            for p in row:
                if p.inv_mass == 0.0:
                    continue
                vx = (p.x - p.old_x) * keep
                vy = (p.y - p.old_y) * keep + ay
                p.old_x, p.old_y = p.x, p.y
                p.x += vx
                p.y += vy

    def satisfy_constraints(self) -> None:
        for rod in self.rods:
            p1, p2 = rod.p1, rod.p2
            w1, w2 = p1.inv_mass, p2.inv_mass
            if w1 + w2 == 0.0:
                continue
            dx, dy = p2.x - p1.x, p2.y - p1.y
            length = max(math.sqrt(dx * dx + dy * dy), EPS)
            diff = (length - rod.rest) / length
            k1, k2 = diff * w1 / (w1 + w2), diff * w2 / (w1 + w2)
            p1.x += dx * k1
            p1.y += dy * k1
            p2.x -= dx * k2
            p2.y -= dy * k2

    def positions(self) -> list[list[tuple[float, float]]]:
        return [[(p.x, p.y) for p in row] for row in self.grid]
