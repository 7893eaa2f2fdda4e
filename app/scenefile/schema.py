"""The scene-file format in one table: every section, every key, its type, range and help.

The loader (app/scenefile/load.py) checks a file against it, the writer (write.py) writes in its
order, the scene (scene.py) reads the checked values, the sliders' fields are its numeric keys, and
the format's reference in docs/experiments.md is generated from it (app/docs/blocks.py). A key
that is not here is an error, never ignored.

Units are the lab's: lengths in px at zoom 1 (y down), time in s, angles in DEGREES (turned into
radians for pymunk), masses in the lab's kg.

Ranges are there for two reasons: pymunk (Chipmunk) aborts the whole process on some values
(iterations 0, negative damping) and silently takes others (a negative radius, NaN), so every
number is finite and in range before it reaches pymunk; and a value past them is no classroom
demo (a body a million px away).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

REQUIRED = object()      # a key without a default: the file must give it

# Bounds shared by many keys.
COORD = 1e5              # px: positions and anchors within +-COORD (app/physics/bounds.REACH)
SPEED = 1e5              # px/s
SPIN = 1e5               # deg/s
BIG = 1e9                # stiffness, force, moment: finite and below overflow in a step
MIN_SIZE = 0.01          # px: a circle's radius, a box's side (smaller: pymunk's moment is NaN)
MIN_AREA = 1e-4          # px^2: the least area a dynamic body's mass is spread over


@dataclass(frozen=True)
class Key:
    """One key of a section.

    kind: "float", "int", "bool", "str", "name" (letters, digits, _ and -, starts with a letter),
    "choice" (one of `choices`), "vec2" ([x, y] of finite numbers, each in lo..hi),
    "color" ([r, g, b], 0..255), "points" (a list of at least 3 [x, y]), "settings" (a table of
    slider, parameter or effect names and their values), "variants" (a list of 2 to 4 settings
    tables). Numbers are within lo..hi (inclusive; `above` means strictly above lo).
    `default` None: optional with no value (the help says what then happens)."""

    name: str
    kind: str
    default: Any = REQUIRED
    help: str = ""
    lo: float | None = None
    hi: float | None = None
    above: bool = False
    choices: tuple[str, ...] = ()
    unit: str = ""

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    @property
    def numeric(self) -> bool:
        return self.kind in ("float", "int", "vec2")

    def accepted(self) -> str:
        """What the key accepts, in words (error messages and the docs)."""
        if self.kind in ("float", "int"):
            word = "an integer" if self.kind == "int" else "a number"
            low = f"above {_num(self.lo)}" if self.above else f"from {_num(self.lo)}"
            return f"{word} {low} to {_num(self.hi)}" + (f" ({self.unit})" if self.unit else "")
        if self.kind == "vec2":
            return (f"[x, y], each a number from {_num(self.lo)} to {_num(self.hi)}"
                    + (f" ({self.unit})" if self.unit else ""))
        if self.kind == "choice":
            return "one of " + ", ".join(f'"{c}"' for c in self.choices)
        if self.kind == "bool":
            return "true or false"
        if self.kind == "color":
            return "[r, g, b], each an integer from 0 to 255"
        if self.kind == "points":
            return (f"a list of 3 to 64 points [x, y], each number from {_num(self.lo)} to "
                    f"{_num(self.hi)}, going round a convex shape")
        if self.kind == "name":
            return "a name of letters, digits, _ and - that starts with a letter (at most 40)"
        if self.kind == "settings":
            return "a table of slider, parameter or effect names and values, e.g. { g = 450 }"
        if self.kind == "variants":
            return "a list of 2 to 4 tables of settings, e.g. [{ iterations = 2 }, " \
                   "{ iterations = 20 }]"
        return "text"

    def default_text(self) -> str:
        if self.required:
            return "required"
        if self.default is None:
            return "-"
        if isinstance(self.default, bool):
            return "true" if self.default else "false"
        if isinstance(self.default, str):
            return f'"{self.default}"'
        if isinstance(self.default, (list, tuple)):
            return "[" + ", ".join(_num(v) for v in self.default) + "]"
        return _num(self.default)


def _num(x: Any) -> str:
    if x is None:
        return "any"
    if isinstance(x, float) and x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return f"{x:g}" if isinstance(x, float) else str(x)


@dataclass(frozen=True)
class Section:
    """A table of the file: `[name]` (one) or `[[name]]` (many; `body.shape` sits inside a body)."""

    name: str
    many: bool
    keys: tuple[Key, ...]
    help: str
    required: bool = False

    def key(self, name: str) -> Key | None:
        return next((k for k in self.keys if k.name == name), None)


def _friction() -> Key:
    return Key("friction", "float", 0.5, "Coulomb friction (pymunk multiplies the two shapes')",
               0.0, 10.0)


def _elasticity() -> Key:
    return Key("elasticity", "float", 0.0, "bounciness: 0 none, 1 a perfect bounce (pymunk "
               "multiplies the two shapes')", 0.0, 1.0)


def _color() -> Key:
    return Key("color", "color", None, "drawing colour (default: by body type)")


BODY_TYPES = ("dynamic", "static", "kinematic")
SHAPE_KINDS = ("circle", "box", "polygon", "segment")
JOINT_KINDS = ("pin", "pivot", "slide", "groove", "damped_spring", "damped_rotary_spring",
               "rotary_limit", "motor")
METRIC_KINDS = ("kinetic_energy", "potential_energy", "energy", "energy_ratio", "energy_drift",
                "momentum_x", "momentum_y", "momentum", "x", "y", "angle", "speed",
                "angular_velocity", "count", "joint_distance", "joint_error", "joint_impulse",
                "spawned", "removed", "max_stretch", "mean_stretch", "pinned_drift",
                "penetration_max", "contacts", "coupling_impulse")
# What each metric kind measures, its JSON unit and what `target` names (the docs' table).
METRIC_HELP: dict[str, tuple[str, str, str]] = {
    "kinetic_energy": ("kg px^2/s^2", "bodies", "sum of 1/2 m v^2 + 1/2 I w^2"),
    "potential_energy": ("kg px^2/s^2", "bodies", "sum of m g (zero_y - y): zero at the height "
                         "`zero_y` (y is down; default the world's bottom edge)"),
    "energy": ("kg px^2/s^2", "bodies", "kinetic + potential"),
    "energy_ratio": ("1", "bodies", "energy now / energy at the start (null if that was 0)"),
    "energy_drift": ("1", "bodies", "(energy now - at the start) / |at the start| (null if 0)"),
    "momentum_x": ("kg px/s", "bodies", "sum of m vx"),
    "momentum_y": ("kg px/s", "bodies", "sum of m vy (y is down)"),
    "momentum": ("kg px/s", "bodies", "length of the total momentum"),
    "x": ("px", "bodies", "x of the body's centre of gravity"),
    "y": ("px", "bodies", "y of the body's centre of gravity (y is down)"),
    "angle": ("deg", "bodies", "the body's angle"),
    "speed": ("px/s", "bodies", "the body's speed"),
    "angular_velocity": ("deg/s", "bodies", "the body's rate of turn"),
    "count": ("count", "bodies", "how many bodies match (spawned ones included)"),
    "joint_distance": ("px", "joint", "distance between the joint's two anchors"),
    "joint_error": ("px", "joint", "how far the joint is from holding: pin |d - its length|, "
                    "pivot d, slide and groove the distance past their range; 0 for the others"),
    "joint_impulse": ("kg px/s", "joint", "the impulse the joint applied in the last "
                      "step (divide by dt for its force)"),
    "spawned": ("count", "spawner", "bodies the spawner has made"),
    "removed": ("count", "spawner", "the spawner's bodies removed after leaving the world"),
    "max_stretch": ("1", "cloth", "largest |length/rest - 1| of the cloth's rods"),
    "mean_stretch": ("1", "cloth", "mean |length/rest - 1| of the cloth's rods"),
    "pinned_drift": ("px", "cloth", "largest distance a pinned particle moved"),
    "penetration_max": ("px", "cloth", "deepest cloth particle inside an obstacle or a coupled "
                        "body after the step (what the projection left)"),
    "contacts": ("count", "cloth", "cloth particles touching an obstacle or a coupled body"),
    "coupling_impulse": ("kg px/s", "cloth", "|momentum| the cloth and the coupled bodies "
                         "exchanged in the last step (at rest on the cloth: M g dt)"),
}
FIELD_SECTIONS = ("world", "body", "shape", "joint", "spawner", "cloth")

SCHEMA: tuple[Section, ...] = (
    Section("scene", False, (
        Key("title", "str", REQUIRED, "the title in the menu and the window"),
        Key("about", "str", "", "what the scene shows and what to try: the help overlay (F1) "
            "and the menu show it; its first paragraph is the summary"),
        Key("category", "str", "Scene files", "the menu's heading it goes under"),
        Key("world_size", "vec2", [960.0, 720.0], "the area the scene draws in (the window "
            "scales it to fit)", 100.0, 4000.0, unit="px"),
    ), "what the scene is called and says about itself", required=True),
    Section("world", False, (
        Key("gravity", "float", 900.0, "downwards acceleration (the slider `g`; the effect "
            "`gravity` turns it off)", 0.0, 5000.0, unit="px/s^2"),
        Key("damping", "float", 1.0, "fraction of every body's velocity kept per second "
            "(1 = no air drag)", 0.0, 1.0),
        Key("iterations", "int", 10, "pymunk solver iterations per step (the slider "
            "`iterations`)", 1, 200),
        Key("hertz", "int", 60, "fixed steps per simulated second (the slider `hertz`)", 1,
            1000),
        Key("substeps", "int", 1, "substeps per step (the slider `substeps`)", 1, 50),
        Key("sleep_time", "float", None, "seconds at rest before bodies fall asleep (none: "
            "nothing sleeps)", 0.01, 60.0, unit="s"),
        Key("idle_speed", "float", None, "bodies slower than this count as at rest for sleeping "
            "(none: pymunk's guess, gravity x the step)", 0.0, SPEED, unit="px/s"),
        Key("collision_slop", "float", 0.1, "overlap pymunk allows between resting shapes", 0.0,
            10.0, unit="px"),
        Key("seed", "int", 0, "seed of the spawners' random positions (the slider `seed`)", 0,
            2**31 - 1),
    ), "the pymunk space and the clock; every key has a default, so the table may be left out"),
    Section("body", True, (
        Key("name", "name", REQUIRED, "how joints, sliders and metrics find it (unique)"),
        Key("type", "choice", "dynamic", "dynamic moves under forces; static never moves; "
            "kinematic moves at its own velocity, pushed by nothing", choices=BODY_TYPES),
        Key("position", "vec2", [0.0, 0.0], "where the body's origin starts", -COORD, COORD,
            unit="px"),
        Key("angle", "float", 0.0, "its starting angle (clockwise on screen, y is down)", -3600.0,
            3600.0, unit="deg"),
        Key("velocity", "vec2", [0.0, 0.0], "its starting velocity", -SPEED, SPEED, unit="px/s"),
        Key("angular_velocity", "float", 0.0, "its starting rate of turn", -SPIN, SPIN,
            unit="deg/s"),
        Key("mass", "float", None, "a dynamic body's mass: give `mass` or `density`", 1e-6, BIG,
            unit="kg"),
        Key("density", "float", None, "mass per px^2 of its shapes' area, instead of `mass`",
            1e-9, 1e6, unit="kg/px^2"),
        Key("moment", "float", None, "moment of inertia (default: computed from the shapes, "
            "the mass spread by area)", 1e-6, 1e15, unit="kg px^2"),
        _color(),
    ), "a rigid body with its shapes (`[[body.shape]]` below it); static bodies need no mass"),
    Section("body.shape", True, (
        Key("kind", "choice", REQUIRED, "the shape", choices=SHAPE_KINDS),
        Key("radius", "float", 0.0, f"circle: its radius (at least {MIN_SIZE:g}); segment: its "
            "thickness / 2; "
            "box and polygon: rounded corners", 0.0, 1e4, unit="px"),
        Key("size", "vec2", None, "box: width and height", MIN_SIZE, 2 * COORD, unit="px"),
        Key("offset", "vec2", [0.0, 0.0], "circle and box: centre relative to the body's "
            "origin", -COORD, COORD, unit="px"),
        Key("points", "points", None, "polygon: its corners relative to the body's origin",
            -COORD, COORD, unit="px"),
        Key("a", "vec2", None, "segment: one end, relative to the body's origin", -COORD, COORD,
            unit="px"),
        Key("b", "vec2", None, "segment: the other end", -COORD, COORD, unit="px"),
        _friction(),
        _elasticity(),
        Key("group", "int", 0, "shapes with the same group above 0 never collide (links of a "
            "chain); 0 collides with everything", 0, 10000),
    ), "a collision shape fixed to the body above it"),
    Section("joint", True, (
        Key("kind", "choice", REQUIRED, "pin: fixed distance; pivot: a shared point; slide: "
            "distance between min and max; groove: b's anchor slides along a groove on a; "
            "damped_spring; damped_rotary_spring; rotary_limit: relative angle between min and "
            "max; motor: a constant relative rate of turn", choices=JOINT_KINDS),
        Key("name", "str", "", "how sliders and metrics find it"),
        Key("a", "str", REQUIRED, "a body's name, or \"world\" (a fixed point: its anchor is in "
            "world coordinates)"),
        Key("b", "str", REQUIRED, "the other body's name, or \"world\""),
        Key("anchor_a", "vec2", [0.0, 0.0], "the anchor on a, relative to its origin", -COORD,
            COORD, unit="px"),
        Key("anchor_b", "vec2", [0.0, 0.0], "the anchor on b, relative to its origin", -COORD,
            COORD, unit="px"),
        Key("pivot", "vec2", None, "pivot: the shared point in world coordinates, instead of "
            "the anchors", -COORD, COORD, unit="px"),
        Key("min", "float", None, "slide: least distance (px); rotary_limit: least relative "
            "angle (deg)", -COORD, COORD),
        Key("max", "float", None, "slide: greatest distance (px); rotary_limit: greatest "
            "relative angle (deg)", -COORD, COORD),
        Key("groove_a", "vec2", None, "groove: one end of the groove on a", -COORD, COORD,
            unit="px"),
        Key("groove_b", "vec2", None, "groove: its other end", -COORD, COORD, unit="px"),
        Key("rest_length", "float", None, "damped_spring: its rest length (default: the "
            "anchors' distance at the start)", 0.0, 2 * COORD, unit="px"),
        Key("stiffness", "float", None, "damped springs: stiffness (required)", 0.0, BIG,
            unit="N/px"),
        Key("damping", "float", 0.0, "damped springs: damping", 0.0, BIG),
        Key("rest_angle", "float", 0.0, "damped_rotary_spring: relative angle at rest", -3600.0,
            3600.0, unit="deg"),
        Key("rate", "float", None, "motor: relative rate of turn b - a (required)", -SPIN, SPIN,
            unit="deg/s"),
        Key("max_force", "float", None, "the most force the joint may apply (default: no limit;"
            " a motor's torque limit)", 0.0, BIG, above=True),
        Key("collide", "bool", True, "whether the two bodies still collide with each other"),
        Key("error_bias", "float", None, "fraction of a joint's error left after one second "
            "(default pymunk's 0.0018; 0 corrects all of it every step)", 0.0, 1.0),
    ), "a constraint between two bodies (or a body and the world)"),
    Section("spawner", True, (
        Key("name", "name", "ball", "its balls are called name1, name2, ... (sliders and "
            "metrics find them with \"name*\")"),
        Key("every", "float", 0.5, "seconds between two balls", 0.001, 3600.0, unit="s"),
        Key("start", "float", 0.0, "seconds before the first ball", 0.0, 3600.0, unit="s"),
        Key("position", "vec2", REQUIRED, "where balls appear (the centre of the area)", -COORD,
            COORD, unit="px"),
        Key("spread", "vec2", [0.0, 0.0], "balls appear at random within +-spread/2 of the "
            "position (seeded by `seed`)", 0.0, COORD, unit="px"),
        Key("max_alive", "int", 100, "no new ball while this many of its balls are in the world",
            1, 2000),
        Key("radius", "float", 10.0, "ball radius", 1.0, 1000.0, unit="px"),
        Key("mass", "float", 1.0, "ball mass", 1e-6, BIG, unit="kg"),
        _friction(),
        _elasticity(),
        Key("velocity", "vec2", [0.0, 0.0], "velocity of a new ball", -SPEED, SPEED,
            unit="px/s"),
        Key("remove_outside", "bool", True, "remove balls that leave the world (below it, to a "
            "side, or a world's height above it)"),
        _color(),
    ), "drops a ball every so often"),
    Section("slider", True, (
        Key("name", "name", REQUIRED, "the parameter's name (the panel, --set NAME=VALUE)"),
        Key("field", "str", REQUIRED, "SECTION.KEY it sets, e.g. \"shape.elasticity\", "
            "\"joint.stiffness\", \"body.velocity.x\"; SECTION is world, body, shape, joint, "
            "spawner or cloth, KEY a number key of that section"),
        Key("target", "str", "*", "which ones: a name (body for body and shape keys, joint, "
            "spawner), \"ball*\" for every one whose name starts with ball, \"*\" for all"),
        Key("lo", "float", REQUIRED, "the slider's least value (within the key's own range)",
            -BIG, BIG),
        Key("hi", "float", REQUIRED, "its greatest value", -BIG, BIG),
        Key("default", "float", None, "its starting value (default: the file's value of the "
            "first target)", -BIG, BIG),
        Key("help", "str", "", "one line on what it changes"),
    ), "a parameter in the panel and on the command line that points at fields of the file; a "
       "change rebuilds the world from the file with the new value"),
    Section("try", True, (
        Key("label", "str", REQUIRED, "the card's button text (--try LABEL)"),
        Key("settings", "settings", {}, "what it sets: the defaults plus these"),
        Key("watch", "str", REQUIRED, "one line: what to watch for"),
        Key("compare", "variants", None, "a comparison: each pane's own settings, side by side "
            "(--compare)"),
    ), "a \"try this\" card: a one-click experiment"),
    Section("metric", True, (
        Key("name", "name", REQUIRED, "its name in the HUD, --json, --csv and --plot"),
        Key("kind", "choice", REQUIRED, "what it measures (the table below)",
            choices=METRIC_KINDS),
        Key("target", "str", "*", "bodies: a name, \"ball*\" or \"*\" (every dynamic body); "
            "joint: a joint's name or \"link*\"; spawner: a spawner's name; cloth: unused"),
        Key("combine", "choice", "", "several bodies or joints: sum, mean, max or min (default: "
            "sum for energies, momenta and count, max for joints, mean for the rest)",
            choices=("", "sum", "mean", "max", "min")),
        Key("over", "choice", "now", "now, or the largest or least seen since the start",
            choices=("now", "max", "min")),
        Key("zero_y", "float", None, "potential energy: the height where it is zero (default "
            "the world's bottom edge)", -COORD, COORD, unit="px"),
        Key("help", "str", "", "one line on what it shows"),
    ), "a number the HUD, --json, --csv and the live plots report"),
    Section("cloth", False, (
        Key("rows", "int", REQUIRED, "particles down", 2, 80),
        Key("cols", "int", REQUIRED, "particles across", 2, 80),
        Key("spacing", "float", 20.0, "rest distance between neighbours", 1.0, 200.0,
            unit="px"),
        Key("origin", "vec2", [300.0, 100.0], "the top-left particle", -COORD, COORD, unit="px"),
        Key("pins", "choice", "top", "which particles are pinned (sides: the first and last "
            "columns, a band held at both ends)", choices=("top", "corners", "sides", "none")),
        Key("iterations", "int", 10, "constraint sweeps per substep (Jakobsen)", 1, 200),
        Key("drag", "float", 0.01, "fraction of velocity lost per 1/60 s", 0.0, 1.0),
        Key("shear", "bool", False, "diagonal rods too"),
        Key("bending", "bool", False, "skip-one rods too"),
        Key("mass", "float", 1.0, "the whole cloth's mass, shared by its particles (what a "
            "coupled body feels)", 1e-6, BIG, unit="kg"),
        Key("friction", "float", 0.0, "Coulomb friction of the cloth on its obstacles "
            "(0: none, and the friction pass is not computed)", 0.0, 10.0),
        Key("couple", "str", "", "the dynamic bodies the cloth is coupled with, both ways: a "
            "name, \"ball*\" or \"*\" (their circle and box shapes); \"\": none"),
        Key("coupling", "choice", "two-way", "two-way: the cloth pushes the bodies back; "
            "one-way: only the bodies push the cloth", choices=("two-way", "one-way")),
        _color(),
    ), "a Verlet cloth (app/physics/cloth.py) beside the bodies; it falls with the world's "
       "gravity, is kept out of its `[[cloth.obstacle]]`s (Jakobsen's projection) and pushes "
       "and is pushed by the bodies named in `couple` (app/physics/coupling.py)"),
    Section("cloth.obstacle", True, (
        Key("kind", "choice", REQUIRED, "circle, box (turned by `angle`), segment (a capsule), "
            "floor (everything below `y`), or body: the circle, box and segment shapes of a "
            "static `[[body]]` (the same solid for the balls and the cloth)",
            choices=("circle", "box", "segment", "floor", "body")),
        Key("position", "vec2", None, "circle and box: the centre", -COORD, COORD, unit="px"),
        Key("radius", "float", None, "circle: its radius", MIN_SIZE, 1e4, unit="px"),
        Key("size", "vec2", None, "box: width and height", MIN_SIZE, 2 * COORD, unit="px"),
        Key("angle", "float", 0.0, "box: its angle (clockwise on screen)", -3600.0, 3600.0,
            unit="deg"),
        Key("a", "vec2", None, "segment: one end", -COORD, COORD, unit="px"),
        Key("b", "vec2", None, "segment: the other end", -COORD, COORD, unit="px"),
        Key("thickness", "float", 2.0, "segment: every point this close to it is solid", 0.0,
            1e4, unit="px"),
        Key("y", "float", None, "floor: its height (y is down: the solid is below)", -COORD,
            COORD, unit="px"),
        Key("body", "str", None, "body: the name of a static body"),
    ), "a solid the cloth is kept out of (app/physics/obstacles.py); it does not move and the "
       "pymunk bodies do not see it (kind body: they see that body)"),
)

SECTIONS = {s.name: s for s in SCHEMA}


def section(name: str) -> Section:
    return SECTIONS[name]


def field_key(field: str) -> tuple[Section, Key, int | None] | None:
    """A slider's field "SECTION.KEY" or "SECTION.KEY.x|y": the section, the key and the
    component (0, 1 or None); None if it names no number key a slider may set."""
    parts = field.split(".")
    if len(parts) not in (2, 3) or parts[0] not in FIELD_SECTIONS:
        return None
    sec = SECTIONS["body.shape" if parts[0] == "shape" else parts[0]]
    key = sec.key(parts[1])
    if key is None or not key.numeric:
        return None
    if key.kind == "vec2":
        if len(parts) != 3 or parts[2] not in ("x", "y"):
            return None
        return sec, key, "xy".index(parts[2])
    if len(parts) != 2:
        return None
    if sec.name == "world" and key.name in ("gravity", "iterations", "hertz", "substeps", "seed"):
        return None     # those are the sliders g, iterations, hertz, substeps, seed already
    return sec, key, None


def slider_fields() -> list[str]:
    """Every field a slider may point at."""
    out = []
    for prefix in FIELD_SECTIONS:
        sec = SECTIONS["body.shape" if prefix == "shape" else prefix]
        for key in sec.keys:
            names = ([f"{prefix}.{key.name}.x", f"{prefix}.{key.name}.y"] if key.kind == "vec2"
                     else [f"{prefix}.{key.name}"])
            out += [n for n in names if key.numeric and field_key(n) is not None]
    return out
