"""How far beyond the world a mouse may pull: one rule for every scene.

The window's mouse stays on screen, but an --input file (or a recorded drag far off the window)
may name any finite double, say (1.797e308, 0). A grabbed particle or body that followed it would
carry numbers no simulation survives (pymunk went to NaN; the cloth's squared rod lengths
overflow). So a mouse target is pulled into the box REACH px around the world: far enough to
fling anything out of sight, small enough that every later product stays finite.
"""

from __future__ import annotations

REACH = 1e5        # px beyond the world's edges that a mouse target may lie


def clamp_point(pos: tuple[float, float], world: tuple[float, float],
                reach: float = REACH) -> tuple[float, float]:
    """pos moved into the box `reach` px around the world (0..w, 0..h); NaN counts as 0."""
    w, h = world
    x, y = (float(v) if v == v else 0.0 for v in pos[:2])
    return (min(max(x, -reach), w + reach), min(max(y, -reach), h + reach))
