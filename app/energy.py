"""Energy bars (as PhET's): what a scene's energy is made of, where each part is zero, and how much
has gone since the start.

A scene that has an energy returns an `Energies` from `energies()` (the Scene default is None:
no bars, and the window says why). The parts are the scene's own sums (kinetic, potential in
gravity, elastic in springs...), in the scene's unit; `start` is the total when the run began
(or when it last re-based: a reset, a release, a change of g). What is not in the parts any more
is `lost`: start - total, to damping, drag, the rods' projection, inelastic contacts, or (with a
minus sign) energy put in by the mouse. A scene that measures what some causes took out, where
they act (the trampoline: its drag, its coupling), names them in `removed`, each zero at the
start; `lost` is then drawn split into those and the `other` rest. Plain data: the window draws
it (app/draw/energy_bars.py).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Energies:
    parts: tuple[tuple[str, float], ...]   # (name as a class reads it, value in the scene's unit)
    start: float                           # the total at the start of the run
    zero: str                              # where each part is zero, in words
    losses: str                            # where energy goes, in words ("drag, the mouse")
    unit: str = "J"                        # the unit the bars are written in
    scale: float = 1.0                     # scene units per shown unit (the mass-spring J: 256^2)
    removed: tuple[tuple[str, float], ...] = ()   # taken out by named causes since the start,
                                                  # measured where they act (0 at the start)

    @property
    def total(self) -> float:
        return float(sum(v for _, v in self.parts))

    @property
    def lost(self) -> float:
        """start - total: > 0 lost (damping, drag, contacts); < 0 put in (the mouse)."""
        return self.start - self.total

    @property
    def other(self) -> float:
        """What is lost beyond the named `removed` parts (all of `lost` when there are none)."""
        return self.lost - float(sum(v for _, v in self.removed))

    def shown(self, value: float) -> float:
        return value / self.scale


__all__ = ["Energies"]
