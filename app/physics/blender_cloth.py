"""Blender's cloth presets and how their numbers become the lab's (px, s, kg).

MATERIALS holds Blender's own cloth presets, from the files
scripts/presets/cloth/{Cotton,Denim,Leather,Rubber,Silk}.py of the blender/blender repository
(vertex mass, tension, compression, shear and bending stiffness, spring damping, air damping).
How Blender turns them into forces is in source/blender/simulation/intern/SIM_mass_spring.cc
(cloth_calc_spring_force) and implicit_solver.cc: a spring's stiffness is k = stiffness /
avg_spring_len (a force per unit *strain*, the same for any mesh resolution); a structural spring
pulls with the tension stiffness when stretched, and resists compression only through Choi &
Ko's buckling curve ("Stable but Responsive Cloth", 2002; the default) or, with `resist_compress`
on, as a linear spring of the compression stiffness; a shear spring resists no compression at
all (its compression stiffness is 0). Blender's default bending model is *angular* (a spring on
the angle between neighbouring faces, damped by `bending_damping`); its older *linear* model has
skip-one bending springs of stiffness kb = bending / (20 avg_spring_len) that act only when
compressed, along Choi & Ko's curve f = max(kb fb(|l|), cb (|l| - r)) whose linear part has the
slope cb = kb x bending_damping: there `cb` is a stiffness, not a damping (those springs have no
damping: "XXX damping not supported"). The damping value is the spring's damping coefficient, air
drag is f = -0.01 air_damping v, and gravity is 0.001 x 9.81 (Blender's solver does not count
time in seconds).
**This lab's simplification (ours, not Blender's):** every spring is a plain damped Hooke
spring, in tension and compression alike: structural springs with the preset's tension value
when stretched and its compression value when compressed, shear and skip-one bending springs with
one stiffness each (bending scaled as Blender's linear model, / 20); spring damping on structural
and shear springs, and on the bending springs a damping rate of BENDING_DAMPING x its stiffness
in Blender time (0.5, Blender's default bending_damping: a damping in its angular model, borrowed
here for our linear springs).
Mapping to this lab's units (px, s, kg; g = 900 px/s^2):
  * length: Blender's springs are taken as 1/16 m (a 2 m plane of 32 x 32 cells), so one
    Blender metre = PX_PER_M = 256 px and a Blender spring = REF_CELL = 16 px;
  * time: one Blender time unit = TAU = sqrt(256 px x 0.00981 / 900 px/s^2) = 0.0528 s, the
    choice that turns Blender's gravity into the lab's g;
  * so stiffness k = K_UNIT x stiffness / spacing with K_UNIT = 256 / TAU^2 = 9.17e4 (a
    particle's weight strains a spring exactly as much as in Blender: m g / (k r) =
    0.00981 m / stiffness), damping k_d = damping / TAU, air k = 0.01 air_damping / TAU;
  * mass: Blender's vertex mass is the mass of one REF_CELL x REF_CELL cell, so the density is
    mass / 256 px^2 and a particle's mass is its area times that.
In these units a particle's weight strains a spring by 0.00981 x mass / tension: 0.03 % for silk,
0.02 % for cotton and denim, 0.005 % for leather, 0.2 % for rubber (heavy and soft).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields


# ----- Blender's units -> the lab's (see the module docstring) ------------------------------------
G_LAB = 900.0                        # px/s^2, the lab's gravity (README: ~9.8 m/s^2 at ~92 px/m)
BLENDER_G = 9.81 * 0.001             # Blender's cloth solver scales gravity by 0.001
PX_PER_M = 256.0                     # one Blender metre
REF_CELL = 16.0                      # px: a Blender spring (1/16 m); a cell of it weighs `mass`
TAU = math.sqrt(PX_PER_M * BLENDER_G / G_LAB)      # seconds per Blender time unit (0.0528)
K_UNIT = PX_PER_M / TAU ** 2         # Blender stiffness -> kg px/s^2 per unit strain (9.17e4)
# Blender's default bending_damping (DNA_cloth_defaults.h): a damping in its angular bending model,
# the slope cb = kb x this of Choi & Ko's curve in its linear one; ours: damping c = .5 TAU k
BENDING_DAMPING = 0.5


@dataclass(frozen=True)
class Material:
    """A Blender cloth preset in Blender's own numbers."""

    mass: float            # vertex mass, kg
    tension: float         # stiffness when stretched
    compression: float     # stiffness when compressed
    shear_stiffness: float
    bending_stiffness: float
    spring_damping: float  # tension = compression = shear damping in every preset
    air_damping: float


MATERIALS: dict[str, Material] = {     # scripts/presets/cloth/*.py (blender/blender)
    "cotton": Material(0.3, 15, 15, 15, 0.5, 5, 1),
    "denim": Material(1, 40, 40, 40, 10, 25, 1),
    "leather": Material(0.4, 80, 80, 80, 150, 25, 1),
    "rubber": Material(3, 15, 15, 15, 25, 25, 1),
    "silk": Material(0.15, 5, 5, 5, 0.05, 0, 1),
}
MATERIAL_KEYS = tuple(f.name for f in fields(Material))
# kg/px^2: the wind's pressure is wind_strength x this per px^2 of cloth, for every material
# (cotton's density: wind_strength is the acceleration it gives cotton)
WIND_DENSITY = MATERIALS["cotton"].mass / REF_CELL ** 2


def material_settings(name: str) -> dict[str, float]:
    """The preset `name` as a dict of slider values (mass, tension, ..., air_damping)."""
    m = MATERIALS[name]
    return {k: float(getattr(m, k)) for k in MATERIAL_KEYS}


def spring_constants(values: dict, spacing: float) -> dict[str, float]:
    """Lab-unit constants from Blender-unit settings (dict with MATERIAL_KEYS) at this spacing:
    stiffness in kg/s^2, damping in kg/s, density in kg/px^2."""
    k_bending = K_UNIT * values["bending_stiffness"] / (20.0 * spacing)
    return {
        "k_tension": K_UNIT * values["tension"] / spacing,
        "k_compression": K_UNIT * values["compression"] / spacing,
        "k_shear": K_UNIT * values["shear_stiffness"] / spacing,
        "k_bending": k_bending,
        "kd": values["spring_damping"] / TAU,
        "kd_bending": BENDING_DAMPING * TAU * k_bending,
        "air": 0.01 * values["air_damping"] / TAU,
        "density": values["mass"] / REF_CELL ** 2,
    }
