"""What the two grid cloths share (the Verlet cloth, app/physics/cloth.py, and the mass-spring
cloth, app/physics/mass_spring.py): the wind's field and finding the particle under the mouse."""

from __future__ import annotations

import math

import numpy as np


def wind_field(field: str, x: np.ndarray, y: np.ndarray, t: float,
               world: tuple[float, float]) -> tuple[np.ndarray, np.ndarray | float]:
    """The wind's acceleration per unit strength at positions (x, y) and time t: (ax, ay).

    lecture: the slide's F = (sin(x*y*t), cos(z*t)) with x, y in world widths/heights for a cloth
    in the plane z = 1 (so cos(z t) = cos(t); the slide's third component is out of the plane);
    gust: a breeze to the right whose strength travels across the cloth in waves."""
    u = x / world[0]                                 # position in world widths/heights
    w = y / world[1]
    if field == "lecture":
        np.clip(u, -10, 10, out=u)                   # sin(u w t) of a far-flung particle: no overflow
        np.clip(w, -10, 10, out=w)
        return np.sin(u * w * t), math.cos(t)
    return ((0.6 + 0.4 * np.sin(1.7 * t - 6.0 * u)) * (0.8 + 0.2 * np.sin(5.0 * w + t)),
            0.3 * np.sin(4.0 * u - 2.3 * t))


def nearest_cell(x: np.ndarray, pos: tuple[float, float], radius: float,
                 mask: np.ndarray | None = None) -> tuple[int, int] | None:
    """The (row, col) of the particle nearest to pos within radius (among `mask` if given), or
    None; x has shape (2, rows, cols)."""
    d2 = (x[0] - pos[0]) ** 2 + (x[1] - pos[1]) ** 2
    if mask is not None:
        d2 = np.where(mask, d2, np.inf)
    r, c = np.unravel_index(int(np.argmin(d2)), d2.shape)
    return (int(r), int(c)) if d2[r, c] <= radius * radius else None
