"""Drawing the Verlet cloth: its structural rods as a strain heat map, locked particles marked.

Colour = how stretched a rod is, |length/rest - 1|, in a few buckets (blue: < 0.2 %, red: > 20 %).
Speed matters: a 64 x 64 cloth has 8000 rods and must draw in a couple of milliseconds, and one
`pygame.draw.line` per rod costs about 10 ms. Two ways, the faster one chosen automatically:
  * runs: each row (and column) of rods is cut into runs of neighbouring rods of one colour, and a
    run is ONE `pygame.draw.lines` call. Few calls when strain is smooth; but the red-black batch
    order leaves every other rod of a column a little more stretched (an honest artefact of the
    solver), and then a column is many short runs;
  * raster: all rods at once in NumPy, one dot per pixel along each rod (a DDA line), written into
    the surface's pixel array (pygame.surfarray). Cost grows with the pixels drawn, not the calls.
The cheaper is estimated frame by frame (DOTS_PER_CALL): small rods on screen rasterise, long
ones (a small cloth on a big window) draw as runs.
Torn rods are not drawn.

A cloth whose particles are under FILL_BELOW pixels apart on screen (three or four panes in a
small window, a zoomed-out view) is drawn as a filled mesh instead: each cell in the colour of
its most stretched rod. Rods 3 px apart, each coloured on its own, beat against the screen's
pixels into a colour moire (and the solver's stripes, see scenes/cloth.py, cannot be told from
it at that size; zoom in with the wheel to see them).
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np
import pygame

from app.draw.text import px
from app.physics.cloth import Cloth

STRAIN_EDGES = (0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2)
STRAIN_COLORS = [(70, 110, 210), (60, 155, 225), (70, 200, 200), (120, 210, 120),
                 (225, 220, 80), (250, 170, 50), (245, 105, 45), (235, 45, 45)]
PIN_COLOR = (240, 240, 240)
GRAB_COLOR = (255, 120, 200)
HOVER_COLOR = (200, 200, 200)


def strain_buckets(stretch: np.ndarray, alive: np.ndarray) -> np.ndarray:
    """Colour bucket 0..7 of every rod (np.digitize against STRAIN_EDGES); -1 where torn."""
    b = np.digitize(stretch, STRAIN_EDGES)
    b[alive <= 0] = -1
    return b


def draw_runs(surface: pygame.Surface, lines: list, buckets: np.ndarray, width: int,
              colors=STRAIN_COLORS) -> None:
    """Draw rods given as polylines: lines[i] holds the screen points of line i, buckets[i, j] the
    colour of its rod j (between points j and j+1; -1: not drawn) in `colors`. One draw call
    per run of equal colour, hottest runs last (on top)."""
    n_lines, n_rods = buckets.shape
    if n_rods == 0:
        return
    starts_run = np.ones(buckets.shape, bool)
    starts_run[:, 1:] = buckets[:, 1:] != buckets[:, :-1]   # a run starts where the colour changes
    starts = np.flatnonzero(starts_run)                      # ...or at the start of a line
    ends = np.append(starts[1:], buckets.size)
    colours = buckets.ravel()[starts]
    order = np.argsort(colours, kind="stable")
    draw_lines = pygame.draw.lines
    for s, e, b in zip(starts[order].tolist(), ends[order].tolist(), colours[order].tolist()):
        if b < 0:
            continue
        line, j0 = divmod(s, n_rods)
        j1 = e - line * n_rods                               # rods j0..j1-1 -> points j0..j1
        draw_lines(surface, colors[b], False, lines[line][j0:j1 + 1], width)


# One pygame.draw.lines call (a run) costs about as much as writing this many raster dots
# (measured with `bench frames`: ~7 us a call, ~0.06 us a dot, a 1920x1080 surface): the
# cheaper of the two ways is chosen by this estimate, frame by frame.
DOTS_PER_CALL = 120
MAX_RASTER_DOTS = 40    # rods longer than this on screen are drawn with pygame.draw.line


@contextmanager
def _pixel_rows(surface: pygame.Surface):
    """The surface's pixels as (h, w) rows (locked while inside the block) and STRAIN_COLORS in
    its pixel format; (None, None) if it has no pixel array to write."""
    try:
        pixels = pygame.surfarray.pixels2d(surface)
    except (ValueError, pygame.error):
        yield None, None
        return
    try:
        yield pixels.T, np.array([surface.map_rgb(c) for c in STRAIN_COLORS], dtype=pixels.dtype)
    finally:
        del pixels                                               # unlock the surface


def _write_clipped(rows: np.ndarray, clip: pygame.Rect, x: np.ndarray, y: np.ndarray,
                   colour: np.ndarray) -> None:
    """rows[y, x] = colour for the dots inside the clip rectangle."""
    inside = (x >= clip.left) & (x < clip.right) & (y >= clip.top) & (y < clip.bottom)
    rows[y[inside], x[inside]] = colour[inside]


def raster_rods(surface: pygame.Surface, a: np.ndarray, b: np.ndarray, buckets: np.ndarray,
                width: int) -> bool:
    """Draw rods a[k] -> b[k] (screen points, shape (n, 2)) in STRAIN_COLORS[buckets[k]] by
    writing their pixels directly; returns False if the surface has no pixel array to write."""
    with _pixel_rows(surface) as (rows_first, palette):
        if rows_first is None:
            return False
        d = (b - a).astype(np.float32)
        need = np.abs(d).max(axis=1) + 1                  # dots for a gap-free line (DDA)
        k = int(min(np.ceil(need.max()), MAX_RASTER_DOTS)) if len(need) else 0
        too_long = need > k
        for p, q, c in zip(a[too_long].tolist(), b[too_long].tolist(),
                           buckets[too_long].tolist()):       # rare: a yanked rod
            pygame.draw.line(surface, STRAIN_COLORS[c], p, q, width)
        keep = ~too_long
        a, d, buckets = a[keep].astype(np.float32), d[keep], buckets[keep]
        t = np.linspace(0.0, 1.0, max(k, 2), dtype=np.float32)  # k dots along every rod
        # the loop this replaces: for each rod, for each dot: pixel[round(a + t d)] = colour
        px = (a[:, 0, None] + 0.5 + d[:, 0, None] * t).astype(np.intp).ravel()
        py = (a[:, 1, None] + 0.5 + d[:, 1, None] * t).astype(np.intp).ravel()
        colour = np.repeat(palette[buckets], len(t))
        clip = surface.get_clip()
        offsets = [(0, 0)] if width < 2 else [(0, 0), (1, 0), (0, 1)]
        if (len(px) and rows_first.flags.c_contiguous and px.min() >= clip.left
                and px.max() < clip.right - 1 and py.min() >= clip.top
                and py.max() < clip.bottom - 1):
            # every dot (and its neighbours right and below) inside: one flat index per dot,
            # no mask (the common case: the cloth on screen)
            flat, pitch = rows_first.reshape(-1), rows_first.shape[1]
            at = py * pitch + px
            for ox, oy in offsets:
                flat[at + (ox + oy * pitch)] = colour
            return True
        for ox, oy in offsets:
            _write_clipped(rows_first, clip, px + ox, py + oy, colour)
    return True


FILL_BELOW = 5.0        # particles closer than this on screen (px): a filled mesh, not rods
MAX_FILL_DOTS = 8       # a cell's dots along each side (cells are under FILL_BELOW px wide)


def cell_buckets(b_h: np.ndarray, b_v: np.ndarray) -> np.ndarray:
    """Each grid cell's colour bucket: the hottest of its four rods (top, bottom, left, right);
    -1 (not drawn) where one of them is torn. b_h: (rows, cols-1), b_v: (rows-1, cols)."""
    four = np.stack([b_h[:-1], b_h[1:], b_v[:, :-1], b_v[:, 1:]])
    return np.where(four.min(axis=0) < 0, -1, four.max(axis=0))


def raster_cells(surface: pygame.Surface, pts: np.ndarray, buckets: np.ndarray) -> bool:
    """Fill every grid cell (the quad of particles (i, j), (i, j+1), (i+1, j), (i+1, j+1); pts:
    (rows, cols, 2) screen points) in STRAIN_COLORS[buckets[i, j]], skipping -1, by writing a
    k x k lattice of dots over it (bilinear between its corners, k from its longest side on
    screen); returns False if the surface has no pixel array to write."""
    with _pixel_rows(surface) as (rows, palette):
        if rows is None:
            return False
        keep = buckets >= 0
        corners = [pts[:-1, :-1][keep], pts[:-1, 1:][keep], pts[1:, :-1][keep],
                   pts[1:, 1:][keep]]                            # (n, 2) each
        if not len(corners[0]):
            return True
        side = max(np.abs(corners[3] - corners[0]).max(), np.abs(corners[2] - corners[1]).max())
        k = int(min(np.ceil(side) + 2, MAX_FILL_DOTS))
        u = np.linspace(0.0, 1.0, k, dtype=np.float32)
        uu, vv = (g.ravel()[None, :, None] for g in np.meshgrid(u, u))    # (1, k*k, 1)
        p00, p10, p01, p11 = (c.astype(np.float32)[:, None, :] for c in corners)
        # the loop this replaces: for each cell, for each (u, v): pixel[bilinear(u, v)] = colour
        p = (1 - uu) * (1 - vv) * p00 + uu * (1 - vv) * p10 + (1 - uu) * vv * p01 + uu * vv * p11
        x = (p[..., 0] + 0.5).astype(np.intp).ravel()
        y = (p[..., 1] + 0.5).astype(np.intp).ravel()
        colour = np.repeat(palette[buckets[keep]], k * k)
        _write_clipped(rows, surface.get_clip(), x, y, colour)
    return True


def draw_cloth(surface: pygame.Surface, view, cloth: Cloth,
               hover: tuple[int, int] | None = None,
               stretch: tuple[np.ndarray, np.ndarray] | None = None) -> None:
    """Draw the cloth's structural rods coloured by strain, its locked particles as dots, the
    grabbed particle as a ring (and `hover`, the particle the mouse would grab, as a thin ring).
    `stretch`: the horizontal and vertical structural rods' |length/rest - 1| if already known
    (computed here otherwise)."""
    pts = view.pts(np.moveaxis(cloth.x, 0, -1))              # (rows, cols, 2) screen points
    width = px(2) if view.len(cloth.spacing) >= 6 else px(1)     # 2 px: seen from the back row
    strip = cloth.rows <= STRIP_ROWS
    if strip:                    # a strip seen edge-on: its rods wide enough to read as a band
        width = strip_width(view.len(cloth.spacing))
    horizontal, vertical = cloth.sets["structural"].families
    if stretch is None:
        stretch = cloth.stretch(horizontal), cloth.stretch(vertical)
    b_h = strain_buckets(stretch[0], horizontal.alive)
    b_v = strain_buckets(stretch[1], vertical.alive)
    if view.len(cloth.spacing) < FILL_BELOW and not strip and \
            raster_cells(surface, pts, cell_buckets(b_h, b_v)):
        _draw_seams(surface, pts, b_h, b_v)
        _draw_marks(surface, view, cloth, pts, hover)
        return
    runs = int((b_h[:, 1:] != b_h[:, :-1]).sum() + (b_v[1:] != b_v[:-1]).sum())
    # dots the raster would write: a dot per pixel along each rod (about its rest length on
    # screen), three per dot for 2 px lines
    dots = (b_h.size + b_v.size) * (view.len(cloth.spacing) + 1) * (3 if width >= 2 else 1)
    drawn = False
    if dots < DOTS_PER_CALL * runs and not strip:           # (the raster draws 1-2 px only)
        a = np.concatenate([pts[:, :-1].reshape(-1, 2), pts[:-1].reshape(-1, 2)])
        b = np.concatenate([pts[:, 1:].reshape(-1, 2), pts[1:].reshape(-1, 2)])
        k = np.concatenate([b_h.ravel(), b_v.ravel()])
        alive = k >= 0
        drawn = raster_rods(surface, a[alive], b[alive], k[alive], width)
    if not drawn:
        draw_runs(surface, pts.tolist(), b_h, width)
        draw_runs(surface, pts.transpose(1, 0, 2).tolist(), b_v.T, width)
    _draw_marks(surface, view, cloth, pts, hover)


STRIP_ROWS = 3          # a cloth this few particles across is a strip seen edge-on (the
                        # collision scenes' two rows, the trampoline's band)
STRIP_WIDTH = 4         # its rods this wide at text scale 1 (2 px lines draped on a ball read
                        # as the ball's rim, issue 26), up to STRIP_FILL of its rows' gap
STRIP_FILL = 0.4        # when zoomed in (at most twice STRIP_WIDTH)


def strip_width(gap: float) -> int:
    """The width of a strip's rods whose rows are `gap` screen pixels apart: STRIP_WIDTH (grown
    with F2), more when zoomed in (up to STRIP_FILL of the gap, so the rows stay two lines)."""
    return max(px(STRIP_WIDTH), min(int(STRIP_FILL * gap), 2 * px(STRIP_WIDTH)))


SEAM_EVERY = 4                  # a filled mesh shows every 4th row and column as a seam
SEAM_COLOR = (25, 28, 36)


def _draw_seams(surface: pygame.Surface, pts: np.ndarray, b_h: np.ndarray,
                b_v: np.ndarray) -> None:
    """Every SEAM_EVERY-th row and column of a filled mesh as a dark line (and its edges), so
    that a sheet still reads as a woven grid, its lines far enough apart not to beat into a
    moire; runs of torn rods are left out."""
    rows, cols = pts.shape[:2]
    for i in sorted({*range(0, rows, SEAM_EVERY), rows - 1}):
        draw_runs(surface, [pts[i].tolist()], np.where(b_h[i:i + 1] < 0, -1, 0), 1,
                  (SEAM_COLOR,))
    for j in sorted({*range(0, cols, SEAM_EVERY), cols - 1}):
        draw_runs(surface, [pts[:, j].tolist()], np.where(b_v[:, j][None] < 0, -1, 0), 1,
                  (SEAM_COLOR,))


def _draw_marks(surface: pygame.Surface, view, cloth: Cloth, pts: np.ndarray,
                hover: tuple[int, int] | None) -> None:
    """The locked particles as dots, the grabbed one as a ring, `hover` as a thin ring."""
    r_pin = max(2, int(round(view.len(cloth.spacing) * 0.16)))
    for p in pts[cloth.locked].tolist():
        pygame.draw.circle(surface, PIN_COLOR, p, r_pin)
    ring = max(5, r_pin * 2 + 2)
    if cloth.grabbed is not None:
        pygame.draw.circle(surface, GRAB_COLOR, pts[cloth.grabbed].tolist(), ring, 2)
    elif hover is not None:
        pygame.draw.circle(surface, HOVER_COLOR, pts[hover].tolist(), ring, 1)


def strain_key() -> tuple:
    """The strain colours as a colour key (colour or None, text) for the HUD: each chip with the
    stretch |l/rest - 1| it goes up to ('<0.2%', '<0.5', ... '>20%'), short enough to read as
    one scale on one line."""
    labels = ([f"<{STRAIN_EDGES[0] * 100:g}%"]
              + [f"<{b * 100:g}" for b in STRAIN_EDGES[1:]]
              + [f">{STRAIN_EDGES[-1] * 100:g}%"])
    return ((None, "stretch:"), *zip(STRAIN_COLORS, labels))
