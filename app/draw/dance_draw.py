"""Drawing the particle dance: thousands of dots coloured by species, and the rule's colour key
(shown in the HUD, so it never covers the dots).

Speed: each species' dot is drawn once into a small sprite, in the screen's own pixel format with
a see-through colour key (no per-pixel alpha: a dot is opaque), and all the dots of a species go
to the screen in one `Surface.fblits` call. `python -m app bench particles` measures pygame's
ways of drawing 5,000 dots at 1280 x 800 side by side: one `pygame.draw.circle` per particle,
this sprite with per-pixel alpha, this sprite with a colour key (the one used here), and stamping
disks into the pixels with NumPy (`surfarray`). One circle call per particle costs about ten times
the colour-keyed sprite; see the bench's table for the figures of the day.
"""

from __future__ import annotations

from itertools import repeat

import numpy as np
import pygame


COLORS = [(240, 90, 80), (80, 170, 250), (250, 210, 70), (110, 215, 120), (210, 120, 240),
          (240, 150, 60)]
NAMES = ("red", "blue", "yellow", "green", "purple", "orange")     # the colours, in words
PULL_COLOR = (240, 240, 240)
PUSH_COLOR = (255, 120, 110)
SEE_THROUGH = (255, 0, 255)        # the sprites' colour key: no species is magenta

_sprites: dict[tuple, pygame.Surface] = {}


def dot_radius(view, radius: float) -> int:
    """A dot's radius in whole screen pixels (at least 1)."""
    return max(1, int(round(view.len(radius))))


def sprite(species: int, radius: int, target: pygame.Surface) -> pygame.Surface:
    """A filled circle of the species' colour on a see-through square, in the pixel format of
    `target` (blitting between equal formats is a copy, no conversion). Cached."""
    key = (species, radius, target.get_bitsize(), target.get_masks())
    if key not in _sprites:
        size = 2 * radius + 1
        dot = pygame.Surface((size, size)).convert(target)
        dot.fill(SEE_THROUGH)
        pygame.draw.circle(dot, COLORS[species], (radius, radius), radius)
        dot.set_colorkey(SEE_THROUGH)
        _sprites[key] = dot
    return _sprites[key]


def draw_particles(surface: pygame.Surface, view, x: np.ndarray, species: np.ndarray,
                   count: int, radius: float) -> None:
    """Dots of `radius` world px at the positions x (n, 2), coloured by species (0..count-1).
    Far-off particles (walls off) are clipped to +-1e5 px: pygame wants coordinates it can hold."""
    r = dot_radius(view, radius)
    corner = (np.clip(view.pts(x), -1e5, 1e5) - r).astype(np.intp)   # each sprite's top left
    for s in range(count):
        # one fblits call per species replaces the loop `for p in corners: surface.blit(dot, p)`
        surface.fblits(list(zip(repeat(sprite(s, r, surface)), corner[species == s].tolist())))


def draw_mouse(surface: pygame.Surface, view, point, radius: float, pulling: bool) -> None:
    """The mouse's reach: a ring, white while it pulls, red while it pushes."""
    pygame.draw.circle(surface, PULL_COLOR if pulling else PUSH_COLOR,
                       view.pt(np.clip(point, -1e5, 1e5)), max(2, int(view.len(radius))), 2)


# ----- the other ways, measured against draw_particles by `python -m app bench particles` -----

def draw_circles(surface: pygame.Surface, view, x: np.ndarray, species: np.ndarray,
                 count: int, radius: float) -> None:
    """The plain way: one pygame.draw.circle call per particle (a Python loop)."""
    r = dot_radius(view, radius)
    for (px, py), s in zip(np.clip(view.pts(x), -1e5, 1e5).tolist(), species.tolist()):
        pygame.draw.circle(surface, COLORS[s], (px, py), r)


def draw_alpha_sprites(surface: pygame.Surface, view, x: np.ndarray, species: np.ndarray,
                       count: int, radius: float) -> None:
    """Like draw_particles, with the sprite's corners see-through by per-pixel alpha instead of
    a colour key (what this module did before: every pixel of every dot is blended)."""
    r = dot_radius(view, radius)
    corner = (np.clip(view.pts(x), -1e5, 1e5) - r).astype(np.intp)
    for s in range(count):
        key = ("alpha", s, r)
        if key not in _sprites:
            dot = pygame.Surface((2 * r + 1, 2 * r + 1), pygame.SRCALPHA)
            pygame.draw.circle(dot, COLORS[s], (r, r), r)
            _sprites[key] = dot
        surface.fblits(list(zip(repeat(_sprites[key]), corner[species == s].tolist())))


def draw_surfarray(surface: pygame.Surface, view, x: np.ndarray, species: np.ndarray,
                   count: int, radius: float) -> None:
    """Stamping the disks into the pixels with NumPy (pygame.surfarray): for each pixel offset
    of the dot's disk, every particle's pixel at that offset at once, kept inside the clip."""
    r = dot_radius(view, radius)
    disk = pygame.surfarray.array_colorkey(sprite(0, r, surface)) > 0      # the dot's pixels
    offsets = np.argwhere(disk) - r                                         # (dx, dy) pairs
    centre = np.rint(np.clip(view.pts(x), -1e5, 1e5)).astype(np.intp)
    colour = np.array([surface.map_rgb(c) for c in COLORS], dtype=np.int64)[species]
    clip = surface.get_clip()
    pixels = pygame.surfarray.pixels2d(surface)       # pixels[x, y], locks the surface
    try:
        for dx, dy in offsets:
            px, py = centre[:, 0] + dx, centre[:, 1] + dy
            inside = np.flatnonzero((px >= clip.left) & (px < clip.right) & (py >= clip.top)
                                    & (py < clip.bottom))
            pixels[px.take(inside), py.take(inside)] = colour.take(inside)
    finally:
        del pixels                                    # unlocks the surface


DRAWERS = {"pygame.draw.circle per particle": draw_circles,
           "sprite with per-pixel alpha, fblits": draw_alpha_sprites,
           "sprite with a colour key, fblits": draw_particles,
           "surfarray stamp (NumPy)": draw_surfarray}
USED = "sprite with a colour key, fblits"        # the one the scene draws with


def rule_key(matrix: np.ndarray) -> tuple:
    """The rule matrix as a colour key for the HUD, a line per species: its colour, then whom it
    pulls (+) and whom it pushes (-) beyond the repulsive core, e.g. "blue: pulls red +0.1;
    pushes blue -0.9, yellow -0.5"."""
    rows = []
    for s, row in enumerate(matrix):
        pulls = [f"{NAMES[t]} {a:+.1f}" for t, a in enumerate(row) if a > 0]
        pushes = [f"{NAMES[t]} {a:+.1f}" for t, a in enumerate(row) if a < 0]
        parts = ([f"pulls {', '.join(pulls)}"] if pulls else []) + \
                ([f"pushes {', '.join(pushes)}"] if pushes else [])
        rows.append((COLORS[s], f"{NAMES[s]}: {'; '.join(parts) or 'indifferent'}"))
    return tuple(rows)


__all__ = ["COLORS", "NAMES", "SEE_THROUGH", "dot_radius", "sprite", "draw_particles", "draw_mouse",
           "rule_key", "draw_circles", "draw_alpha_sprites", "draw_surfarray", "DRAWERS", "USED"]
