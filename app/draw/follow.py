"""A view that closes in on a strip once it has settled: the collision scenes let a strip of
cloth as wide as the window fall onto a ball a third as wide, and a view fitted to the strip as it
starts leaves the draped strip a thin rim on the ball, two thirds of the picture empty (issue 26:
content share .30 at 1024x768). `follow` eases the content's bounds from those wide ones towards
the strip and the obstacles as they are now, with a time constant of TAU simulated seconds
closing in (TAU_OUT widening), so the picture closes in while the strip drapes and does not jump
with every frame. It never goes outside the wide bounds, or the world where the world reaches
further: a crumpled cloth's heap, wider than the cloth it started as, stays in the picture (it
was cut off at the pane's edge); a particle flung far off the world does not zoom it out. A
reset (time 0) starts wide again; the state is an attribute of the scene, kept in its
snapshot, so a rollback or a scrub of the timeline takes it back with the rest (the collision
scenes' snapshots did not keep it: a scrub back jumped to the start's wide view).
"""

from __future__ import annotations

import math

import numpy as np

TAU = 1.0          # s: the view's time constant closing in (the strip drapes in about a second)
TAU_OUT = 0.2      # ... and widening (a swinging end or a drag must not leave the picture): a
                   # swing widens it at once and lets it close slowly, so it hardly breathes
MARGIN = 3.0       # the strip's bounds grown by this many of its spacings, each side


def follow(scene, wide: tuple[float, float, float, float], pts: np.ndarray,
           spacing: float) -> tuple[float, float, float, float]:
    """The content's bounds for `scene` at its time: eased from `wide` (the bounds a strip
    needs at its start) towards the strip's particles `pts` (2 x n) and the scene's obstacles
    (its contact_bounds), MARGIN spacings around them, clipped to `wide` or the world,
    whichever reaches further on each side."""
    x0, y0, x1, y1 = wide[0], wide[1], wide[0] + wide[2], wide[1] + wide[3]
    m = MARGIN * spacing
    finite = np.isfinite(pts).all(axis=0)
    if not finite.any():
        return wide
    px, py = pts[0][finite], pts[1][finite]
    tight = scene.contact_bounds((float(px.min()) - m, float(py.min()) - m,
                                  float(px.max() - px.min()) + 2 * m,
                                  float(py.max() - py.min()) + 2 * m))
    # clipped to the wide bounds, or to the world where it reaches further: a cloth that
    # spreads wider than a strip starts (a crumpled heap) stays in the picture; one flung far
    # off the world does not zoom it out
    ww, wh = scene.world_size
    tx0, ty0 = max(min(x0, 0.0), tight[0]), max(min(y0, 0.0), tight[1])
    tx1 = min(max(x1, float(ww)), tight[0] + tight[2])
    ty1 = min(max(y1, float(wh)), tight[1] + tight[3])
    if tx1 <= tx0 or ty1 <= ty0:        # the strip has left the wide bounds and the world
        return wide
    t = scene.time
    last = getattr(scene, "_follow", None)
    if t <= 0.0 or (last is not None and t < last[0]):
        now = (x0, y0, x1, y1)
    else:
        if last is None:        # first asked after the start (a headless run's picture at
            last = (0.0, (x0, y0, x1, y1))  # its end): eased from the start over all of t,
            # towards the content now (a view asked every frame eased towards where the content
            # was, so it is a little wider: 442 against 350 px at 2 s of the drape, within ~4 %
            # by 6 s: a review's run)
        k_in, k_out = (1.0 - math.exp(-(t - last[0]) / tau) for tau in (TAU, TAU_OUT))
        now = tuple(a + (k_out if (b - a) * side > 0 else k_in) * (b - a)
                    for a, b, side in zip(last[1], (tx0, ty0, tx1, ty1), (-1, -1, 1, 1)))
    scene._follow = (t, now)
    return (now[0], now[1], now[2] - now[0], now[3] - now[1])
