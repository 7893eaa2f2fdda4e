"""The one world <-> screen transform of the project.

World coordinates are pixels at zoom 1 with y pointing down (pymunk's pygame convention, gravity
(0, +g)). The window fits a scene's `world_size` into the space it has by a uniform scale and an
offset; headless drawing uses the identity. Scene code never scales or offsets by hand: it calls
`view.pt`, `view.pts` and `view.len`.
"""

from __future__ import annotations

import numpy as np


class View:
    """scale and offset: screen = world * scale + offset."""

    def __init__(self, scale: float = 1.0, offset: tuple[float, float] = (0.0, 0.0)):
        self.scale = float(scale)
        self.offset = (float(offset[0]), float(offset[1]))

    @classmethod
    def fit(cls, world_size: tuple[int, int], rect: tuple[int, int, int, int]) -> "View":
        """The view that shows the whole world, centred, in the screen rectangle (x, y, w, h)."""
        x, y, w, h = rect
        s = min(w / world_size[0], h / world_size[1])
        return cls(s, (x + (w - world_size[0] * s) / 2, y + (h - world_size[1] * s) / 2))

    @classmethod
    def fit_bounds(cls, bounds: tuple[float, float, float, float],
                   rect: tuple[int, int, int, int]) -> "View":
        """The view that shows the world rectangle `bounds` (x, y, w, h) as large as fits,
        centred, in the screen rectangle `rect` (zooming in on a small scene)."""
        bx, by, bw, bh = bounds
        x, y, w, h = rect
        s = max(min(w / bw, h / bh), 1e-3)
        return cls(s, (x + (w - bw * s) / 2 - bx * s, y + (h - bh * s) / 2 - by * s))

    def pt(self, p) -> tuple[int, int]:
        """One world point -> integer screen point."""
        return (int(round(p[0] * self.scale + self.offset[0])),
                int(round(p[1] * self.scale + self.offset[1])))

    def pts(self, a: np.ndarray) -> np.ndarray:
        """World points, shape (..., 2) -> screen points as float array of the same shape."""
        return np.asarray(a, dtype=float) * self.scale + np.asarray(self.offset)

    def len(self, d: float) -> float:
        """A world length -> screen length."""
        return d * self.scale

    def to_world(self, p) -> tuple[float, float]:
        """A screen point -> world point."""
        return ((p[0] - self.offset[0]) / self.scale, (p[1] - self.offset[1]) / self.scale)

    def world_rect(self, world_size: tuple[int, int]) -> tuple[int, int, int, int]:
        """The screen rectangle covered by the world."""
        x, y = self.pt((0, 0))
        return (x, y, int(round(world_size[0] * self.scale)), int(round(world_size[1] * self.scale)))
