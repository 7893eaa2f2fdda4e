"""The Verlet cloth's obstacles and self-collision, the scene's side: its settings, the obstacle
sets, the starts (folded, crumpled), dragging an obstacle with the mouse, metrics, HUD lines.
The physics is in app/physics/cloth_contact.py and app/physics/obstacles.py; scenes/cloth.py
mixes this in (so each module stays short enough to read).

Obstacle sets (`obstacles`), placed below the cloth as built (the cloth drapes over them once it
falls, pins=none, or once you drag it or them together):
  ball    a ball                         box    a box tilted by `box_angle` degrees
  table   a table top on two legs (thin rods), on a floor
  floor   the floor                      bar    a thin bar (4 px thick) far below: tunnelling
Starts (`start`): flat (the grid), folded (a strip folded once onto itself: the self-collision
card), crumpled (the grid squeezed to a third and jittered: a crumpled cloth let go).

The mouse: LMB pressed INSIDE an obstacle drags the obstacle (a thin rod: within 5 px of it);
pressed anywhere else it grabs the nearest particle, as before. Particles never stay inside an
obstacle, so the two never compete. A dragged obstacle follows the mouse at most half its size
per substep (a ball: its radius; at least 8 px; a floor: at once), so a fast drag pushes the
cloth aside instead of jumping over it; its motion is its velocity for friction (cloth resting
on it is carried along).
"""

from __future__ import annotations

import copy
import math

import numpy as np

from app.physics.cloth_contact import OVERLAP_SLACK, SELF_DISTANCE, SELF_METHODS, self_overlaps
from app.physics.obstacles import (Box, Circle, HalfPlane, Obstacle, Segment, floor,
                                   obstacle_at, penetration_max)
from app.scene import Effect, InputEvent, Param, Unit

OBSTACLE_SETS = ("none", "ball", "box", "table", "floor", "bar")
STARTS = ("flat", "folded", "crumpled")
MU = 0.5                       # Coulomb coefficient: holds a cloth on a slope up to atan(0.5) = 27 deg
BOX_ANGLE = 20.0               # degrees
BAR_THICKNESS = 2.0            # px each side of its line (4 px thick): where fast particles tunnel
PRESSED_FOR = 1.0              # s: the pairs pushed outnumber the particles this long: the HUD
                               # says so (if more pairs than particles are still too close)

CONTACT_PARAMS = (
    Param("obstacles", "none", str, choices=OBSTACLE_SETS,
          help="what stands below the cloth: ball, tilted box, table, floor, thin bar (drag "
               "them with LMB)"),
    Param("mu", MU, float, 0.0, 2.0, help="Coulomb friction coefficient of the obstacles",
          rebuild=False),
    Param("box_angle", BOX_ANGLE, float, -60.0, 60.0,
          help="tilt of the box (obstacles=box) in degrees, positive: right side down",
          rebuild=False),
    Param("self_distance", SELF_DISTANCE, float, 0.1, 1.0,
          help="self-collision: the closest two particles not joined by a rod may come, in rod "
               "lengths", rebuild=False),
    Param("self_method", "grid", str, choices=SELF_METHODS,
          help="self-collision's pair search: the neighbour grid or all pairs (O(n^2))",
          rebuild=False),
    Param("start", "flat", str, choices=STARTS,
          help="the cloth at the start: flat, folded once onto itself, or crumpled"),
)
CONTACT_EFFECTS = (
    Effect("collisions", True, "obstacles push the cloth out (Jakobsen's projection)"),
    Effect("friction", True, "Coulomb friction on the obstacles' surfaces", amount="mu"),
    Effect("self_collision", False, "particles kept self_distance apart (neighbour grid)"),
)
CONTACT_UNITS = {"penetration_max": Unit("px", resolution=0.01)}


