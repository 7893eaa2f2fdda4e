"""Drawing the velocity and force arrows (app/vectors.py says what they measure).

An arrow's length on screen stands for a quantity, not a world length, so arrows keep their
meaning at any zoom and in any pane: `ArrowScale` picks, per kind, the value an arrow of
REFERENCE_PX screen pixels (times the text scale: arrows grow with F2 like the text beside them)
stands for, rounded to 1, 2 or 5 times a power of ten so the legend reads "36 px = 200 px/s". It
follows the typical magnitude on screen (the 90th percentile): it grows at once when things speed
up and shrinks only when they have slowed five-fold, so arrows do not breathe with every frame.
In compare mode one scale serves every pane (arrows compare across panes). An arrow longer than
MAX_REFERENCES references is drawn at that length with a double head (it goes on).
"""

from __future__ import annotations

import math

import numpy as np
import pygame

from app.draw.text import TEXT, px
from app.vectors import Arrows

VELOCITY_COLOR = (90, 225, 120)
FORCE_COLOR = (255, 140, 60)
REFERENCE_PX = 36          # the legend's arrow, screen px at text scale 1
VELOCITY_FLOOR = 20.0      # px/s: a reference arrow stands for at least this speed
ACCEL_FLOOR = 50.0         # px/s^2 (times the mass): and for at least this net force
MAX_REFERENCES = 3.0       # arrows are capped at this many reference lengths
SHRINK = 5.0               # the scale shrinks when the typical magnitude fell this many times


def nice_up(x: float) -> float:
    """The smallest 1, 2 or 5 x 10^k that is >= x (x > 0)."""
    k = math.floor(math.log10(x))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10.0 ** k >= x * (1 - 1e-12):
            return m * 10.0 ** k
    return 10.0 ** (k + 1)


class ArrowScale:
    """What an arrow of reference length stands for, per kind ("velocity", "force")."""

    def __init__(self):
        self.per: dict[str, float | None] = {"velocity": None, "force": None}

    def update(self, kind: str, vectors: np.ndarray, floor: float) -> None:
        """Follow the typical magnitude of `vectors`, never below `floor` (what a reference
        arrow stands for at least: a cloth at rest trembles by 0.01 px/s, which must not
        become a full arrow)."""
        mags = np.hypot(vectors[:, 0], vectors[:, 1]) if len(vectors) else np.zeros(0)
        mags = mags[np.isfinite(mags)]
        if not len(mags):
            return
        target = nice_up(max(float(np.percentile(mags, 90)), floor))
        now = self.per[kind]
        if now is None or target > now or target * SHRINK <= now:
            self.per[kind] = target

    @staticmethod
    def reference_px() -> float:
        return REFERENCE_PX * TEXT.scale


def draw_arrows(surface: pygame.Surface, view, arrows: Arrows, force: np.ndarray | None,
                scale: ArrowScale) -> int:
    """Draw velocity (and, if measured, force) arrows from each body; return how many."""
    ref = scale.reference_px()
    start = view.pts(arrows.pos)
    drawn = 0
    for kind, vectors, color in (("velocity", arrows.vel, VELOCITY_COLOR),
                                 ("force", force, FORCE_COLOR)):
        per = scale.per[kind]
        if vectors is None or per is None:
            continue
        lengths = np.hypot(vectors[:, 0], vectors[:, 1]) / per * ref     # screen px
        ok = np.isfinite(lengths) & (lengths >= 2.0)
        cap = MAX_REFERENCES * ref
        with np.errstate(invalid="ignore", divide="ignore"):
            unit = vectors / np.hypot(vectors[:, 0], vectors[:, 1])[:, None]
        for i in np.flatnonzero(ok):
            capped = lengths[i] > cap
            _arrow(surface, color, start[i], unit[i], min(lengths[i], cap), capped)
            drawn += 1
    return drawn


def _arrow(surface: pygame.Surface, color, p0: np.ndarray, u: np.ndarray, length: float,
           capped: bool) -> None:
    width = px(2)
    head = max(5.0, 7.0 * TEXT.scale)
    tip = p0 + u * length
    pygame.draw.line(surface, color, p0, tip, width)
    normal = np.array((-u[1], u[0]))
    for back in ((0.0, head * 0.8) if capped else (0.0,)):
        t = tip - u * back
        pygame.draw.polygon(surface, color, [t, t - u * head + normal * head * 0.5,
                                             t - u * head - normal * head * 0.5])


def legend_lines(arrows: Arrows | None, scale: ArrowScale, has_force: bool) -> list:
    """The HUD's lines for the arrows: what they sit on and what a reference arrow stands for."""
    from app.draw.hud import DIM_COLOR, Line
    from app.units import fmt_number
    if arrows is None:
        return [Line("arrows: this scene has none (V turns the overlay off)", DIM_COLOR)]
    ref = int(round(REFERENCE_PX * TEXT.scale))
    v = scale.per["velocity"]
    f = scale.per["force"]
    force_name = "net force" if arrows.mass is not None else "acceleration (net force / mass)"
    force_unit = "kg px/s^2" if arrows.mass is not None else "px/s^2"
    items = [(VELOCITY_COLOR, f"velocity: {ref} px = {fmt_number(v)} px/s"
              if v is not None else "velocity: at rest")]
    items.append((FORCE_COLOR, f"{force_name}: {ref} px = {fmt_number(f)} {force_unit}"
                  if f is not None and has_force else f"{force_name}: measured over a step"))
    return [Line(f"arrows on {arrows.of}" if arrows.of else "arrows", DIM_COLOR),
            Line("", DIM_COLOR, keys=tuple(items))]


__all__ = ["ArrowScale", "draw_arrows", "legend_lines", "nice_up", "VELOCITY_COLOR",
           "FORCE_COLOR"]
