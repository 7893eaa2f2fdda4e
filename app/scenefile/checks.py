"""The scene file's cross-checks: what one key cannot say alone (a body's name used twice, a
joint whose end names no body, a dynamic body without a mass, a slider pointing at a key no
target has). app/scenefile/load.py checks each key against the schema first, then calls these
with its Checker `c`, whose `fail(where, message)` raises the one-line error at the line of
`where`.
"""

from __future__ import annotations

import math
import re

from app.scenefile.schema import (MIN_AREA, MIN_SIZE, SECTIONS, Key, field_key,
                                  slider_fields)

WORLD = "world"                 # a joint's a or b that means a fixed point


def check_all(c, spec: dict) -> None:
    """Every cross-check, in the order a reader would fix them."""
    _check_bodies(c, spec)
    _check_joints(c, spec)
    _check_names(c, spec)
    _check_sliders(c, spec)
    _check_metrics(c, spec)
    _check_cloth(c, spec)


SHAPE_NEEDS = {"circle": ("radius",), "box": ("size",), "polygon": ("points",),
               "segment": ("a", "b")}
SHAPE_TAKES = {"circle": {"radius", "offset"}, "box": {"size", "offset", "radius"},
               "polygon": {"points", "radius"}, "segment": {"a", "b", "radius"}}
COMMON_SHAPE = {"kind", "friction", "elasticity", "group"}

JOINT_NEEDS = {"pin": (), "pivot": (), "slide": ("min", "max"), "groove": ("groove_a",
                                                                          "groove_b"),
               "damped_spring": ("stiffness",), "damped_rotary_spring": ("stiffness",),
               "rotary_limit": ("min", "max"), "motor": ("rate",)}
JOINT_TAKES = {"pin": {"anchor_a", "anchor_b"}, "pivot": {"anchor_a", "anchor_b", "pivot"},
               "slide": {"anchor_a", "anchor_b", "min", "max"},
               "groove": {"groove_a", "groove_b", "anchor_b"},
               "damped_spring": {"anchor_a", "anchor_b", "rest_length", "stiffness", "damping"},
               "damped_rotary_spring": {"rest_angle", "stiffness", "damping"},
               "rotary_limit": {"min", "max"}, "motor": {"rate"}}
COMMON_JOINT = {"kind", "name", "a", "b", "max_force", "collide", "error_bias"}


def _given(c, where: tuple) -> set[str]:
    """The keys the file itself wrote in the table at `where` (not filled-in defaults)."""
    return {p[-1] for p in c.lines if len(p) == len(where) + 1 and p[:-1] == where}


MAX_SHAPES = 5000              # shapes in all: a step of a few ms, not of seconds


def _check_bodies(c, spec: dict) -> None:
    shapes = sum(len(b["shape"]) for b in spec["body"])
    if shapes > MAX_SHAPES:
        c.fail(("body",), f"{shapes:,} shapes in all; accepted: at most {MAX_SHAPES:,}")
    seen: dict[str, int] = {}
    for i, body in enumerate(spec["body"]):
        where, what = ("body", i), f"body '{body['name']}'"
        if body["name"] in seen:
            c.fail(where + ("name",), f"{what}: the name is taken by body {seen[body['name']]}"
                   "; accepted: a name no other body has")
        if body["name"] == WORLD:
            c.fail(where + ("name",), f"{what}: \"world\" means a fixed point in joints; "
                   "accepted: another name")
        seen[body["name"]] = i + 1
        dynamic = body["type"] == "dynamic"
        if dynamic and body["mass"] is None and body["density"] is None:
            c.fail(where, f"{what}: a dynamic body needs a mass; accepted: mass = NUMBER or "
                   "density = NUMBER")
        if body["mass"] is not None and body["density"] is not None:
            c.fail(where + ("density",), f"{what}: give mass or density, not both")
        if not dynamic:
            for k in ("mass", "density", "moment"):
                if body[k] is not None:
                    c.fail(where + (k,), f"{what}: a {body['type']} body has no {k}; accepted: "
                           "mass, density and moment on dynamic bodies only")
        if dynamic and not body["shape"] and body["moment"] is None:
            c.fail(where, f"{what}: a dynamic body without shapes needs a moment; accepted: "
                   "a [[body.shape]] or moment = NUMBER")
        for j, shape in enumerate(body["shape"]):
            sw = where + ("shape", j)
            kind = shape["kind"]
            for k in SHAPE_NEEDS[kind]:
                if shape[k] is None or (k == "radius" and shape[k] < MIN_SIZE):
                    key = SECTIONS["body.shape"].key(k)
                    if k == "radius":
                        key = Key(k, "float", lo=MIN_SIZE, hi=key.hi, unit=key.unit)
                    c.fail(sw + ((k,) if shape[k] is not None else ()),
                           f"{what}, shape {j + 1}: a {kind} needs {k}"
                           + (f" of at least {MIN_SIZE:g}" if k == "radius" else "")
                           + f"; accepted: {key.accepted()}")
            for k in _given(c, sw) - COMMON_SHAPE - SHAPE_TAKES[kind]:
                c.fail(sw + (k,), f"{what}, shape {j + 1}: a {kind} has no '{k}'; accepted: "
                       + ", ".join(sorted(COMMON_SHAPE | SHAPE_TAKES[kind])))
        if body["density"] is not None and _area(body) < MIN_AREA:
            c.fail(where + ("density",), f"{what}: its shapes have no area, so a density gives "
                   "no mass; accepted: mass = NUMBER, or shapes with an area")
        if dynamic and body["moment"] is None and body["shape"] and _area(body) < MIN_AREA:
            c.fail(where, f"{what}: its shapes have no area to spread the mass over (segments "
                   "of radius 0); accepted: moment = NUMBER, or a segment radius above 0")


