"""A scene file as a Scene: the checked data (app/scenefile/load.py) becomes a PymunkScene
subclass made at run time, so a file runs through the same contract as a scene written in
Python: window and headless, --json, compare mode, plots, clips, record and replay, try cards.

    cls = scene_class("scenes/files/seesaw.toml")     # SceneFileError if it is not accepted
    scene = cls({"stiffness": 800})                   # its sliders are ordinary params

What a file turns into:
  * [world] gives the defaults of the lab's own settings g, iterations, hertz, substeps and seed;
    the effect `gravity` turns gravity off as in every pymunk scene;
  * each [[slider]] is a Param (rebuild=True): build() reads the file's data with every slider's
    value written into the fields it points at, so a change rebuilds the world from the file;
  * [[body]], [[body.shape]], [[joint]] and [[spawner]] become pymunk objects in build_space;
    a body with `mass` spreads it over its shapes by area, and pymunk finds the centre of gravity
    and the moment from them (a `moment` given keeps the centre at the body's origin);
  * [[metric]] are computed from the bodies when metrics() is called (`over` max or min: after
    every step); [[try]] are the cards; [cloth] is a Verlet cloth stepped beside the space.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any, Iterable

import numpy as np
import pygame
import pymunk

from app.draw import pymunk_draw as D
from app.pymunk_scene import PYMUNK_EFFECTS, PYMUNK_PARAMS, PymunkScene
from app.scene import Param, ParamError, Try, common
from app.draw.scenefile_draw import draw_joint
from app.scenefile.checks import WORLD, _targets, coupled_bodies, matches, slider_start
from app.scenefile.cloth_contact import couple_step, deepest, touching
from app.scenefile.load import SceneFileError, load_spec
from app.scenefile.parts import area_of, body_measure, joint_measure, make_shape, shape_area
from app.scenefile.schema import METRIC_HELP, field_key

KINEMATIC_COLOR = (200, 130, 255)
ENERGY_KINDS = ("kinetic_energy", "potential_energy", "energy", "energy_ratio", "energy_drift")
SUMMED = ENERGY_KINDS + ("momentum_x", "momentum_y", "momentum", "count")


def applied(spec: dict, values: dict[str, Any]) -> dict:
    """A copy of the file's data with every slider's value written into its fields."""
    out = copy.deepcopy(spec)
    for s in out["slider"]:
        if s["name"] not in values:
            continue
        sec, key, part = field_key(s["field"])
        value = values[s["name"]]
        for item in _targets(out, sec.name, s["target"]):
            if part is None:
                item[key.name] = value
            else:
                item[key.name] = list(item[key.name] or [0.0, 0.0])
                item[key.name][part] = float(value)
            if sec.name == "body" and key.name in ("mass", "density"):
                item["density" if key.name == "mass" else "mass"] = None
    return out


class FileScene(PymunkScene):
    """Base of every scene made from a file (scene_class sets spec, path and the declarations)."""

    spec: dict = {}
    path: str = ""
    world_keys = ("space", "named", "joints", "spawners", "cloth", "track")
    arrow_name = "body"

    # ----- declarations ---------------------------------------------------------------------------
    @classmethod
    def check_combination(cls, values) -> None:
        """Slider values each in range can still make a file the loader would refuse (a slide
        joint's min above its max, a circle of radius 0): the data with the values written in
        goes through the loader's checks again, before anything reaches pymunk."""
        from app.scenefile.load import check_spec
        from app.scenefile.write import to_data
        try:
            check_spec(to_data(applied(cls.spec, values)), "", cls.path)
        except SceneFileError as e:
            raise ParamError(f"these slider values do not fit the file: {e.message}") from None

    def content_bounds(self) -> tuple[float, float, float, float]:
        return (0.0, 0.0, float(self.world_size[0]), float(self.world_size[1]))

    # ----- building -------------------------------------------------------------------------------
    def build_space(self, space: pymunk.Space) -> None:
        spec = applied(self.spec, self.p)
        self.data = spec
        world = spec["world"]
        space.damping = world["damping"]
        space.collision_slop = world["collision_slop"]
        if world["sleep_time"] is not None:
            space.sleep_time_threshold = world["sleep_time"]
        if world["idle_speed"] is not None:
            space.idle_speed_threshold = world["idle_speed"]
        self.named: dict[str, pymunk.Body] = {}
        self.colors: dict[str, tuple[int, int, int]] = {}
        for b in spec["body"]:
            self.add_body(space, b)
        self.joints: list[tuple[dict, pymunk.Constraint]] = [
            (j, self.add_joint(space, j)) for j in spec["joint"]]
        self.spawners = [{"spec": s, "due": s["start"], "spawned": 0, "removed": 0,
                          "alive": []} for s in spec["spawner"]]
        self.track: dict[str, Any] = {"start": {}, "seen": {},
                                      "coupling": {"impulse": 0.0, "contacts_last": 0}}
        self.coupled = [b["name"] for b in coupled_bodies(spec)]
        self.cloth = self.make_cloth(spec["cloth"])
        self.rebaseline()

    def add_body(self, space: pymunk.Space, b: dict) -> pymunk.Body:
        kind = b["type"]
        if kind == "static":
            body = pymunk.Body(body_type=pymunk.Body.STATIC)
        elif kind == "kinematic":
            body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        elif b["moment"] is not None:
            mass = b["mass"] if b["mass"] is not None else b["density"] * area_of(b["shape"])
            body = pymunk.Body(mass, b["moment"])
        else:
            body = pymunk.Body()           # mass, moment and centre from the shapes' masses
        body.position = tuple(b["position"])
        body.angle = math.radians(b["angle"])
        body.velocity = tuple(b["velocity"])
        body.angular_velocity = math.radians(b["angular_velocity"])
        shapes = [make_shape(body, s) for s in b["shape"]]
        if kind == "dynamic" and b["moment"] is None:
            areas = [shape_area(s) for s in b["shape"]]
            total = sum(areas)
            for shape, area in zip(shapes, areas):
                if b["density"] is not None:
                    shape.density = b["density"]
                else:
                    shape.mass = b["mass"] * area / total
        space.add(body, *shapes)
        self.named[b["name"]] = body
        self.colors[b["name"]] = tuple(b["color"]) if b["color"] else (
            D.STATIC if kind == "static" else KINEMATIC_COLOR if kind == "kinematic" else D.BALL)
        return body

    def end(self, name: str) -> pymunk.Body:
        return self.space.static_body if name == WORLD else self.named[name]

    def add_joint(self, space: pymunk.Space, j: dict) -> pymunk.Constraint:
        a, b = self.end(j["a"]), self.end(j["b"])
        aa, ab = tuple(j["anchor_a"]), tuple(j["anchor_b"])
        kind = j["kind"]
        if kind == "pin":
            c = pymunk.PinJoint(a, b, aa, ab)
        elif kind == "pivot":
            c = (pymunk.PivotJoint(a, b, tuple(j["pivot"])) if j["pivot"] is not None
                 else pymunk.PivotJoint(a, b, aa, ab))
        elif kind == "slide":
            c = pymunk.SlideJoint(a, b, aa, ab, j["min"], j["max"])
        elif kind == "groove":
            c = pymunk.GrooveJoint(a, b, tuple(j["groove_a"]), tuple(j["groove_b"]), ab)
        elif kind == "damped_spring":
            rest = j["rest_length"]
            if rest is None:
                rest = (a.local_to_world(aa) - b.local_to_world(ab)).length
            c = pymunk.DampedSpring(a, b, aa, ab, rest, j["stiffness"], j["damping"])
        elif kind == "damped_rotary_spring":
            c = pymunk.DampedRotarySpring(a, b, math.radians(j["rest_angle"]), j["stiffness"],
                                          j["damping"])
        elif kind == "rotary_limit":
            c = pymunk.RotaryLimitJoint(a, b, math.radians(j["min"]), math.radians(j["max"]))
        else:
            # Chipmunk drives b.w - a.w towards -rate; the file's rate is b's turn relative to a
            c = pymunk.SimpleMotor(a, b, -math.radians(j["rate"]))
        if j["max_force"] is not None:
            c.max_force = j["max_force"]
        c.collide_bodies = j["collide"]
        if j["error_bias"] is not None:
            c.error_bias = j["error_bias"]
        space.add(c)
        return c

    def make_cloth(self, spec: dict | None):
        if spec is None:
            return None
        from app.physics.cloth import Cloth
        from app.scenefile.cloth_contact import obstacles_of
        cloth = Cloth(spec["rows"], spec["cols"], spec["spacing"], tuple(spec["origin"]),
                      "none" if spec["pins"] == "sides" else spec["pins"],
                      self.cloth_effects(spec))
        if spec["pins"] == "sides":          # a band held at both ends
            cloth.lock_cells([(r, c) for r in range(spec["rows"])
                              for c in (0, spec["cols"] - 1)])
        cloth.iterations = spec["iterations"]
        cloth.drag = spec["drag"]
        cloth.gravity = self.gravity()
        cloth.world = (float(self.world_size[0]), float(self.world_size[1]))
        cloth.contact.mu = spec["friction"]
        cloth.set_obstacles(obstacles_of(spec, self.named))
        return cloth

    def cloth_effects(self, spec: dict) -> set[str]:
        """The cloth's rod sets, forces and contact passes: what is off is left out (it costs
        nothing): collisions only with obstacles, friction only above 0."""
        on = {"structural", "drag"}
        on |= {n for n in ("shear", "bending") if spec[n]}
        if "gravity" in self.on:
            on.add("gravity")
        if spec["obstacle"]:
            on.add("collisions")
            if spec["friction"] > 0:
                on.add("friction")
        return on

    def cloth_obstacle_kinds(self) -> list[str]:
        """The kind of each of the cloth's obstacles (a body obstacle: one per shape)."""
        return [ob["kind"] for ob in self.data["cloth"]["obstacle"] for _ in (
            self.named[ob["body"]].shapes if ob["kind"] == "body" else (0,))]

    # ----- stepping -------------------------------------------------------------------------------
    def step(self, h: float) -> None:
        sleep = self.data["world"]["sleep_time"]
        if sleep is not None:
            # at rest for sleep_time and at least 4 substeps (as falling_balls: at hertz 1 a
            # ball spawned at rest fell asleep in mid-air)
            self.space.sleep_time_threshold = max(sleep, 4 * h)
        super().step(h)
        if self.cloth is not None:
            self.cloth.gravity = self.gravity()
            self.cloth.step(h)
            if self.coupled:                 # none named: nothing computed
                couple_step(self, h)
        for sp in self.spawners:        # as falling_balls: remove, then spawn, after the step
            if sp["spec"]["remove_outside"] and sp["alive"]:
                self.remove_outside(sp)
            self.spawn(sp, h)

    def spawn(self, sp: dict, h: float) -> None:
        """The spawner's clock: a ball every `every` seconds while fewer than max_alive of its
        balls are in the world, at a random place within +-spread/2 (seeded)."""
        s = sp["spec"]
        sp["due"] -= h
        while sp["due"] <= 0:
            sp["due"] += s["every"]
            if len(sp["alive"]) >= s["max_alive"]:
                continue
            x = s["position"][0] + self.random.uniform(-0.5, 0.5) * s["spread"][0]
            y = s["position"][1] + self.random.uniform(-0.5, 0.5) * s["spread"][1]
            r, m = s["radius"], s["mass"]
            body = pymunk.Body(m, pymunk.moment_for_circle(m, 0, r))
            body.position = (x, y)
            body.velocity = tuple(s["velocity"])
            shape = pymunk.Circle(body, r)
            shape.friction, shape.elasticity = s["friction"], s["elasticity"]
            self.space.add(body, shape)
            sp["spawned"] += 1
            name = f"{s['name']}{sp['spawned']}"
            self.named[name] = body
            self.colors[name] = tuple(s["color"]) if s["color"] else D.BALL
            sp["alive"].append(name)

    def remove_outside(self, sp: dict) -> None:
        """Remove the spawner's balls whose centre left the world: below it, to a side, or more
        than a world's height above it (a non-finite centre counts as out)."""
        w, h = self.world_size
        r = sp["spec"]["radius"]
        keep = []
        for name in sp["alive"]:
            x, y = self.named[name].position
            if (y <= h + 2 * r) and (y >= -h) and (x >= -2 * r) and (x <= w + 2 * r):
                keep.append(name)
                continue
            body = self.named.pop(name)
            if self.mouse_joint is not None and body in (self.mouse_joint.a, self.mouse_joint.b):
                self.release()
            self.space.remove(body, *body.shapes)
            sp["removed"] += 1
        sp["alive"] = keep

    def advance(self) -> None:
        self.track["coupling"]["impulse"] = 0.0     # summed over this step's substeps
        super().advance()

    def after_step(self) -> None:
        seen = self.track["seen"]
        for m in self.data["metric"]:
            if m["over"] == "now":
                continue
            v = self.measure(m)
            if v is None:
                continue
            old = seen.get(m["name"])
            seen[m["name"]] = v if old is None else (max if m["over"] == "max" else min)(old, v)

    def settings_changed(self, names: set[str]) -> None:
        super().settings_changed(names)
        if "gravity" in names and self.cloth is not None:
            self.cloth.set_effects(self.cloth_effects(self.data["cloth"]))

    def gravity_changed(self) -> None:
        self.rebaseline()

    def rebaseline(self) -> None:
        """The energies at the start (energy_ratio, energy_drift), measured now."""
        for m in self.data["metric"]:
            if m["kind"] in ("energy_ratio", "energy_drift"):
                self.track["start"][m["name"]] = self.energy(self.bodies(m["target"]), m)

    # ----- measuring ------------------------------------------------------------------------------
    def bodies(self, target: str) -> list[pymunk.Body]:
        """The dynamic bodies a metric's target names ("*": all, spawned balls included)."""
        return [b for n, b in self.named.items()
                if matches(target, n) and b.body_type == pymunk.Body.DYNAMIC]

    def energy(self, bodies: list[pymunk.Body], m: dict, part: str = "energy") -> float:
        zero = m["zero_y"] if m["zero_y"] is not None else float(self.world_size[1])
        g = self.gravity()
        total = 0.0
        for b in bodies:
            if part in ("energy", "kinetic_energy"):
                v, w = b.velocity, b.angular_velocity     # (w * w: ** raises OverflowError
                spin = 0.5 * b.moment * (w * w) if math.isfinite(b.moment) else 0   # past 1e154)
                total += 0.5 * b.mass * (v.x * v.x + v.y * v.y) + spin
            if part in ("energy", "potential_energy"):
                total += b.mass * g * (zero - b.local_to_world(b.center_of_gravity).y)
        return total

    def json_unit(self, name: str) -> str:     # a file's metric: the unit of its kind
        kind = next((m["kind"] for m in self.data["metric"] if m["name"] == name), None)
        return METRIC_HELP[kind][0] if kind in METRIC_HELP else ""

    def measure(self, m: dict) -> float | None:
        kind, target = m["kind"], m["target"]
        owner = METRIC_HELP[kind][1]
        if owner == "spawner":
            sp = next(s for s in self.spawners if s["spec"]["name"] == target)
            return sp[kind]
        if owner == "cloth":
            c = self.cloth
            if kind == "pinned_drift":
                return c.pinned_drift()
            if kind == "penetration_max":
                return deepest(self)
            if kind == "contacts":
                return touching(self)
            if kind == "coupling_impulse":
                return self.track["coupling"]["impulse"]
            s = np.concatenate([c.stretch(f).ravel() for f in c.sets["structural"].families])
            return float(s.max() if kind == "max_stretch" else s.mean())
        if owner == "joint":
            values = [joint_measure(kind, c) for j, c in self.joints
                      if j["name"] and matches(target, j["name"])]
            how = m["combine"] or "max"
            return float({"sum": np.sum, "mean": np.mean, "max": np.max, "min": np.min}[how](
                values))
        bodies = self.bodies(target)
        if kind == "count":
            return len(bodies)
        if kind in ("kinetic_energy", "potential_energy", "energy"):
            return self.energy(bodies, m, kind)
        if kind in ("energy_ratio", "energy_drift"):
            e0, e = self.track["start"].get(m["name"]), self.energy(bodies, m)
            if e0 is None or abs(e0) < 1e-12:
                return None
            return e / e0 if kind == "energy_ratio" else (e - e0) / abs(e0)
        if kind.startswith("momentum"):
            px = sum(b.mass * b.velocity.x for b in bodies)
            py = sum(b.mass * b.velocity.y for b in bodies)
            return {"momentum_x": px, "momentum_y": py, "momentum": math.hypot(px, py)}[kind]
        if not bodies:
            return None
        values = [body_measure(kind, b) for b in bodies]
        how = m["combine"] or ("sum" if kind in SUMMED else "mean")
        return float({"sum": np.sum, "mean": np.mean, "max": np.max, "min": np.min}[how](values))

    def metrics(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for m in self.data["metric"]:
            if m["over"] == "now":
                out[m["name"]] = self.measure(m)
            else:
                now = self.measure(m)
                seen = self.track["seen"].get(m["name"])
                both = [v for v in (seen, now) if v is not None]
                out[m["name"]] = ((max if m["over"] == "max" else min)(both) if both else None)
        return out

    def state_arrays(self) -> Iterable[np.ndarray]:
        arrays = [self.body_state()]
        if self.cloth is not None:
            arrays += self.cloth.state_arrays()
        return arrays

    # ----- drawing --------------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, view) -> None:
        if self.cloth is not None:
            from app.draw.cloth_draw import draw_cloth
            from app.draw.obstacle_draw import draw_obstacles
            own = [o for o, ob in zip(self.cloth.contact.obstacles, self.cloth_obstacle_kinds())
                   if ob != "body"]              # a body obstacle is drawn as the body
            if own:
                draw_obstacles(surface, view, own)
            draw_cloth(surface, view, self.cloth)
        for name, body in self.named.items():
            D.draw_shapes(surface, view, body.shapes, self.colors[name])
        for j, c in self.joints:
            draw_joint(surface, view, j["kind"], c)
        self.draw_mouse(surface, view)

    def handle_event(self, event) -> None:
        """The mouse drags a dynamic body (PymunkScene); with a cloth and no body under the
        mouse, it drags the nearest particle as the cloth scene does (dropped, it stays pinned
        where it was let go)."""
        c = self.cloth
        if c is not None and event.kind.startswith("mouse") and (
                c.grabbed is not None or (event.kind == "mouse_down" and event.button == 1
                                          and self.space.point_query_nearest(
                                              event.pos, 5.0, pymunk.ShapeFilter()) is None)):
            if event.kind == "mouse_down":
                cell = c.nearest(event.pos, max(14.0, 1.2 * c.spacing))
                if cell is not None:
                    c.grab(cell, event.pos)
                    return
            elif event.kind == "mouse_move":
                c.move_grab(event.pos)
                return
            elif event.kind == "mouse_up" and event.button == 1:
                c.release(event.pos)
                return
        super().handle_event(event)

    def hud_details(self) -> list[str]:
        return [f"file: {self.path}", "LMB: drag a dynamic body"
                + (" or a particle of the cloth" if self.cloth is not None else "")]


# ----- the class ------------------------------------------------------------------------------
def scene_class(path: str, name: str | None = None) -> type[FileScene]:
    """The Scene subclass that runs the file at `path` (its CLI name: `name`, default the path
    as given). Raises SceneFileError (one line) if the file is not accepted, a try card's
    settings included."""
    spec = load_spec(path)
    world = spec["world"]
    params: list[Param] = [
        common("hertz", default=world["hertz"]),
        common("substeps", default=world["substeps"]),
        common("seed", default=world["seed"]),
    ]
    for prm in PYMUNK_PARAMS:
        default = world["gravity"] if prm.name == "g" else world["iterations"]
        params.append(Param(prm.name, prm.kind(default), prm.kind, prm.lo, prm.hi,
                            help=prm.help, rebuild=prm.rebuild))
    for s in spec["slider"]:
        _, key, _ = field_key(s["field"])
        kind = int if key.kind == "int" else float
        start = slider_start(spec, s)
        params.append(Param(s["name"], kind(start), kind, kind(s["lo"]), kind(s["hi"]),
                            help=s["help"] or f"{s['field']} of {s['target']}"))
    tries, comparisons = [], []
    for t in spec["try"]:
        card = Try(t["label"], dict(t["settings"]), t["watch"],
                   tuple(dict(v) for v in t["compare"] or ()))
        (comparisons if card.compare else tries).append(card)
    scene = spec["scene"]
    about = scene["about"].strip() or scene["title"]
    attrs = {
        "name": name or path, "title": scene["title"], "category": scene["category"],
        "__doc__": about + f"\n\nFile: {name or path} (a scene file: edit it in any text "
                           "editor; python -m app scene check FILE checks it).",
        "params": tuple(params), "effects": PYMUNK_EFFECTS,
        "world_size": (int(scene["world_size"][0]), int(scene["world_size"][1])),
        "spec": spec, "path": name or path, "tries": tuple(tries),
        "comparisons": tuple(comparisons),
    }
    cls = type(f"FileScene[{Path(path).stem}]", (FileScene,), attrs)
    _check_cards(cls, spec, path)
    return cls


def _check_cards(cls: type[FileScene], spec: dict, path: str) -> None:
    """Every card's settings (and each variant's) as the panel and --try will apply them."""
    from app.scenefile.load import Checker, read_text
    for i, t in enumerate(spec["try"]):
        for what, settings in [("settings", t["settings"])] + [
                ("compare", {**t["settings"], **v}) for v in t["compare"] or ()]:
            try:
                cls.resolve(settings)
            except ParamError as e:
                checker = Checker(path, read_text(path))
                raise SceneFileError(path, checker.line(("try", i, what)),
                                     f"try card '{t['label']}': {e}") from None