# ----- the obstacle sets ------------------------------------------------------------------------
def obstacle_layout(name: str, rect: tuple[float, float, float, float], spacing: float,
                    world: tuple[float, float], box_angle: float = BOX_ANGLE) -> list[Obstacle]:
    """The obstacles of set `name` below a cloth at rect (x, y, w, h) with rods `spacing` long."""
    x0, y0, w, h = rect
    wh = world[1]
    cx, below = x0 + w / 2, y0 + h
    if name == "ball":
        r = min(max(0.2 * w, 3 * spacing), 0.18 * wh)
        return [Circle(cx, below + r + 3 * spacing, r, label="ball")]
    if name == "box":
        box = Box(cx, 0.0, min(max(0.9 * w, 4 * spacing), 0.45 * world[0]),
                  max(0.12 * w, 2 * spacing),
                  math.radians(box_angle), label="box")
        box.move_by(0.0, below + 3 * spacing - box.corners()[:, 1].min())
        return [box]
    if name == "table":
        half_w, half_h = 0.3 * w, max(0.5 * spacing, 4.0)
        top_y = below + 2 * spacing + half_h
        foot = top_y + half_h + max(0.35 * w, 6 * spacing)
        leg = max(3.0, 0.25 * spacing)
        legs = [Segment(cx + k * 0.8 * half_w, top_y + half_h + leg, cx + k * 0.8 * half_w,
                        foot - leg, leg, label="leg") for k in (-1, 1)]
        return [Box(cx, top_y, half_w, half_h, label="table")] + legs + [floor(foot, cx, label="floor")]
    if name == "floor":
        return [floor(below + max(0.25 * wh, 4 * spacing), cx, label="floor")]
    if name == "bar":
        y = below + max(0.35 * wh, 4 * spacing)
        return [Segment(x0 - 0.1 * w, y, x0 + 1.1 * w, y, BAR_THICKNESS, label="bar")]
    return []


def folded(rows: int, cols: int, spacing: float, center_x: float, top: float) -> np.ndarray:
    """A strip folded once onto itself, (2, rows, cols): row 0 runs along a path (right along
    the bottom, a half turn of radius R = rows x spacing, back left on top), each further row
    `spacing` further inside the fold. Rods along the straight parts are at their rest length."""
    total = (cols - 1) * spacing
    radius = rows * spacing
    straight = max((total - math.pi * radius) / 2, 0.0)
    u = np.arange(cols) * spacing                      # arc length of each column along the path
    theta = np.clip((u - straight) / radius, 0.0, math.pi)
    back = np.maximum(u - straight - math.pi * radius, 0.0)
    x_left = center_x - (straight + radius) / 2
    bottom = top + 2 * radius
    px = np.where(u <= straight, x_left + u, x_left + straight + radius * np.sin(theta))
    py = np.where(u <= straight, bottom, bottom - radius + radius * np.cos(theta))
    px = np.where(back > 0, x_left + straight - back, px)
    py = np.where(back > 0, bottom - 2 * radius, py)
    nx, ny = -np.sin(theta), -np.cos(theta)            # towards the inside of the fold
    r = np.arange(rows)[:, None] * spacing
    return np.stack([px[None] + r * nx[None], py[None] + r * ny[None]])


def crumpled(rest_x: np.ndarray, rng: np.random.Generator, spacing: float) -> np.ndarray:
    """The flat grid squeezed to a third around its centre and jittered by +-spacing/3."""
    c = rest_x.reshape(2, -1).mean(1)[:, None, None]
    return c + (rest_x - c) / 3 + rng.uniform(-spacing / 3, spacing / 3, rest_x.shape)