def _area(body: dict) -> float:
    import pymunk
    total = 0.0
    for s in body["shape"]:
        if s["kind"] == "circle":
            total += math.pi * s["radius"] ** 2
        elif s["kind"] == "box":
            total += s["size"][0] * s["size"][1]
        elif s["kind"] == "polygon":
            total += pymunk.area_for_poly([tuple(p) for p in s["points"]], s["radius"])
        else:
            total += pymunk.area_for_segment(tuple(s["a"]), tuple(s["b"]), s["radius"])
    return total


def _check_joints(c, spec: dict) -> None:
    bodies = {b["name"]: b for b in spec["body"]}
    for i, joint in enumerate(spec["joint"]):
        where, kind = ("joint", i), joint["kind"]
        what = f"joint {i + 1} ({kind}" + (f" '{joint['name']}')" if joint["name"] else ")")
        for end in ("a", "b"):
            if joint[end] != WORLD and joint[end] not in bodies:
                c.fail(where + (end,), f"{what}: {end} = \"{joint[end]}\" names no body; "
                       f"accepted: \"world\" or one of " + ", ".join(
                           f"\"{n}\"" for n in list(bodies)[:20]) + (" ..." if len(bodies) > 20
                                                                    else ""))
        if joint["a"] == joint["b"]:
            c.fail(where + ("b",), f"{what}: a and b are the same body; accepted: two bodies")
        ends = [bodies.get(joint[e]) for e in ("a", "b")]
        if all(e is None or e["type"] != "dynamic" for e in ends):
            c.fail(where, f"{what}: neither end is a dynamic body, so it holds nothing; "
                   "accepted: at least one dynamic body")
        for k in JOINT_NEEDS[kind]:
            if joint[k] is None:
                c.fail(where, f"{what}: a {kind} joint needs '{k}'; accepted: "
                       f"{SECTIONS['joint'].key(k).accepted()}")
        for k in _given(c, where) - COMMON_JOINT - JOINT_TAKES[kind]:
            c.fail(where + (k,), f"{what}: a {kind} joint has no '{k}'; accepted: "
                   + ", ".join(sorted(COMMON_JOINT | JOINT_TAKES[kind])))
        if kind in ("slide", "rotary_limit") and joint["min"] > joint["max"]:
            c.fail(where + ("max",), f"{what}: min {joint['min']:g} is above max "
                   f"{joint['max']:g}; accepted: min <= max")
        if kind == "slide" and joint["min"] < 0:
            c.fail(where + ("min",), f"{what}: a slide joint's min is a distance; accepted: "
                   "min from 0")
        if kind == "groove" and joint["groove_a"] == joint["groove_b"]:
            c.fail(where + ("groove_b",), f"{what}: the groove's two ends are one point; "
                   "accepted: two different points")
        if kind == "groove" and joint["a"] == WORLD:
            pass       # a groove on the world: fine, its ends are world points


def _check_names(c, spec: dict) -> None:
    for sec, key in (("joint", "name"), ("spawner", "name"), ("metric", "name"),
                     ("slider", "name"), ("try", "label")):
        seen: set[str] = set()
        for i, item in enumerate(spec[sec]):
            name = item[key]
            if not name:
                continue
            if name in seen:
                c.fail((sec, i, key), f"{sec} {i + 1}: {key} \"{name}\" is given twice; "
                       f"accepted: a {key} no other {sec} has")
            seen.add(name)
    bodies = {b["name"] for b in spec["body"]}
    for i, sp in enumerate(spec["spawner"]):
        clash = next((b for b in bodies if re.fullmatch(re.escape(sp["name"]) + r"\d+", b)),
                     None)
        if clash:
            c.fail(("spawner", i, "name"), f"spawner '{sp['name']}': its balls would be called "
                   f"like body '{clash}'; accepted: another name")


