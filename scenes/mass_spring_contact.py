"""The mass-spring cloth's obstacles, the scene's side: the settings, the obstacle sets (the Verlet
cloth's: scenes/cloth_contact.py, the same names and places), dragging an obstacle with the
mouse, the metrics and the HUD line. The physics is app/physics/mass_spring_contact.py (penalty
or projection, Coulomb friction) on app/physics/obstacles.py; scenes/mass_spring_cloth.py mixes
this in.

`contact` chooses how a particle that went into an obstacle comes out, and the HUD names it:
  projection  moved to the surface after the step, its velocity into the obstacle filtered out
              (Baraff & Witkin's constraint on a particle): no stiffness, no limit on the step;
  penalty     a stiff spring k_c = contact_stiffness pushes it out: a force every integrator
              sees, which raises the cloth's highest frequency (k_c/m on that particle) and so
              lowers the step limit: the HUD gives the contact's own limit 2 sqrt(m/k_c) beside
              h, and the bound on the whole cloth's, 2/sqrt(omega_max^2 + k_c/m), undamped (the
              spring damping lowers it: at the defaults the strip blows up at half of it).
The mouse: LMB pressed inside an obstacle drags it (its motion is its velocity, so friction
carries what rests on it); anywhere else it grabs a particle as before.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.mass_spring_contact import (CONTACT_METHODS, PenaltyContact, contact_limit,
                                             penalty_friction, project_and_filter, touching)
from app.physics.obstacles import obstacle_at, penetration_max
from app.physics.spring_forces import Timed
from app.scene import Effect, InputEvent, Param, Try, Unit
from scenes.cloth_contact import BOX_ANGLE, MU, OBSTACLE_SETS, obstacle_layout

# kg/s^2: the cards' cotton strip's lightest particle (a corner, 0.028 kg) has the contact limit
# 2 sqrt(m/k_c) = 19 ms at this stiffness, above the default step of 16.7 ms
PENALTY_K = 300.0

MS_CONTACT_PARAMS = (
    Param("obstacles", "none", str, choices=OBSTACLE_SETS,
          help="what stands below the cloth: ball, tilted box, table, floor, thin bar (drag "
               "them with LMB)"),
    Param("contact", "projection", str, choices=CONTACT_METHODS,
          help="projection: moved out, velocity filtered (Baraff & Witkin); penalty: a spring "
               "of contact_stiffness (it lowers the step limit)", rebuild=False),
    Param("contact_stiffness", PENALTY_K, float, 1.0, 1e7,
          help="penalty: k_c in kg/s^2; its own step limit is 2 sqrt(m/k_c)", rebuild=False),
    Param("mu", MU, float, 0.0, 2.0, help="Coulomb friction coefficient of the obstacles",
          rebuild=False),
    Param("box_angle", BOX_ANGLE, float, -60.0, 60.0,
          help="tilt of the box (obstacles=box) in degrees, positive: right side down",
          rebuild=False),
)
MS_CONTACT_EFFECTS = (
    Effect("collisions", True, "obstacles push the cloth out (projection or penalty: `contact`)"),
    Effect("friction", True, "Coulomb friction on the obstacles' surfaces", amount="mu"),
)
MS_CONTACT_UNITS = {"penetration_max": Unit("px", resolution=0.01),
                    "contact_limit_h": Unit("ms", 1e3)}
STRIP = {"pins": "none", "rows": 2, "spacing": 10.0}     # a cloth seen edge-on: a strip
MS_CONTACT_TRIES = (
    Try("Drape over a ball", {"obstacles": "ball", **STRIP, "cols": 60},
        "a strip falls onto the ball and drapes over it (projection: nothing sinks in); drag "
        "the ball with LMB and the cloth rides on it"),
    Try("Penalty contact, soft", {"obstacles": "ball", **STRIP, "cols": 60,
                                  "contact": "penalty"},
        "a spring pushes the cloth out: it sinks in a few px (penetration_max), and the HUD "
        "gives the contact's step limit 2 sqrt(m/k_c)"),
    Try("Penalty past its limit", {"obstacles": "ball", **STRIP, "cols": 60,
                                   "contact": "penalty", "contact_stiffness": 1e4},
        "k_c = 1e4: the contact's limit (3.3 ms for the strip's corners) is far below h = "
        "16.7 ms: where the strip lands it is thrown off, fast, even with implicit Euler"),
    Try("Pull the tablecloth", {"obstacles": "table", **STRIP, "cols": 64},
        "the cloth settles on the table; grab an end (LMB) and pull: friction holds it back"),
)
MS_CONTACT_COMPARISONS = (
    Try("Slope: friction off vs on", {"obstacles": "box", **STRIP, "cols": 30},
        "a strip lands on a box tilted 20 deg: without friction (A) it slides off; with mu 0.5 "
        "(B), more than tan 20 deg = 0.36, it stays on the slope",
        compare=({"friction": False}, {"friction": True})),
)


class MassSpringContact:
    """Mixed into MassSpringClothScene: obstacles, the contact step, dragging, reports."""

    def build_contact(self) -> None:
        """After the cloth is built: its obstacles, placed below it (the Verlet cloth's sets)."""
        c, p = self.cloth, self.p
        rect = (*c.rest_x[0], c.spacing * (c.cols - 1), c.spacing * (c.rows - 1))
        self.obstacles = obstacle_layout(p["obstacles"], rect, c.spacing, self.world_size,
                                         p["box_angle"])
        self.dragged: int | None = None
        self.drag_target = (0.0, 0.0)
        self.grip = (0.0, 0.0)
        self.last_contacts = 0

    @property
    def colliding(self) -> bool:
        return bool(self.obstacles) and "collisions" in self.on

    @property
    def penalty(self) -> bool:
        return self.colliding and self.p["contact"] == "penalty"

    def sync_contact(self) -> None:
        """After the cloth's force list was rebuilt: the penalty is one more force in it."""
        c = self.cloth
        for ob in self.obstacles:
            if ob.label == "box":
                ob.angle = math.radians(self.p["box_angle"])
        if self.penalty:
            c.spent.setdefault("collisions", 0.0)
            c.calls.setdefault("collisions", 0)
            force = PenaltyContact(self.obstacles, self.p["contact_stiffness"])
            c.ps.forces.append(Timed("collisions", force, c.watch, c.calls))

    def contact_start(self) -> None:
        """Before the integrator's step: where the particles start (for back_to_entry)."""
        self.start = self.cloth.ps.x.copy() if self.colliding and not self.penalty else None

    def contact_step(self, h: float) -> None:
        """After the integrator's step: drag the obstacle; projection (and its friction), or the
        penalty's friction. Nothing at all with collisions off or no obstacles."""
        if not self.obstacles:
            return
        self.move_obstacles(h)
        if not self.colliding:
            return
        c, mu = self.cloth, (self.p["mu"] if "friction" in self.on else None)
        with c.watch("collisions"):
            if self.penalty:
                if mu is not None:
                    penalty_friction(c.ps, self.obstacles, self.p["contact_stiffness"], h, mu)
            else:
                self.last_contacts = project_and_filter(c.ps, self.obstacles, h, mu,
                                                        self.start).count

    # ----- the mouse ----------------------------------------------------------------------------
    def obstacle_at(self, pos: tuple[float, float]) -> int | None:
        """The obstacle a press at pos picks (app/physics/obstacles.py: obstacle_at)."""
        return obstacle_at(self.obstacles, pos)

    def contact_event(self, event: InputEvent) -> bool:
        """Start, move or end an obstacle drag; True if the event was the obstacle's."""
        if event.kind == "mouse_down" and event.button == 1 and self.cloth.grabbed is None:
            k = self.obstacle_at(self.mouse)
            if k is None:
                return False
            cx, cy = self.obstacles[k].center
            self.dragged, self.grip = k, (cx - self.mouse[0], cy - self.mouse[1])
            self.drag_target = (cx, cy)
            return True
        if self.dragged is None:
            return False
        if event.kind == "mouse_move":
            self.drag_target = (self.mouse[0] + self.grip[0], self.mouse[1] + self.grip[1])
        elif event.kind == "mouse_up" and event.button == 1:
            self.dragged = None
        return True

    def move_obstacles(self, h: float) -> None:
        """The dragged obstacle follows the mouse, at most 8 px a step; its motion / h is its
        velocity (friction carries what rests on it); the others stand still."""
        for k, ob in enumerate(self.obstacles):
            ob.velocity = (0.0, 0.0)
            if k == self.dragged:
                (cx, cy), (tx, ty) = ob.center, self.drag_target
                dx, dy = tx - cx, ty - cy
                dist = math.hypot(dx, dy)
                if dist > 8.0:
                    dx, dy = dx * 8.0 / dist, dy * 8.0 / dist
                if dist > 0:
                    ob.move_by(dx, dy)
                    ob.velocity = (dx / h, dy / h)

    # ----- reports ------------------------------------------------------------------------------
    def penalty_limits(self) -> tuple[float, float]:
        """(the contact's own limit 2 sqrt(m/k_c), the bound 2/sqrt(omega_max^2 + k_c/m) on the
        whole cloth's), seconds, for the lightest free particle."""
        c, k = self.cloth, self.p["contact_stiffness"]
        mass = c.ps.mass[c.ps.free[:, 0] > 0]
        mass = mass if mass.size else c.ps.mass
        own = contact_limit(k, mass)
        bound = 2.0 / math.sqrt(self.omega_max ** 2 + k / float(mass.min()))
        return own, bound

    def contact_metrics(self) -> dict:
        c = self.cloth
        movable = c.ps.free[:, 0] > 0
        if not self.colliding:
            contacts = 0
        elif self.penalty:                       # inside, pushed by the spring now
            contacts = int(np.count_nonzero(touching(self.obstacles, c.ps.x, movable, 0.0)))
        else:                                    # moved out in the last step
            contacts = self.last_contacts
        return {
            "contacts": contacts,
            "penetration_max": penetration_max(self.obstacles, c.ps.x, movable),
            "contact_limit_h": self.penalty_limits()[0] if self.penalty else None,
        }

    def contact_hud(self) -> list[str]:
        if not self.obstacles:
            return []
        if not self.colliding:
            return ["collisions off: the cloth passes through the obstacles"]
        m = self.contact_metrics()
        fr = f"mu {self.p['mu']:g}" if "friction" in self.on else "no friction"
        deep = self.shown("penetration_max", m["penetration_max"])
        if not self.penalty:
            # (phrases parted by '  |  ': a row breaks between them at F2, never inside)
            # (Baraff & Witkin's name is in the contact parameter's help and the docstring)
            return [f"contact: projection, velocity filtered  |  {fr}: "
                    f"{m['contacts']} touching, deepest {deep}"]
        own, bound = self.penalty_limits()
        h = self.dt / self.p["substeps"]
        verdict = "below it" if h < own else "past it: unstable in contact"
        return [f"contact: penalty k_c {self.p['contact_stiffness']:g} kg/s^2  |  {fr}: "
                f"{m['contacts']} touching, deepest {deep}",
                f"its limit 2 sqrt(m/k_c) = {own * 1e3:.3g} ms  |  cloth and contact, undamped: >= "
                f"{bound * 1e3:.3g} ms; h = {h * 1e3:.3g} ms, {verdict}"]

    def contact_bounds(self, bounds):
        """bounds grown to hold every obstacle that has finite bounds, inside the world."""
        x, y, w, h = bounds
        x1, y1 = x + w, y + h
        for ob in self.obstacles:
            bx0, by0, bx1, by1 = ob.bounds()
            if all(math.isfinite(v) for v in (bx0, by0, bx1, by1)):
                x, y, x1, y1 = min(x, bx0), min(y, by0), max(x1, bx1), max(y1, by1)
        W, H = self.world_size
        x, y = max(x, 0.0), max(y, 0.0)
        return (x, y, min(x1, W) - x, min(y1, H) - y)

    def draw_contact(self, surface, view) -> None:
        if self.obstacles:
            from app.draw.obstacle_draw import draw_obstacles
            draw_obstacles(surface, view, self.obstacles, self.dragged)

    def hud_lines(self) -> list[str]:
        return super().hud_lines() + self.contact_hud()
