"""Obstacles for particles: how far a point is from a solid, and how to push it back out.

The lecture's cloth collides by *projection* (Jakobsen, "Advanced Character Physics", 2001):
after the Verlet step, a particle found inside an obstacle is simply moved to the obstacle's
surface, along the shortest way out. No force, no stiffness, nothing to make the step unstable;
the rods then pull the rest of the cloth along. This module gives both cloths (the Verlet cloth,
app/physics/cloth.py, and the mass-spring cloth) the same four obstacles and the same tools.

The one idea all of it rests on is the **signed distance** d(p) of a point p to an obstacle:

    d > 0   p is outside, d px from the surface
    d = 0   p is on the surface
    d < 0   p is inside, -d px deep

and its **outward normal** n(p), the unit direction in which d grows fastest (the shortest way
out for a point inside). Then "move a particle inside to the surface" is one line for any shape:

    if d < 0:   p += -d * n            (Jakobsen's projection)

The four shapes, in the lab's coordinates (px, y points DOWN):

    Circle(cx, cy, radius)                 a ball:     d = |p - c| - r,   n = (p - c) / |p - c|
    Box(cx, cy, half_w, half_h, angle)     a rotated box (angle in radians, turning x towards
                                           +y): in the box's own frame q = |p_local| - half,
                                           d = |max(q, 0)| outside, max(qx, qy) inside
    HalfPlane(px, py, nx, ny)              everything behind the line through (px, py) with
                                           outward normal (nx, ny): d = (p - point) . n.
                                           floor(y) is the half-plane below y (n = (0, -1))
    Segment(ax, ay, bx, by, thickness)     a static rod: a capsule, every point within
                                           `thickness` px of the segment a-b:
                                           d = |p - closest point of a-b| - thickness

Every function takes points as an (n, 2) array (a view is fine: the Verlet cloth hands over
x.reshape(2, -1).T, so writing into it moves the cloth) and works on all n points at once, one
obstacle at a time: no Python loop over particles.

What a step does with them (the Verlet cloth; the mass-spring cloth uses the same pieces):

1. `project(obstacles, points)`: every particle inside an obstacle is moved to its surface (plus
   an optional `margin`); returns a `Contacts` record: which particles touch (`mask`), how far
   each was moved along the normal (`depth`, px), that normal, and which obstacle it touched.
   Obstacles are handled one after the other, as Jakobsen's loop over constraints does: a
   particle pushed out of one obstacle into a second one that overlaps it is then pushed out of
   the second (and may end inside the first: where two obstacles crush the cloth between them
   there is no place outside both, and `penetration_max` says how deep the trapped ones are).
2. `verlet_friction(x, x_prev, contacts, mu)` (written in app/physics/friction.py, imported from
   here like the rest): Coulomb friction on the Verlet cloth. For a
   particle in contact, the distance travelled in this step is v = x - x_prev (x: projected, x_prev:
   where it started). Its part along
   the surface, v_t = v - (v . n) n, is reduced by at most mu times the normal correction that
   the projection made (the "normal force" of a position-based step is its normal correction):

       |v_t| <= mu * depth:   v_t = 0                  (static friction: it sticks)
       otherwise:             v_t shrinks by mu * depth (kinetic friction: it slides, slower)

   It does so by moving x back along the surface (friction on positions, as Macklin et al.'s
   position-based friction does): the particle travels less in this step, and since the next
   Verlet step reads its velocity from x - x_prev, it carries the slower velocity on. (Moving
   x_prev instead would slow the velocity but keep this step's travel: a cloth on a slope that
   should stick creeps down by g h^2 sin(slope) every step.) Friction only ever slows the sliding: it never reverses it (a test checks). A moving obstacle (its
   `velocity`, px/s) drags what touches it: the sliding is measured relative to the surface.
   `coulomb_friction` is the same rule for any motion array, e.g. velocities (mass-spring cloth:
   reduce the tangential velocity by mu times the normal velocity the contact removed).
3. `penetration_max(obstacles, points)`: the deepest point inside any obstacle, px (0 if none):
   after a step with projection, a measure of what the projection did not fix.
4. Tunnelling: projection only sees where a particle ends, so a fast particle can pass right
   through a thin obstacle in one step. app/physics/tunnelling.py finds such paths (`swept`);
   each shape's `entry` says where a straight path first meets its surface, solved exactly (a
   quadratic for a ball, slab clipping for a box, both for a capsule's three pieces), and
   `distance` gives d alone where no normal is needed (cheaper).

Obstacles are small mutable objects: a scene drags one by `move_by(dx, dy)` (or `move_to`) and
sets its `velocity` (px/s) so that friction carries what rests on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

# imported from here like the rest: Contacts, the friction rules; path entries, project()'s guard
from app.physics.friction import Contacts, coulomb_friction, verlet_friction
from app.physics.paths import back_to_entry, circle_entry, slab_entry

OBSTACLE_KINDS = ("circle", "box", "half_plane", "segment")
TINY = 1e-12                                 # shortest length we divide by (no 0/0)
NEAR_SLACK = 0.01     # px: near_bounds reads float32 positions: no point lost to their rounding


def _xy(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The x and y columns of an (n, 2) array, as float64 (what the distances are computed in)."""
    p = np.asarray(points)
    return p[:, 0].astype(np.float64, copy=False), p[:, 1].astype(np.float64, copy=False)