def matches(target: str, name: str) -> bool:
    """A target is a name, 'prefix*' (every name that starts with prefix) or '*' (all)."""
    return name.startswith(target[:-1]) if target.endswith("*") else name == target


def _check_sliders(c, spec: dict) -> None:
    from app.pymunk_scene import PYMUNK_PARAMS
    from app.scene import COMMON_PARAMS
    taken = {p.name for p in PYMUNK_PARAMS + COMMON_PARAMS} | {"gravity"}
    for i, s in enumerate(spec["slider"]):
        where, what = ("slider", i), f"slider '{s['name']}'"
        if s["name"] in taken:
            c.fail(where + ("name",), f"{what}: the name is the lab's own setting; accepted: "
                   "a name other than " + ", ".join(sorted(taken)))
        found = field_key(s["field"])
        if found is None:
            prefix = s["field"].split(".")[0]
            fields = [f for f in slider_fields() if f.startswith(prefix + ".")]
            c.fail(where + ("field",), f"{what}: field \"{s['field']}\" is no number a slider "
                   "can set; accepted: " + (", ".join(fields) if fields else
                                            "SECTION.KEY, SECTION one of world, body, shape, "
                                            "joint, spawner, cloth (e.g. joint.stiffness)"))
        sec, key, part = found
        if s["lo"] >= s["hi"]:
            c.fail(where + ("hi",), f"{what}: lo {s['lo']:g} is not below hi {s['hi']:g}")
        inside = Key(key.name, "float", None, lo=key.lo, hi=key.hi, above=key.above,
                     unit=key.unit)
        for end in ("lo", "hi"):
            v = s[end]
            if (key.lo is not None and (v <= key.lo if key.above else v < key.lo)) or (
                    key.hi is not None and v > key.hi):
                c.fail(where + (end,), f"{what}: {end} {v:g} is outside what {s['field']} "
                       f"accepts; accepted: {inside.accepted()}")
            if key.kind == "int" and not float(v).is_integer():
                c.fail(where + (end,), f"{what}: {end} {v:g}: {s['field']} is an integer")
        items = _targets(spec, sec.name, s["target"])
        if not items:
            c.fail(where + ("target",), f"{what}: target \"{s['target']}\" matches no "
                   f"{_owner(sec.name)}; accepted: a name, \"prefix*\" or \"*\"")
        start = slider_start(spec, s)
        if start is None:
            c.fail(where, f"{what}: its targets do not set {s['field']}, so there is no "
                   "value to start from; accepted: default = NUMBER")
        if not s["lo"] <= start <= s["hi"]:
            c.fail(where + ("default",), f"{what}: its starting value {start:g} is "
                   f"outside lo..hi ({s['lo']:g}..{s['hi']:g}); accepted: a default within them")


def slider_start(spec: dict, slider: dict) -> float | None:
    """A slider's starting value: its `default`, else the file's value of its first target."""
    if slider["default"] is not None:
        return slider["default"]
    found = field_key(slider["field"])
    if found is None:
        return None
    sec, key, part = found
    items = _targets(spec, sec.name, slider["target"])
    value = items[0][key.name] if items else None
    if value is None:
        return None
    return float(value[part] if part is not None else value)


def _owner(section: str) -> str:
    return {"body": "body", "body.shape": "body", "joint": "joint with a name",
            "spawner": "spawner", "cloth": "cloth"}.get(section, section)


def _targets(spec: dict, section: str, target: str) -> list[dict]:
    """The tables a slider's field points at: bodies, the shapes of matching bodies, joints,
    spawners, the world or the cloth."""
    if section == "world":
        return [spec["world"]]
    if section == "cloth":
        return [spec["cloth"]] if spec["cloth"] is not None else []
    if section == "body.shape":
        return [s for b in spec["body"] if matches(target, b["name"]) for s in b["shape"]]
    return [x for x in spec[section] if x.get("name") and matches(target, x["name"])]


