"""Drawing the integrator lab (scenes/integrators.py): the systems, the phase portrait, the energy
chart and the table, laid out in screen pixels in whatever rectangle the window gives the scene.

Text is sized in screen pixels (the size at text scale 1, times the large-text switch F2), never
with the zoom: at a small window a zoomed-out picture had 10 px labels, and F2 made the charts
smaller. The panels are placed from the measured size of their text: the table takes the room
its rows need (its text shrinks only when the rectangle is too narrow, never below
SMALLEST_TEXT), the energy chart goes beside it when the rectangle is wide enough, above it
otherwise, and nowhere where it would be too short to read (chart_least: the table has E/E0),
and the systems and the phase portrait share what is left. Every label drawn is remembered in
`labels` (its rectangle and text) so that a test can check that none overlaps another, at any
window and text size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pygame

from app.draw.hud import wrap
from app.draw.text import TEXT, fit_size, font, px
from app.draw.view import View
from app.physics.integrators import INTEGRATORS

GHOST = (235, 235, 235)
LABEL = (200, 200, 210)
AXIS = (170, 170, 180)
PANEL = (32, 35, 44)
EDGE = (70, 74, 88)
OFF = (110, 110, 110)
SHORT = {"euler": "Euler", "symplectic_euler": "sympl.", "verlet": "Verlet",
         "midpoint": "midpt", "rk4": "RK4", "implicit_euler": "impl."}
TITLE_SIZE = 22          # font sizes at text scale 1 (pygame's default font: glyphs ~0.7 x size)
TABLE_SIZE = 24
SMALL_SIZE = 20
SMALLEST_TEXT = 16       # the table shrinks no further (11 px glyphs): narrow panes
GAP = 8                  # px between panels
TOP_SHARE = 0.55         # the systems and the phase portrait: at least this share of the height
# the systems' own coordinates (px of the problem, the lab's units): the panel shows this box
SYSTEM_BOX = (0.0, 0.0, 480.0, 300.0)
SPRING_DRAW_SCALE = 0.8  # the spring column is drawn at 80 % so the bobs fit the box
SPRING_LINE = 1.6        # the springs' line width in SYSTEM_BOX units (1 px at zoom 0.6)
BOUNCE_FLOOR = 270.0     # bounce: where the floor is drawn in SYSTEM_BOX
BALL_RADIUS = 10.0       # bounce: the ball's radius (its lowest point is the problem's y)
PLOT_SECONDS = 10.0
TABLE_TEMPLATES = ("9999.9", "-8.88e+88", "-8.888e+88")   # widest us/step, error, E/E0
HEADS = ("integrator", "f evals", "us/step", "error", "E/E0")


@dataclass
class LabRects:
    """Where the four panels go, in screen pixels, and the table's text size."""
    systems: pygame.Rect
    phase: pygame.Rect
    energy: pygame.Rect
    table: pygame.Rect
    table_size: int


