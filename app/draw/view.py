"""The one world <-> screen transform of the project.

World coordinates are pixels at zoom 1 with y pointing down (pymunk's pygame convention, gravity
(0, +g)). The window fits a scene's `world_size` into the space it has by a uniform scale and an
offset; headless drawing uses the identity. Scene code never scales or offsets by hand: it calls
`view.pt`, `view.pts` and `view.len`.

Drawing never raises on a state, however wild: a blown-up simulation may hand over 1e300 or NaN,
and pygame refuses such coordinates (or a float NaN cannot become an int). So `pt` and `pts`
pull every screen coordinate into +-SCREEN_LIMIT px and send NaN to -SCREEN_LIMIT (off screen, to
the top left): what cannot be drawn is drawn out of sight, and the run's summary still comes out.
"""

from __future__ import annotations

import numpy as np

# px: screen coordinates are clamped to +-this (far off any screen). Not more: pygame's line
# drawing takes time in proportion to a line's length (a line to 1e7 px takes ~50 ms, to 1e9 px
# ~5 s), and a blow-up watched with B hands over cloths thousands of screens wide.
SCREEN_LIMIT = 2e4


def _safe(v: float) -> float:
    """v clamped to +-SCREEN_LIMIT; NaN -> -SCREEN_LIMIT (comparisons with NaN are False)."""
    if -SCREEN_LIMIT <= v <= SCREEN_LIMIT:
        return v
    return SCREEN_LIMIT if v > SCREEN_LIMIT else -SCREEN_LIMIT


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
        """One world point -> integer screen point (clamped: see the module docstring)."""
        # (a float product overflows to inf, no exception: _safe clamps it)
        return (int(round(_safe(float(p[0]) * self.scale + self.offset[0]))),
                int(round(_safe(float(p[1]) * self.scale + self.offset[1]))))

    def pts(self, a: np.ndarray) -> np.ndarray:
        """World points, shape (..., 2) -> screen points as float array of the same shape
        (clamped to +-SCREEN_LIMIT, NaN to -SCREEN_LIMIT)."""
        with np.errstate(over="ignore", invalid="ignore"):
            s = np.asarray(a, dtype=float) * self.scale + np.asarray(self.offset)
        s = np.nan_to_num(s, nan=-SCREEN_LIMIT, posinf=SCREEN_LIMIT, neginf=-SCREEN_LIMIT)
        return np.clip(s, -SCREEN_LIMIT, SCREEN_LIMIT, out=s)

    def len(self, d: float) -> float:
        """A world length -> screen length."""
        return d * self.scale

    def to_world(self, p) -> tuple[float, float]:
        """A screen point -> world point."""
        return ((p[0] - self.offset[0]) / self.scale, (p[1] - self.offset[1]) / self.scale)