# ----- the scene's part -------------------------------------------------------------------------
class ClothContact:
    """Mixed into ClothScene: obstacles, their dragging, self-collision's settings and reports."""

    def build_contact(self, rect: tuple[float, float, float, float]) -> None:
        """After the cloth is built: the start's positions, the obstacles, the settings."""
        c, p = self.cloth, self.p
        self.obstacles = obstacle_layout(p["obstacles"], rect, c.spacing, self.world_size,
                                         p["box_angle"])
        if p["start"] != "flat":
            if p["start"] == "folded":
                # just above a floor if there is one (2 rods: it lands at ~200 px/s, a few px a
                # step, slower than self-collision can see), else where the cloth would hang
                ground = [ob.py for ob in self.obstacles if isinstance(ob, HalfPlane)]
                top = ground[0] - 2 * (c.rows + 1) * c.spacing if ground else rect[1]
                x = folded(c.rows, c.cols, c.spacing, self.world_size[0] / 2, top)
            else:
                x = crumpled(c.rest_x, self.rng, c.spacing)
            c.x[...] = x
            c.x_prev[...] = x
            c.rest_x[...] = x
            c.anchor[...] = x
        c.set_obstacles(self.obstacles)
        self.dragged: int | None = None           # the obstacle LMB drags, and where to
        self.drag_target = (0.0, 0.0)
        self._contact_cache: dict | None = None
        self._pressed_since: float | None = None  # when the pairs pushed began to outnumber
                                                  # the particles (note_pressed; None: not now)
        self.sync_contact()

    def sync_contact(self) -> None:
        st, p = self.cloth.contact, self.p
        st.mu = p["mu"]
        st.self_distance = p["self_distance"] * self.cloth.spacing
        st.self_method = p["self_method"]

    def contact_settings_changed(self, names: set[str]) -> None:
        if "box_angle" in names:
            for ob in self.obstacles:
                if isinstance(ob, Box) and ob.label == "box":
                    ob.angle = math.radians(self.p["box_angle"])
        self._contact_cache = None

    # ----- the mouse ----------------------------------------------------------------------------
    def obstacle_at(self, pos: tuple[float, float]) -> int | None:
        """The obstacle a press at pos picks (app/physics/obstacles.py: obstacle_at)."""
        return obstacle_at(self.obstacles, pos)

    def contact_event(self, event: InputEvent) -> bool:
        """Start, move or end an obstacle drag; True if the event was the obstacle's."""
        if event.kind == "mouse_down" and event.button == 1:
            k = self.obstacle_at(self.cloth.clamp(event.pos))
            if k is None:
                return False
            cx, cy = self.obstacles[k].center
            px, py = self.cloth.clamp(event.pos)
            self.dragged, self.grip = k, (cx - px, cy - py)
            self.drag_target = (cx, cy)
            return True
        if self.dragged is None:
            return False
        if event.kind == "mouse_move":
            px, py = self.cloth.clamp(event.pos)
            self.drag_target = (px + self.grip[0], py + self.grip[1])
        elif event.kind == "mouse_up" and event.button == 1:
            self.dragged = None
        return True

    def move_obstacles(self, h: float) -> None:
        """Once per substep: the dragged obstacle moves towards the mouse, at most half its size;
        every obstacle's velocity is what it moved in this substep / h."""
        for k, ob in enumerate(self.obstacles):
            ob.velocity = (0.0, 0.0)
            if k != self.dragged:
                continue
            (cx, cy), (tx, ty) = ob.center, self.drag_target
            dx, dy = tx - cx, ty - cy
            dist = math.hypot(dx, dy)
            cap = _max_move(ob)
            if dist > cap:
                dx, dy = dx * cap / dist, dy * cap / dist
            if dist > 0:
                ob.move_by(dx, dy)
                ob.velocity = (dx / h, dy / h)

    # ----- reports ------------------------------------------------------------------------------
    def contact_metrics(self) -> dict[str, float]:
        """contacts, penetration_max (px), tunneled, self_overlaps: computed once per step."""
        key = (self.steps, id(self.cloth.x))
        cache = self._contact_cache
        if cache is None or cache["key"] != key:
            c, st = self.cloth, self.cloth.contact
            pts = c.x.reshape(2, -1).T
            free = c.free.ravel() > 0
            cache = {"key": key, "values": {
                "contacts": int(np.count_nonzero(st.touching)) if st.touching is not None
                and self.obstacles and "collisions" in self.on else 0,
                "penetration_max": penetration_max(self.obstacles, pts, free),
                "tunneled": st.tunneled,
                "self_overlaps": self_overlaps(c, st.self_distance, st.self_method)}}
            self._contact_cache = cache
        return dict(cache["values"])

    def note_pressed(self) -> None:
        """After each substep with self-collision on: since when the pairs it pushed have
        outnumbered the particles (None: they do not now). One comparison a substep, so the
        HUD's line below does not hang on how often the metrics are asked (a headless run asks
        once, at its end)."""
        c = self.cloth
        if c.contact.self_pairs <= c.rows * c.cols:
            self._pressed_since = None
        elif self._pressed_since is None:
            self._pressed_since = self.time

    def contact_hud(self, m: dict) -> list[str]:
        lines = []
        if self.obstacles:
            on = "collisions" in self.on
            fr = f"mu {self.p['mu']:g}" if "friction" in self.on else "no friction"
            lines.append(f"{m['contacts']} touching ({fr})  deepest "
                         f"{self.shown('penetration_max', m['penetration_max'])}  "
                         f"tunneled {m['tunneled']}" if on else
                         f"collisions off: the cloth passes through (deepest "
                         f"{self.shown('penetration_max', m['penetration_max'])})")
        if "self_collision" in self.on:
            st = self.cloth.contact
            lst = st.self_list                  # (the grid's Verlet list: app/physics/self_list.py)
            listed = (f"; list reused {lst.reuses}, built {lst.builds}"
                      if st.self_method == "grid" and self.cloth.kernel == "numpy" else "")
            lines.append(f"self-collision ({st.self_method}): {st.self_pairs} pairs pushed; "
                         f"{m['self_overlaps']} still closer than "
                         f"{100 * (1 - OVERLAP_SLACK):.0f}% of {self.p['self_distance']:g} "
                         f"rods{listed}")       # ('; ': where a row may break, app/draw/wrap.py)
            since = self._pressed_since
            if m["self_overlaps"] > self.cloth.rows * self.cloth.cols and since is not None \
                    and self.time - since >= PRESSED_FOR:
                # the crumpled cloth's heap at 1 substep: its weight presses it into itself
                # faster than 2 sweeps a substep part it (at 3 it holds: bench cloth's rows);
                # not a moment's crowd (a crumpled start falling, a landing)
                lines.append("pressed into itself (more pairs too close than particles, for "
                             "over a second): try more substeps")
        return lines

    def contact_bounds(self, bounds: tuple[float, float, float, float]
                       ) -> tuple[float, float, float, float]:
        """bounds grown to hold every obstacle (a floor or half-plane: its line, with a margin)."""
        x, y, w, h = bounds
        x1, y1 = x + w, y + h
        for ob in self.obstacles:
            if isinstance(ob, Circle):
                pts = np.array([[ob.cx - ob.radius, ob.cy - ob.radius],
                                [ob.cx + ob.radius, ob.cy + ob.radius]])
            elif isinstance(ob, Box):
                pts = ob.corners()
            elif isinstance(ob, Segment):
                pts = np.array([[ob.ax, ob.ay], [ob.bx, ob.by]]) + [[0, -ob.thickness],
                                                                    [0, ob.thickness]]
            else:
                pts = np.array([[x, ob.py + 20.0]])
            x, y = min(x, pts[:, 0].min()), min(y, pts[:, 1].min())
            x1, y1 = max(x1, pts[:, 0].max()), max(y1, pts[:, 1].max())
        return (x, y, x1 - x, y1 - y)

    def contact_snapshot(self) -> dict:
        return {"obstacles": copy.deepcopy(self.obstacles), "tunneled": self.cloth.contact.tunneled,
                "dragged": self.dragged, "target": self.drag_target,
                "pressed_since": self._pressed_since,
                "follow": getattr(self, "_follow", None)}     # (the view: app/draw/follow.py)

    def contact_restore(self, snap: dict) -> None:
        for ob, saved in zip(self.obstacles, snap["obstacles"]):
            ob.__dict__.update(copy.deepcopy(saved.__dict__))
        self.cloth.contact.tunneled = snap["tunneled"]
        self.dragged, self.drag_target = snap["dragged"], snap["target"]
        self._contact_cache = None
        self._pressed_since = snap.get("pressed_since")
        self._follow = snap.get("follow")

    def obstacle_state(self) -> np.ndarray:
        """Every obstacle's centre, for the state hash and the finite check."""
        return np.array([ob.center for ob in self.obstacles], float).reshape(-1)


def _max_move(ob: Obstacle) -> float:
    """How far an obstacle may follow the mouse in one substep: half its size, at least 8 px."""
    if isinstance(ob, Circle):
        size = ob.radius
    elif isinstance(ob, Box):
        size = min(ob.half_w, ob.half_h)
    elif isinstance(ob, Segment):
        size = ob.thickness
    else:
        size = math.inf
    return max(8.0, size)