class LabDrawing:
    """Draws one integrator lab scene into a screen rectangle; keeps rendered labels (most are
    the same every frame) and the rectangles of the last frame's labels."""

    def __init__(self):
        self._texts: dict = {}
        self.labels: list[tuple[pygame.Rect, str]] = []
        self.table_text = 0           # the table's glyph height in the last frame (tests)
        self.spring_width = 1         # the springs' line width in the last frame (px)

    # ----- text ---------------------------------------------------------------------------------
    def render(self, text: str, color, size: int) -> pygame.Surface:
        key = (text, color, size, TEXT.scale)
        label = self._texts.get(key)
        if label is None:
            if len(self._texts) > 1000:                  # numbers change: forget now and then
                self._texts.clear()
            label = self._texts[key] = font(size).render(text, True, color)
        return label

    def text(self, surface, pos, text: str, color, size: int, anchor: str = "topleft",
             within: pygame.Rect | None = None) -> pygame.Rect | None:
        """Blit `text` with its `anchor` point at `pos`; remember its rectangle. With `within`,
        a label that does not fit inside it is left out (a panel too small for it: the table
        says the same)."""
        img = self.render(text, color, size)
        rect = img.get_rect(**{anchor: (int(pos[0]), int(pos[1]))})
        if within is not None and not within.contains(rect):
            return None
        surface.blit(img, rect)
        self.labels.append((rect, text))
        return rect

    # ----- layout -------------------------------------------------------------------------------
    def table_need(self, rows, size: int) -> tuple[int, int]:
        f = font(size)
        gap = f.size("  ")[0]
        columns = self._columns(rows)
        widths = [max(f.size(t)[0] for t in column) for column in columns]
        notes = [note for _, _, note in rows if note] or [""]
        w = 2 * max(4, f.get_height() // 4) + f.get_height() + gap * (len(widths) + 1) \
            + sum(widths) + max(f.size(n)[0] for n in notes)
        h = f.get_linesize() * (len(rows) + 1) + 2 * max(4, f.get_height() // 4)
        return w, h

    def table_fit(self, rows, width: int) -> tuple[list, int, int, int]:
        """The rows as the table will show them (notes in full, shortened, or left out: the
        systems panel and the HUD say it too) and the largest text size, down to
        SMALLEST_TEXT, at which they fit `width`; with the table's (w, h)."""
        for k in range(3):
            shown = [(c, cells, (note[k] if k < 2 else "")) for c, cells, note in rows]
            size = TABLE_SIZE
            need_w, need_h = self.table_need(shown, size)
            while need_w > width and size > SMALLEST_TEXT:
                size = max(SMALLEST_TEXT, int(size * 0.9))
                need_w, need_h = self.table_need(shown, size)
            if need_w <= width:
                break
        return shown, size, need_w, need_h

    def table_within(self, rows, size: int, height: int) -> tuple[int, int, int]:
        """(size, width, height) of the table at the largest text <= `size` whose rows fit in
        `height` px, but never below SMALLEST_TEXT (then taller than `height`)."""
        need_w, need_h = self.table_need(rows, size)
        while need_h > height and size > SMALLEST_TEXT:
            size = max(SMALLEST_TEXT, size - 1)
            need_w, need_h = self.table_need(rows, size)
        return size, need_w, need_h

    def layout(self, rect: pygame.Rect, rows) -> LabRects:
        """The four panels in `rect`, from the table's measured size."""
        s = TEXT.scale
        rows, size, need_w, need_h = self.table_fit(rows, rect.width)
        self.rows = rows
        min_chart = int(320 * s)
        chart_h = max(int(150 * s), need_h)
        if rect.width >= need_w + GAP + min_chart:       # energy chart | table, one row
            bottom = pygame.Rect(rect.left, rect.bottom - chart_h, rect.width, chart_h)
            table = pygame.Rect(bottom.right - need_w, bottom.top, need_w, chart_h)
            energy = pygame.Rect(bottom.left, bottom.top, bottom.width - need_w - GAP, chart_h)
            top_bottom = bottom.top - GAP
        else:                                             # energy chart above the table
            # the systems and the phase portrait keep at least TOP_SHARE of the height: they
            # are the picture (at 1024x768 with F2 they had 40 %: springs 10 px tall); the
            # table's text shrinks (never below SMALLEST_TEXT) before the energy chart goes
            # below the least height a class can read, and the chart gets what is left, up
            # to 30 %
            below = rect.height - int(TOP_SHARE * rect.height) - 2 * GAP
            energy_least = chart_least()
            widest = size
            size, need_w, need_h = self.table_within(rows, size, below - energy_least)
            if need_h <= below - energy_least:
                table = pygame.Rect(rect.left, rect.bottom - need_h, rect.width, need_h)
                energy_h = min(below - need_h, int(0.3 * rect.height))
                energy = pygame.Rect(rect.left, table.top - GAP - energy_h, rect.width, energy_h)
                top_bottom = energy.top - GAP
            else:
                # no room for a chart a class can read (at 1024x768 with F2 it was a 50 px
                # plot with one label, its lines flat): none (the table has E/E0, the phase
                # portrait the spiral); the table's text back to the largest that fits the
                # width and what is below the pictures, and the rest is the picture's
                size, need_w, need_h = self.table_within(rows, widest, below + GAP)
                table = pygame.Rect(rect.left, rect.bottom - need_h, rect.width, need_h)
                energy = pygame.Rect(rect.left, table.top, rect.width, 0)
                top_bottom = table.top - GAP
        top = pygame.Rect(rect.left, rect.top, rect.width, max(top_bottom - rect.top, 1))
        if top.height > 1.3 * top.width / 2:             # tall and narrow: one above the other
            half = (top.height - GAP) // 2
            systems = pygame.Rect(top.left, top.top, top.width, half)
            phase = pygame.Rect(top.left, top.top + half + GAP, top.width, half)
        else:
            half = (top.width - GAP) // 2
            systems = pygame.Rect(top.left, top.top, half, top.height)
            phase = pygame.Rect(top.left + half + GAP, top.top, top.width - half - GAP,
                                top.height)
        return LabRects(systems, phase, energy, table, size)

    # ----- the frame ----------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, rect: pygame.Rect, scene) -> None:
        self.labels = []
        r = self.rects = self.layout(rect, table_rows(scene))
        self.draw_systems(surface, r.systems, scene)
        self.draw_phase(surface, r.phase, scene)
        if r.energy.height > 0:
            self.draw_energy(surface, r.energy, scene)
        self.draw_table(surface, r.table, self.rows, r.table_size)

    def frame(self, surface, r: pygame.Rect, title: str, bottom: bool = False) -> pygame.Rect:
        """A panel with its title at the top (or the bottom), wrapped onto a second line before
        it shrinks (never below SMALLEST_TEXT); returns the room left inside."""
        pygame.draw.rect(surface, PANEL, r)
        pygame.draw.rect(surface, EDGE, r, 1)
        size = TITLE_SIZE
        rows = wrap(title, font(size), r.width - 12)
        while len(rows) > 2 and size > SMALLEST_TEXT:
            size = max(SMALLEST_TEXT, int(size * 0.9))
            rows = wrap(title, font(size), r.width - 12)
        line = font(size).get_linesize()
        height = line * len(rows)
        y = r.bottom - 4 - height if bottom else r.y + 4
        for row in rows:
            self.text(surface, (r.x + 6, y), row, LABEL, size)
            y += line
        if bottom:
            return pygame.Rect(r.x + 2, r.y + 2, r.width - 4, r.height - height - 8)
        return pygame.Rect(r.x + 2, r.y + height + 6, r.width - 4, r.height - height - 8)

    # left: the systems
    def draw_systems(self, surface, r: pygame.Rect, scene) -> None:
        problem = scene.problem
        inner = self.frame(surface, r, f"{problem.title}  (white ring: exact)", bottom=True)
        columns = problem.name in ("spring", "bounce")      # one column per integrator
        names_h = 2 * font(SMALL_SIZE).get_linesize() + 4 if columns else 0
        box = pygame.Rect(inner.x, inner.y, inner.width, max(inner.height - names_h, 1))
        view = View.fit_bounds(SYSTEM_BOX, box)      # (centred: the names go right under)
        old_clip = surface.get_clip()
        surface.set_clip(inner.clip(old_clip))
        x_ref, _ = scene.exact()
        if columns:
            self._springs(surface, view, scene, x_ref, box, names_h)
        else:
            self._bodies(surface, view, scene, x_ref)
        surface.set_clip(old_clip)

    def _springs(self, surface, view: View, scene, x_ref, box: pygame.Rect, names_h: int) -> None:
        """One column per integrator: a bob on its spring from the ceiling, or (bounce) a ball
        over the floor, with the exact solution as a white ring in every column."""
        bounce = scene.problem.name == "bounce"
        k = 1.0 if bounce else SPRING_DRAW_SCALE
        drawn = pygame.Rect(view.pt(SYSTEM_BOX[:2]), (round(view.len(SYSTEM_BOX[2])),
                                                       round(view.len(SYSTEM_BOX[3]))))
        self.springs_box = drawn                        # (tests: how much room it has)
        # the coils as wide as the zoom draws 1.6 units: 1 px in a small window, 2-3 on a
        # projector's 1920x1080 (1 px springs were hairlines there)
        self.spring_width = max(1, round(view.len(SPRING_LINE)))
        names_row = pygame.Rect(box.left, drawn.bottom, box.width, names_h)
        column = int(view.len(80.0))
        names = list(SHORT.values()) + ["blew up", "t=88.88s"]
        size = fit_size(names, SMALL_SIZE, column - 4, smallest=SMALLEST_TEXT)
        two_rows = fit_size(names, SMALL_SIZE, 2 * column - 4, smallest=int(SMALLEST_TEXT * 0.7))
        staggered = max(font(size).size(t)[0] for t in names) > column - 4 or two_rows > size
        if staggered:               # too narrow for a row of names at full size: two rows,
            size = two_rows         # every other one (at 1024x768 one row shrank them to 11 px)
        named = max(font(size).size(t)[0] for t in names) <= 2 * column - 4   # else too small
        if not named:                # for any name (the table has them): none
            names_row = pygame.Rect(0, 0, 0, 0)
        for i, name in enumerate(INTEGRATORS):
            origin = np.array([40.0 + 80.0 * i, BOUNCE_FLOOR if bounce else 22.0])
            run = next((r for r in scene.runs if r.name == name), None)
            color = run.color if run else OFF
            cx = view.pt(origin)[0]
            y = names_row.top + 2 + (font(size).get_linesize() if staggered and i % 2 else 0)
            half_w = font(size).size(SHORT[name])[0] // 2 + 1   # the end names kept inside
            x = min(max(cx, names_row.left + half_w), names_row.right - half_w)
            self.text(surface, (x, y), SHORT[name], color, size, "midtop", within=names_row)
            half = 40 if bounce else 18                  # the floor runs under every column
            pygame.draw.line(surface, (150, 150, 160), view.pt(origin - (half, 0)),
                             view.pt(origin + (half, 0)), px(2))
            lift = np.array([0.0, -BALL_RADIUS if bounce else 0.0])  # bounce: its lowest point
            ghost = origin + k * scene.problem.points(x_ref)[-1] + lift
            pygame.draw.circle(surface, GHOST, view.pt(ghost), max(2, round(view.len(12))), 1)
            if run is None:
                continue
            if run.blew_up_t is not None:     # two lines, every other column lower if narrow
                line = font(size).get_linesize()
                top = (view.pt(origin)[1] + 6 - (3 * line if bounce else 0)
                       + (2 * line if staggered and i % 2 else 0))
                if named:
                    self.text(surface, (cx, top), "blew up", run.color, size, "midtop",
                              within=box)
                    self.text(surface, (cx, top + line), f"t={run.blew_up_t:.2f}s", run.color,
                              size, "midtop", within=box)
                continue
            bob = np.clip(origin + k * scene.problem.points(run.ps.x)[-1] + lift, -1e4, 1e4)
            if not bounce:
                _spring(surface, view, origin, bob, run.color, self.spring_width)
            pygame.draw.circle(surface, run.color, view.pt(bob), max(2, round(view.len(10))))

    def _bodies(self, surface, view: View, scene, x_ref) -> None:
        problem, kind = scene.problem, scene.problem.name
        origin = np.array([240.0, 30.0] if kind == "pendulum" else [260.0, 150.0])
        if kind == "orbit":
            ellipse = problem.exact_orbit_points()
            pygame.draw.lines(surface, (90, 90, 100), True, view.pts(origin + ellipse), 1)
        for run in scene.live():
            pts = np.clip(origin + problem.points(run.ps.x), -1e4, 1e4)
            if kind == "pendulum":
                pygame.draw.line(surface, run.color, view.pt(origin), view.pt(pts[0]), px(2))
            elif len(run.trail) > 1:
                trail = np.clip(origin + run.trail.values(), -1e4, 1e4)
                pygame.draw.lines(surface, run.color, False, view.pts(trail), px(2))
            for j, p in enumerate(pts):
                radius = 10 if kind == "pendulum" else 6 + 3 * (j == 0)
                pygame.draw.circle(surface, run.color, view.pt(p),
                                   max(2, round(view.len(radius))))
        for j, p in enumerate(origin + problem.points(x_ref)):
            radius = 13 if kind == "pendulum" else 8 + 3 * (j == 0)
            pygame.draw.circle(surface, GHOST, view.pt(p), max(2, round(view.len(radius))), 1)
        pygame.draw.circle(surface, (150, 150, 160), view.pt(origin), max(2, round(view.len(4))))

    # right: the phase portrait
    def draw_phase(self, surface, r: pygame.Rect, scene) -> None:
        qlab, plab = scene.problem.phase_labels
        inner = self.frame(surface, r, f"phase portrait: {plab} against {qlab}")
        c = scene.curve
        qlo, qhi = c[:, 0].min(), c[:, 0].max()
        plo, phi = c[:, 1].min(), c[:, 1].max()
        qpad, ppad = 0.15 * (qhi - qlo), 0.15 * (phi - plo)   # the curve fills the panel
        plot = inner.inflate(-12, -8)
        to_px = _mapper(plot, qlo - qpad, qhi + qpad, plo - ppad, phi + ppad)
        old_clip = surface.get_clip()
        surface.set_clip(inner.clip(old_clip))
        curve = to_px(c[:, 0], c[:, 1])
        self.phase_curve = pygame.Rect(curve[0], (0, 0)).unionall(
            [pygame.Rect(p, (1, 1)) for p in curve])     # the exact curve's extent (tests)
        pygame.draw.lines(surface, GHOST, True, curve, px(1))
        for run in scene.runs:
            if len(run.phase) > 1:
                pts = run.phase.values()
                pygame.draw.lines(surface, run.color, False, to_px(pts[:, 0], pts[:, 1]), px(2))
            if len(run.phase):
                q, p = run.phase.last()
                pygame.draw.circle(surface, run.color, to_px(q, p)[0], px(5))
        q, p = scene.exact_phase
        pygame.draw.circle(surface, GHOST, to_px(q, p)[0], px(7), 1)
        surface.set_clip(old_clip)

    # the energy error over time
    def draw_energy(self, surface, r: pygame.Rect, scene) -> None:
        inner = self.frame(surface, r, "energy error |E/E0 - 1| (log scale, last 10 s)")
        small = font(SMALL_SIZE)
        label_w = small.size("10^-16")[0] + 8
        plot = pygame.Rect(inner.x + label_w, inner.y + small.get_height() // 2,
                           inner.width - label_w - 8,
                           inner.height - small.get_linesize() - small.get_height() // 2 - 2)
        if len(scene.sample_times) < 2 or plot.width < 10 or plot.height < 10:
            return
        t = scene.sample_times.values()[:, 0]
        # one point per pixel of plot width is all a line can show: thin the samples out,
        # newest kept (the slice replaces a loop picking every stride-th sample)
        stride = max(1, len(t) // max(1, plot.width))
        keep = slice(len(t) - 1 - stride * ((len(t) - 1) // stride), None, stride)
        t = t[keep]
        # log10 |E/E0 - 1|: a magnitude (a log axis has no negative values), floored at 1e-16
        # (rounding); growth like forward Euler's is a straight line
        values = [np.log10(np.maximum(np.abs(run.energy.values()[keep, 0] - 1.0), 1e-16))
                  for run in scene.runs]
        data = np.concatenate(values + [np.array([-3.0, 0.0])])
        lo, hi = max(float(data.min()), -16.0), min(float(data.max()), 6.0)
        pad = 0.08 * (hi - lo)
        lo, hi = lo - pad, hi + pad
        tlo, thi = max(t[-1] - PLOT_SECONDS, 0.0), max(t[-1], PLOT_SECONDS)
        to_px = _mapper(plot, tlo, thi, lo, hi)
        ticks = decade_ticks(lo, hi, plot.height, small.get_linesize())
        for k in ticks:                                  # gridlines and their labels
            y = to_px(np.array(tlo), np.array(float(k)))[0][1]
            pygame.draw.line(surface, (120, 120, 125) if k == 0 else (52, 56, 66),
                             (plot.left, y), (plot.right, y), 1)
            self.text(surface, (plot.left - 4, y), f"10^{k}", AXIS, SMALL_SIZE, "midright")
        old_clip = surface.get_clip()
        surface.set_clip(plot.clip(old_clip))
        for run, e in zip(scene.runs, values):
            n = min(len(e), len(t))
            if n > 1:
                clipped = np.clip(e[-n:], lo, hi)
                pygame.draw.lines(surface, run.color, False, to_px(t[-n:], clipped), px(2))
        surface.set_clip(old_clip)
        self.text(surface, (inner.right - 6, inner.bottom), f"t = {scene.t:.1f} s", AXIS,
                  SMALL_SIZE, "bottomright")

    # the table
    @staticmethod
    def _columns(rows) -> list[list[str]]:
        columns = [[h, *(cells[i] for _, cells, _ in rows)] for i, h in enumerate(HEADS)]
        for column, widest in zip(columns[2:], TABLE_TEMPLATES):
            column.append(widest)
        return columns

    def draw_table(self, surface, r: pygame.Rect, rows, size: int) -> None:
        """One row per integrator; columns laid out from the measured widths of their text (and
        of the widest number each can show), so that no two ever run together."""
        pygame.draw.rect(surface, PANEL, r)
        pygame.draw.rect(surface, EDGE, r, 1)
        f = font(size)
        self.table_text = f.get_height()
        pad = max(4, f.get_height() // 4)
        gap = f.size("  ")[0]
        widths = [max(f.size(t)[0] for t in column) for column in self._columns(rows)]
        chip = f.get_height()
        x = r.x + pad + chip + gap
        lefts = []
        for w in widths:
            lefts.append(x)
            x += w + gap
        note_x = x
        y = r.y + pad
        for i, head in enumerate(HEADS):              # numbers right-aligned, names left
            self.text(surface, (lefts[i] + (widths[i] if i else 0), y), head, LABEL, size,
                      "topright" if i else "topleft", within=r)
        for color, cells, note in rows:
            y += f.get_linesize()
            side = chip * 2 // 3
            pygame.draw.rect(surface, color, (r.x + pad, y + chip // 6, side, side))
            for i, text in enumerate(cells):
                self.text(surface, (lefts[i] + (widths[i] if i else 0), y), text, color, size,
                          "topright" if i else "topleft", within=r)
            if note:
                self.text(surface, (note_x, y), note, color, size, within=r)


def chart_least() -> int:
    """The least height of an energy chart a class can read: its title, its time label and a
    plot with room for three decade labels (at the text size now)."""
    title, small = font(TITLE_SIZE).get_linesize(), font(SMALL_SIZE).get_linesize()
    return title + 6 + small + 4 * small + 8


def table_rows(scene) -> list[tuple[tuple[int, int, int], tuple[str, ...], tuple[str, str]]]:
    """(colour, cells, (note, short note)) per integrator, in the table's order."""
    rows = []
    for name, info in INTEGRATORS.items():
        run = next((r for r in scene.runs if r.name == name), None)
        evals = f"{info.evaluations}" if info.explicit else f"{info.evaluations} + CG"
        if run is None:
            rows.append((OFF, (info.title, evals, "off", "", ""), ("", "")))
            continue
        note = ("", "")
        if run.blew_up_t is not None:
            note = (f"blew up at t = {run.blew_up_t:.2f} s", f"blew up {run.blew_up_t:.2f} s")
        elif run.cg_failure_t is not None:      # CG stopped short; a dense solve took over
            note = (f"CG stopped short at t = {run.cg_failure_t:.2f} s: dense solve used",
                    "CG fell back")
        rows.append((run.color, (info.title, evals, f"{run.step_us:.1f}", f"{run.error:.2e}",
                                 f"{run.energy_ratio:.4g}"), note))
    return rows


def decade_ticks(lo: float, hi: float, height: int, line: int) -> list[int]:
    """Powers of ten k (10^k) between lo and hi (log10 units) to label on an axis `height` px
    tall, spaced so that labels `line` px tall never touch: every decade if they fit, else
    every 2nd, 5th, 10th ..."""
    first, last = math.ceil(lo), math.floor(hi)
    if last < first:
        return []
    per_decade = height / max(hi - lo, 1e-9)
    for step in (1, 2, 3, 5, 10, 20):
        if step * per_decade >= 1.3 * line:
            break
    start = math.ceil(first / step) * step
    return list(range(start, last + 1, step))


def _mapper(rect: pygame.Rect, xlo, xhi, ylo, yhi):
    """data -> screen points inside rect; far-off points are pulled in to +-1e4 px so pygame
    never sees a huge coordinate (the panels clip them anyway)."""
    def to_px(x, y) -> list:
        x, y = np.atleast_1d(x), np.atleast_1d(y)
        pts = np.stack((rect.left + (x - xlo) / (xhi - xlo) * rect.width,
                        rect.bottom - (y - ylo) / (yhi - ylo) * rect.height), -1)
        return np.clip(pts, -1e4, 1e4).round().astype(int).tolist()
    return to_px


def _spring(surface, view: View, a, b, color, width: int = 1) -> None:
    """A zig-zag from a to b (12 coils), `width` px wide."""
    s = np.linspace(0.0, 1.0, 26)
    d = b - a
    normal = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-9)
    wiggle = np.where(np.arange(26) % 2 == 0, -1.0, 1.0) * 8.0
    wiggle[[0, 1, -2, -1]] = 0.0
    pts = a + s[:, None] * d + wiggle[:, None] * normal
    pygame.draw.lines(surface, color, False, view.pts(pts), width)


__all__ = ["LabDrawing", "LabRects", "table_rows", "decade_ticks"]
