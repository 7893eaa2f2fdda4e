"""The one world <-> screen transform of the project.

World coordinates are pixels at zoom 1 with y pointing down (pymunk's pygame convention, gravity
(0, +g)). The window fits a scene's `world_size` into the space it has by a uniform scale and an
offset; headless drawing uses the identity. Scene code never scales or offsets by hand: it calls
`view.pt`, `view.pts` and `view.len`.

On top of the fitted view, a `Camera` holds what a person did to it: zoom (the mouse wheel, about
the pointer) and pan (a middle-button drag). It is kept apart from the fit, as a zoom factor and a
shift in world units, so it survives a new fit (another text size, a resize, the HUD growing):
`camera.apply(fitted, rect)` is the view drawn and the mouse's. Zoom 1 and no shift is the fitted
view itself (key 0 comes back to it).

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


ZOOM_RANGE = (0.25, 40.0)     # the camera's zoom against the fitted view: its least and most
ZOOM_STEP = 1.2               # one notch of the mouse wheel


class Camera:
    """Zoom and pan on top of a fitted view: `zoom` multiplies the fitted scale, `shift` (world
    units) moves the world point shown at the centre of the rectangle. One camera may serve
    several fitted views (the panes of a comparison: the same zoom and shift in each)."""

    def __init__(self) -> None:
        self.zoom = 1.0
        self.shift = (0.0, 0.0)

    @property
    def fitted(self) -> bool:
        """True while the camera changes nothing (the view is the fitted one)."""
        return self.zoom == 1.0 and self.shift == (0.0, 0.0)

    def reset(self) -> None:
        self.zoom, self.shift = 1.0, (0.0, 0.0)

    @staticmethod
    def _centre(rect) -> tuple[float, float]:
        x, y, w, h = rect
        return (x + w / 2.0, y + h / 2.0)

    def apply(self, fitted: View, rect) -> View:
        """The view drawn: `fitted` (the view that fits the content into `rect`, x y w h) zoomed
        by `zoom` about the centre of `rect` and shifted by `shift`."""
        if self.fitted:
            return fitted
        c = self._centre(rect)
        w = fitted.to_world(c)
        look = (w[0] + self.shift[0], w[1] + self.shift[1])    # the world point at the centre
        s = fitted.scale * self.zoom
        return View(s, (c[0] - look[0] * s, c[1] - look[1] * s))

    def zoom_at(self, fitted: View, rect, screen_point, factor: float) -> None:
        """Zoom by `factor` (clamped to ZOOM_RANGE) keeping the world point under
        `screen_point` where it is on screen."""
        before = self.apply(fitted, rect)
        under = before.to_world(screen_point)
        self.zoom = min(max(self.zoom * factor, ZOOM_RANGE[0]), ZOOM_RANGE[1])
        s = fitted.scale * self.zoom
        c = self._centre(rect)
        look = (under[0] - (screen_point[0] - c[0]) / s, under[1] - (screen_point[1] - c[1]) / s)
        w = fitted.to_world(c)
        self.shift = (look[0] - w[0], look[1] - w[1])
        if abs(self.zoom - 1.0) < 1e-9 and max(abs(v) for v in self.shift) < 1e-6:
            self.reset()

    def pan(self, fitted: View, screen_delta) -> None:
        """Move the picture by `screen_delta` pixels (a drag): the world follows the pointer."""
        s = fitted.scale * self.zoom
        self.shift = (self.shift[0] - screen_delta[0] / s, self.shift[1] - screen_delta[1] / s)