def _check_metrics(c, spec: dict) -> None:
    from app.scenefile.schema import METRIC_HELP
    bodies = [b["name"] for b in spec["body"]]
    joints = {j["name"]: j for j in spec["joint"] if j["name"]}
    spawners = {s["name"] for s in spec["spawner"]}
    for i, m in enumerate(spec["metric"]):
        where, what = ("metric", i), f"metric '{m['name']}'"
        owner = METRIC_HELP[m["kind"]][1]
        if owner == "joint" and not any(matches(m["target"], n) for n in joints):
            c.fail(where + ("target",), f"{what}: target \"{m['target']}\" names no joint; "
                   "accepted: " + (", ".join(f"\"{n}\"" for n in joints) or
                                   "a joint's name (give the joint a name = \"...\")"))
        if owner == "spawner" and m["target"] not in spawners:
            c.fail(where + ("target",), f"{what}: target \"{m['target']}\" names no spawner; "
                   "accepted: " + (", ".join(f"\"{n}\"" for n in spawners) or "none: the file "
                                   "has no [[spawner]]"))
        if owner == "cloth" and spec["cloth"] is None:
            c.fail(where + ("kind",), f"{what}: {m['kind']} measures the cloth and the file "
                   "has no [cloth]")
        if owner == "bodies" and m["target"] != "*" and not m["target"].endswith("*") \
                and m["target"] not in bodies:
            c.fail(where + ("target",), f"{what}: target \"{m['target']}\" names no body; "
                   "accepted: a body's name, \"prefix*\" or \"*\"")
        if m["zero_y"] is not None and m["kind"] not in ("potential_energy", "energy",
                                                         "energy_ratio", "energy_drift"):
            c.fail(where + ("zero_y",), f"{what}: zero_y is for the energies only")


OBSTACLE_NEEDS = {"circle": ("position", "radius"), "box": ("position", "size"),
                  "segment": ("a", "b"), "floor": ("y",), "body": ("body",)}
OBSTACLE_TAKES = {"circle": {"position", "radius"}, "box": {"position", "size", "angle"},
                  "segment": {"a", "b", "thickness"}, "floor": {"y"}, "body": {"body"}}
COUPLED_SHAPES = ("circle", "box")       # what app/physics/obstacles.py has for a moving body


def coupled_bodies(spec: dict) -> list[dict]:
    """The bodies the cloth's `couple` names (all of them dynamic: _check_cloth)."""
    cloth = spec["cloth"]
    if cloth is None or not cloth["couple"]:
        return []
    return [b for b in spec["body"] if matches(cloth["couple"], b["name"])]


def _check_cloth(c, spec: dict) -> None:
    """The cloth's obstacles have what their kind needs (and nothing another kind takes); a
    body obstacle names a static body of circle, box and segment shapes; `couple` names
    dynamic bodies of circles and boxes without rounded corners."""
    cloth = spec["cloth"]
    if cloth is None:
        return
    bodies = {b["name"]: b for b in spec["body"]}
    for i, ob in enumerate(cloth["obstacle"]):
        where, kind = ("cloth", "obstacle", i), ob["kind"]
        what = f"cloth obstacle {i + 1} ({kind})"
        for k in OBSTACLE_NEEDS[kind]:
            if ob[k] is None:
                c.fail(where, f"{what}: a {kind} needs '{k}'; accepted: "
                       f"{SECTIONS['cloth.obstacle'].key(k).accepted()}")
        for k in _given(c, where) - {"kind"} - OBSTACLE_TAKES[kind]:
            c.fail(where + (k,), f"{what}: a {kind} has no '{k}'; accepted: "
                   + ", ".join(sorted(OBSTACLE_TAKES[kind] | {"kind"})))
        if kind == "body":
            b = bodies.get(ob["body"])
            if b is None or b["type"] != "static":
                c.fail(where + ("body",), f"{what}: body \"{ob['body']}\" is "
                       + ("no body" if b is None else f"{b['type']}, not static")
                       + "; accepted: the name of a static body: "
                       + (", ".join(f'"{n}"' for n, x in bodies.items() if x["type"] == "static")
                          or "none in this file"))
            bad = next((s["kind"] for s in b["shape"] if s["kind"] == "polygon" or (
                s["kind"] == "box" and s["radius"] > 0)), None)
            if bad:
                c.fail(where + ("body",), f"{what}: body '{b['name']}' has a "
                       + ("polygon" if bad == "polygon" else "box with rounded corners")
                       + ", which the cloth cannot collide with; accepted: a static body of "
                       "circle, box (radius 0) and segment shapes")
    if not cloth["couple"]:
        return
    found = coupled_bodies(spec)
    if not found:
        c.fail(("cloth", "couple"), f"[cloth]: couple \"{cloth['couple']}\" names no body; "
               "accepted: a dynamic body's name, \"prefix*\" or \"*\"")
    for b in found:
        if b["type"] != "dynamic":
            c.fail(("cloth", "couple"), f"[cloth]: couple names body '{b['name']}', which is "
                   f"{b['type']}; accepted: dynamic bodies (a static one is an obstacle: "
                   "[[cloth.obstacle]] kind = \"body\")")
        for s in b["shape"]:
            if s["kind"] not in COUPLED_SHAPES or (s["kind"] == "box" and s["radius"] > 0):
                c.fail(("cloth", "couple"), f"[cloth]: couple names body '{b['name']}', which "
                       f"has a {s['kind']}" + (" with rounded corners" if s["kind"] == "box"
                                               else "")
                       + "; accepted: bodies of circles and boxes (radius 0)")