def _pairs(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Two (n,) arrays as the columns of one (n, 2) array (np.stack's work, less overhead)."""
    out = np.empty((len(a), 2))
    out[:, 0] = a
    out[:, 1] = b
    return out


def _unit_or(nx: np.ndarray, ny: np.ndarray, length: np.ndarray, fallback: tuple[float, float]
             ) -> tuple[np.ndarray, np.ndarray]:
    """(nx, ny) / length, or `fallback` where the length is 0 (a point at a circle's centre)."""
    safe = np.maximum(length, TINY)
    ux, uy = nx / safe, ny / safe
    zero = length <= TINY
    if zero.any():                      # rare: fix those few, not every element
        ux[zero], uy[zero] = fallback
    return ux, uy


# ----- the shapes ---------------------------------------------------------------------------------
@dataclass
class Obstacle:
    """What every obstacle has: a velocity (px/s, set by whoever moves it; friction measures
    sliding relative to it) and a name for the HUD."""

    velocity: tuple[float, float] = field(default=(0.0, 0.0), kw_only=True)
    label: str = field(default="", kw_only=True)
    kind = "obstacle"

    def signed_distance(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(d, normal): d (n,) signed distance in px (negative inside), normal (n, 2) outward unit."""
        d, nx, ny = self.distance_xy(*_xy(points))
        return d, _pairs(nx, ny)

    def distance_xy(self, x: np.ndarray, y: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The same from the points' x and y columns: (d, normal x, normal y), each (n,)."""
        raise NotImplementedError

    def distance(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """The signed distance alone (n,), for tests that need no normal (cheaper per shape)."""
        return self.distance_xy(x, y)[0]

    def move_by(self, dx: float, dy: float) -> None:
        raise NotImplementedError

    def bounds(self) -> tuple[float, float, float, float]:
        """(x_min, y_min, x_max, y_max) of the obstacle (infinite for a half-plane): points
        outside it, grown by a margin, need no distance (project() skips them)."""
        return (-math.inf, -math.inf, math.inf, math.inf)

    @property
    def center(self) -> tuple[float, float]:
        raise NotImplementedError

    def move_to(self, x: float, y: float) -> None:
        """Move the obstacle so that its `center` is at (x, y)."""
        cx, cy = self.center
        self.move_by(x - cx, y - cy)

    def contains(self, points: np.ndarray) -> np.ndarray:
        """True where a point is strictly inside (d < 0)."""
        return self.signed_distance(points)[0] < 0

    def half_width(self) -> float:
        """Half the obstacle's thinnest width (a ball: its radius): a point that starts outside
        has to travel at least this far to get past its middle (0: not known, always check)."""
        return 0.0

    def entry(self, ax: np.ndarray, ay: np.ndarray, ex: np.ndarray, ey: np.ndarray
              ) -> np.ndarray:
        """Where each straight path a + t e (0 <= t <= 1) first meets the surface: its t, for
        paths that start outside (d >= 0) and reach inside. Each shape below solves it exactly
        (a circle: a quadratic; a box: slab clipping); this fallback halves [0, 1] 30 times."""
        lo, hi = np.zeros(len(ax)), np.ones(len(ax))
        for _ in range(30):                     # d >= 0 at lo, d < 0 at hi
            mid = (lo + hi) / 2
            out = self.distance_xy(ax + mid * ex, ay + mid * ey)[0] >= 0
            lo, hi = np.where(out, mid, lo), np.where(out, hi, mid)
        return lo


@dataclass
class Circle(Obstacle):
    """A ball of `radius` px centred at (cx, cy)."""

    cx: float
    cy: float
    radius: float
    kind = "circle"

    def distance_xy(self, x, y):
        dx, dy = x - self.cx, y - self.cy
        r = np.sqrt(dx * dx + dy * dy)     # (np.hypot: the same but for the last bit, 5x slower)
        nx, ny = _unit_or(dx, dy, r, (0.0, -1.0))        # at the centre: out through the top
        return r - self.radius, nx, ny

    def distance(self, x, y):
        return np.hypot(x - self.cx, y - self.cy) - self.radius

    def move_by(self, dx, dy):
        self.cx += dx
        self.cy += dy

    @property
    def center(self):
        return (self.cx, self.cy)

    def bounds(self):
        r = self.radius
        return (self.cx - r, self.cy - r, self.cx + r, self.cy + r)

    def half_width(self):
        return self.radius

    def entry(self, ax, ay, ex, ey):
        return circle_entry(ax - self.cx, ay - self.cy, ex, ey, self.radius)[0]


@dataclass
class Box(Obstacle):
    """A rectangle of half sizes (half_w, half_h) centred at (cx, cy), turned by `angle` radians
    (positive turns +x towards +y: clockwise on screen, since y points down)."""

    cx: float
    cy: float
    half_w: float
    half_h: float
    angle: float = 0.0
    kind = "box"

    def axes(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The box's own x and y axes in the world (unit vectors)."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        return (c, s), (-s, c)

    def corners(self) -> np.ndarray:
        """The four corners (4, 2), in order around the box."""
        (ux, uy), (vx, vy) = self.axes()
        signs = ((-1, -1), (1, -1), (1, 1), (-1, 1))
        return np.array([(self.cx + a * self.half_w * ux + b * self.half_h * vx,
                          self.cy + a * self.half_w * uy + b * self.half_h * vy)
                         for a, b in signs])

    def distance_xy(self, x, y):
        (ux, uy), (vx, vy) = self.axes()
        dx, dy = x - self.cx, y - self.cy
        lx, ly = dx * ux, dx * vx       # the point in the box's frame (sums made in place)
        lx += dy * uy
        ly += dy * vy
        qx, qy = np.abs(lx), np.abs(ly)
        qx -= self.half_w
        qy -= self.half_h
        ox, oy = np.maximum(qx, 0.0), np.maximum(qy, 0.0)
        face_x = qx >= qy
        d = np.minimum(np.maximum(qx, qy, out=qx), 0.0, out=qx)   # inside: -(to nearest face)
        # the normal in the box's frame: the nearest face's (+1 on an axis: either side will
        # do), its side given by the signs of lx, ly
        gx = face_x.astype(np.float64)
        gy = 1.0 - gx
        # outside, d is the distance to the nearest point of the box: beside a face one of ox,
        # oy is 0 (their sum is the distance, the face's normal the way out); past a corner
        # both are > 0: the distance to the corner, hypot(ox, oy), and the normal points away
        # from it (written for those few alone: hypot is the slowest call here)
        out = ox + oy
        corner = (np.minimum(ox, oy, out=qy) > 0).nonzero()[0]
        if corner.size:
            cx, cy = ox[corner], oy[corner]
            out[corner] = to_corner = np.hypot(cx, cy)
            np.maximum(to_corner, TINY, out=to_corner)
            gx[corner], gy[corner] = cx / to_corner, cy / to_corner
        d += out
        np.copysign(gx, lx, out=gx)
        np.copysign(gy, ly, out=gy)
        nx, ny = gx * ux, gx * uy
        nx += gy * vx
        ny += gy * vy
        return d, nx, ny

    def distance(self, x, y):
        (ux, uy), (vx, vy) = self.axes()
        dx, dy = x - self.cx, y - self.cy
        qx = np.abs(dx * ux + dy * uy) - self.half_w
        qy = np.abs(dx * vx + dy * vy) - self.half_h
        return np.hypot(np.maximum(qx, 0.0), np.maximum(qy, 0.0)) + \
            np.minimum(np.maximum(qx, qy), 0.0)

    def move_by(self, dx, dy):
        self.cx += dx
        self.cy += dy

    @property
    def center(self):
        return (self.cx, self.cy)

    def half_width(self):
        return min(self.half_w, self.half_h)

    def entry(self, ax, ay, ex, ey):
        (ux, uy), (vx, vy) = self.axes()
        dx, dy = ax - self.cx, ay - self.cy           # the path in the box's own frame
        return slab_entry(dx * ux + dy * uy, dx * vx + dy * vy, ex * ux + ey * uy,
                           ex * vx + ey * vy, self.half_w, self.half_h)[0]

    def bounds(self):
        c, s = abs(math.cos(self.angle)), abs(math.sin(self.angle))
        ex, ey = self.half_w * c + self.half_h * s, self.half_w * s + self.half_h * c
        return (self.cx - ex, self.cy - ey, self.cx + ex, self.cy + ey)


@dataclass
class HalfPlane(Obstacle):
    """Everything behind the line through (px, py) whose outward normal is (nx, ny) (normalised
    on creation). floor(y) makes the ground: solid below y, its normal pointing up (0, -1)."""

    px: float
    py: float
    nx: float
    ny: float
    kind = "half_plane"

    def __post_init__(self):
        length = math.hypot(self.nx, self.ny)
        if not length > 0:
            raise ValueError("a half-plane needs a non-zero normal")
        self.nx, self.ny = self.nx / length, self.ny / length

    def distance_xy(self, x, y):
        d = (x - self.px) * self.nx + (y - self.py) * self.ny
        return d, np.full(len(d), self.nx), np.full(len(d), self.ny)

    def half_width(self):
        return math.inf

    def entry(self, ax, ay, ex, ey):
        d0 = (ax - self.px) * self.nx + (ay - self.py) * self.ny
        fall = -(ex * self.nx + ey * self.ny)           # how much d drops over the whole path
        return np.clip(d0 / np.maximum(fall, TINY), 0.0, 1.0)

    def move_by(self, dx, dy):
        self.px += dx
        self.py += dy

    @property
    def center(self):
        return (self.px, self.py)


def floor(y: float, x: float = 0.0, **kw) -> HalfPlane:
    """The ground at height y: solid below (y grows downwards), normal (0, -1)."""
    return HalfPlane(x, y, 0.0, -1.0, **kw)


@dataclass
class Segment(Obstacle):
    """A static rod from (ax, ay) to (bx, by), `thickness` px thick on every side: a capsule (a
    rectangle with round ends). Thin ones (a few px) are where fast particles tunnel."""

    ax: float
    ay: float
    bx: float
    by: float
    thickness: float
    kind = "segment"

    def closest(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The nearest point of the segment a-b to each point: (x, y) arrays."""
        return self._closest(*_xy(points))

    def _closest(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        ex, ey = self.bx - self.ax, self.by - self.ay
        e2 = ex * ex + ey * ey
        t = ((x - self.ax) * ex + (y - self.ay) * ey) / e2 if e2 > 0 else np.zeros_like(x)
        t = np.clip(t, 0.0, 1.0)
        return self.ax + t * ex, self.ay + t * ey

    def distance_xy(self, x, y):
        cx, cy = self._closest(x, y)
        dx, dy = x - cx, y - cy
        r = np.hypot(dx, dy)
        ex, ey = self.bx - self.ax, self.by - self.ay
        e = math.hypot(ex, ey)
        up = (ey / e, -ex / e) if e > 0 else (0.0, -1.0)    # on the core line: one side's normal
        nx, ny = _unit_or(dx, dy, r, up)
        return r - self.thickness, nx, ny

    def move_by(self, dx, dy):
        self.ax += dx
        self.bx += dx
        self.ay += dy
        self.by += dy

    @property
    def center(self):
        return ((self.ax + self.bx) / 2, (self.ay + self.by) / 2)

    def half_width(self):
        return self.thickness

    def entry(self, ax, ay, ex, ey):
        # the capsule is a rectangle (the core, `thickness` each side) and a disc at either end:
        # the path enters it where it first enters one of the three
        sx, sy = self.bx - self.ax, self.by - self.ay
        length = math.hypot(sx, sy)
        ux, uy = (sx / length, sy / length) if length > 0 else (1.0, 0.0)
        dx, dy = ax - (self.ax + self.bx) / 2, ay - (self.ay + self.by) / 2
        t, hit = slab_entry(dx * ux + dy * uy, -dx * uy + dy * ux, ex * ux + ey * uy,
                             -ex * uy + ey * ux, length / 2, self.thickness)
        t = np.where(hit, t, np.inf)
        for px, py in ((self.ax, self.ay), (self.bx, self.by)):
            tc, hc = circle_entry(ax - px, ay - py, ex, ey, self.thickness)
            t = np.where(hc & (tc < t), tc, t)
        return np.where(np.isfinite(t), t, 0.0)

    def bounds(self):
        t = self.thickness
        return (min(self.ax, self.bx) - t, min(self.ay, self.by) - t,
                max(self.ax, self.bx) + t, max(self.ay, self.by) + t)


# ----- distances to several obstacles: app/physics/obstacle_queries.py (re-exported here) ------
from app.physics.obstacle_queries import (PICK_THIN, nearest, obstacle_at,  # noqa: E402
                                          penetration_max)


# ----- projection ---------------------------------------------------------------------------------
def project(obstacles, points: np.ndarray, margin: float = 0.0,
            movable: np.ndarray | None = None, start: np.ndarray | None = None) -> Contacts:
    """Move every point found closer than `margin` to an obstacle (inside it, for margin 0) out
    along the normal to distance `margin`: p += (margin - d) * n. Writes into `points` (n, 2);
    points where `movable` is False (pinned, grabbed) are left where they are. Obstacles are
    handled in order (see the module docstring). Returns the Contacts.

    `start` ((2, n), optional): where each point was before this step. The shortest way out of
    a thin obstacle can be through its far side: a point that came down 6 px into a table top
    10 px thick is nearer its underside. With `start`, a point whose normal now points against
    the normal where it started (it has crossed the middle) is first put back where its path
    from `start` entered the obstacle, then pushed out from there: on the side it came from."""
    n = len(points)
    depth = np.zeros(n)
    normal = np.zeros((n, 2))
    index = np.full(n, -1)
    hit = np.zeros(n, bool)
    px, py = points[:, 0], points[:, 1]        # views: writing into them moves the points
    for k, ob in enumerate(obstacles):
        ids = near_bounds(ob, px, py, margin, movable)     # the cheap test first
        if ids.size == 0:
            continue
        d, nx, ny = ob.distance_xy(px[ids].astype(np.float64), py[ids].astype(np.float64))
        inside = (d < margin).nonzero()[0]
        if inside.size == 0:
            continue
        if inside.size < ids.size:                                # usually few
            ids, d, nx, ny = ids[inside], d[inside], nx[inside], ny[inside]
        if start is not None and not isinstance(ob, HalfPlane):
            d, nx, ny = back_to_entry(ob, ids, d, nx, ny, px, py, start)
        push = margin - d
        px[ids] += (push * nx).astype(points.dtype, copy=False)
        py[ids] += (push * ny).astype(points.dtype, copy=False)
        depth[ids] += push
        normal[ids, 0] = nx
        normal[ids, 1] = ny
        index[ids] = k
        hit[ids] = True
    return Contacts(hit, depth, normal, index)


def near_bounds(ob: Obstacle, px: np.ndarray, py: np.ndarray, margin: float = 0.0,
                movable: np.ndarray | None = None) -> np.ndarray:
    """Indices of the points (x and y columns) within `margin` of the obstacle's bounds (and
    `movable`, if given): the only ones that can be inside or within the margin."""
    margin += NEAR_SLACK           # (m.nonzero()[0]: np.flatnonzero(m) without its wrappers)
    if isinstance(ob, HalfPlane):                # no box: the plane's own test, as cheap
        near = (px - ob.px) * ob.nx + (py - ob.py) * ob.ny < margin
        return (near & movable if movable is not None else near).nonzero()[0]
    x0, y0, x1, y1 = ob.bounds()
    near = (px > x0 - margin) & (px < x1 + margin) & (py > y0 - margin) & (py < y1 + margin)
    if movable is not None:
        near &= movable
    return near.nonzero()[0]


__all__ = ["PICK_THIN", "obstacle_at", "OBSTACLE_KINDS", "Obstacle", "Circle", "Box", "HalfPlane", "Segment", "floor",
           "nearest", "penetration_max", "Contacts", "project", "near_bounds", "coulomb_friction",
           "verlet_friction"]
