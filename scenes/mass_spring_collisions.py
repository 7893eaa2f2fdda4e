"""Mass-spring cloth on obstacles: penalty or projection, and Coulomb friction.

What it shows: the mass-spring cloth (scenes/mass_spring_cloth.py, every setting of it is here
too) seen edge-on, a strip two particles deep let go above an obstacle (the Verlet cloth's:
ball, tilted box, table, floor, thin bar; scenes/cloth_collisions.py shows that cloth on them).
It drapes over the ball, sticks to or slides off the tilted box, lies on the table.

The idea: a particle that went into an obstacle must come out, and there are two ways
(app/physics/mass_spring_contact.py), chosen by `contact` and named in the HUD:
  * projection (the default): after the step it is moved to the surface, and its velocity into
    the obstacle is filtered out, as Baraff & Witkin constrain a particle; nothing is left
    inside (penetration_max 0 but where obstacles overlap), and the step has no new limit;
  * penalty: a spring k_c = contact_stiffness pushes it out, a force like gravity that every
    integrator sees. A spring sinks in (m g / k_c at rest, more when it lands), and it is stiff:
    its own limit on the step is 2 sqrt(m/k_c) (the HUD gives it beside h; a particle pressed
    into it holds at 0.9x that step and is thrown out at 1.1x, tests/test_mass_spring_contact.py),
    and the cloth's highest frequency rises to at most sqrt(omega_max^2 + k_c/m). Here implicit
    Euler steps the contact explicitly too (it is not in its matrix), so it obeys the same limit.
Coulomb friction (`mu`): the sliding velocity loses at most mu times what the contact took from
the normal velocity in the step, and the step's slide with it; on the 20 degree box mu 0.5
(> tan 20 = 0.36) holds the strip, mu 0 lets it slide off.

Controls: LMB inside an obstacle drags it (the cloth on it rides along); LMB elsewhere grabs a
particle; RMB unlocks one; U unlocks all. Effects collisions and friction: off, nothing computed.
"""

from __future__ import annotations

from dataclasses import replace

from app.scene import Try
from scenes.mass_spring_cloth import MassSpringClothScene
from scenes.mass_spring_contact import MS_CONTACT_COMPARISONS, MS_CONTACT_TRIES, STRIP

DEFAULTS = {"obstacles": "ball", **STRIP, "cols": 60}


class MassSpringCollisionsScene(MassSpringClothScene):
    """Mass-spring cloth on obstacles: projection (Baraff & Witkin's filter) or a penalty spring
    (its step limit in the HUD), Coulomb friction.

    LMB inside an obstacle: drag it. LMB elsewhere: grab a particle. RMB: unlock. U: unlock all.
    """

    name = "mass_spring_collisions"
    title = "Mass-spring cloth: collisions"
    params = tuple(replace(p, default=DEFAULTS[p.name]) if p.name in DEFAULTS else p
                   for p in MassSpringClothScene.params)
    tries = MS_CONTACT_TRIES
    comparisons = MS_CONTACT_COMPARISONS + (
        Try("Projection vs penalty", {},
            "the same strip onto the ball: projected (A) it lies on the surface, nothing "
            "inside; pushed by a spring (B) it sinks in by a px or more (penetration_max)",
            compare=({"contact": "projection"}, {"contact": "penalty"})),
    )

    def snapshot(self):
        """The cloth's state and the view's (app/draw/follow.py): a rewind shows the picture of
        its moment, not the start's wide one closing in again."""
        return {"state": super().snapshot(), "follow": getattr(self, "_follow", None)}

    def restore(self, snap) -> None:
        super().restore(None if snap is None else snap["state"])
        if snap is not None:
            self._follow = snap["follow"]

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The strip, room for its ends to hang (half its length) and every obstacle, as it
        starts; then closing in on the strip and the obstacles as it settles (app/draw/follow.py:
        draped on the ball, the strip was a thin rim in two thirds of empty picture)."""
        from app.draw.follow import follow
        c = self.cloth
        cw = c.spacing * (c.cols - 1)
        ox, oy = c.rest_x[0]
        return follow(self, self.contact_bounds((ox - 0.05 * cw, oy - 2 * c.spacing, 1.1 * cw,
                                                 c.spacing * (c.rows + 1) + 0.5 * cw)),
                      c.x, c.spacing)
