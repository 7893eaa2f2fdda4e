"""The Scene contract: what every scene of the lab declares and which hooks the shell calls.

A scene is a class that
  * names itself (`name` for the command line, `title`, `category`) and documents itself in its
    docstring (the window's help overlay shows it: say what the scene shows and list its controls);
  * declares its tunable `params` (each a `Param`: default, type, range or choices, one-line help)
    and the physical `effects` it can simulate (each an `Effect`, on or off);
  * builds its world in `build()` from `self.p` (resolved parameter values) and `self.on` (the set of
    effects that are on), and advances it in `step(h)`.

The shell (window, headless runner, tests, benchmarks) drives every scene the same way:

    scene = SceneClass({"iterations": 5, "shear": False})   # validated, then build()
    scene.advance()                                        # one fixed step = `substeps` x step(h)
    scene.handle_event(InputEvent("mouse_down", pos=(x, y), button=1))
    scene.draw(surface, view)                              # view: app.draw.view.View
    scene.metrics(), scene.state_hash(), scene.is_finite()

Every hook has a do-nothing default, so a scene overrides only what it uses.
Coordinates: world units are pixels at zoom 1, y grows downwards, gravity is (0, +g).

The order in which the shell calls the hooks:

    __init__(overrides)  -> resolve() (validate) -> build()        also on R / reset(): build()
    every fixed step:    advance() = substeps x step(dt/substeps), then after_step() once
    between steps:       handle_event(event)       (mouse and key events, world coordinates)
                         set(name, value)          (the panel) -> build() if the setting needs a
                                                   rebuild, else settings_changed({name})
    every frame:         draw(surface, view), metrics(), hud_lines(), effect_costs();
                         hud_details() too while the HUD shows its second page (F4)
    a "try this" card:   apply_card(card): the defaults plus the card's settings, then build()
    layout:              content_bounds()          (what draw() covers, world coordinates);
                         fit_to(size) first for a scene whose content_fills its room
    overlays:            arrows() after every step, only while the arrows overlay is on;
                         reference_error() for a compare pane's label (app/compare.py)
    non-finite guard:    is_finite(); snapshot() every so often; restore(snap) on a blow-up,
                         then blowup_hint() for the message
    determinism tests:   state_hash()
"""

from __future__ import annotations

import copy
import hashlib
import random
from dataclasses import dataclass
from typing import Any, Iterable, Mapping

import numpy as np

from app.keys import SHELL_KEY_NAMES
from app.params import (COMMON_PARAMS, Effect, Param, ParamError,  # noqa: F401 (re-exported)
                        common, plain_number, shown_text)
from app.units import PLAIN, Unit
from app.units import shown as shown_in
from app.vectors import Arrows


class SceneError(RuntimeError):
    """A failure the scene reports to the person at the keyboard instead of crashing: e.g. a
    student's exercise code raised. The window pauses and shows the message (the scene stays
    open); a headless run prints it on stderr and exits 1. The message may span lines (a
    student's traceback: their file and line)."""


# The shell's keys, as pygame names them (from the one key table, app/keys.py): they
# pause, step, reset, help, ... in the window, and never reach a scene (live or replayed).
SHELL_KEYS = SHELL_KEY_NAMES

# An event is due at step k when t <= k * dt + EVENT_SLACK: times written by hand or rounded in a
# file still land on the step they name (1 microsecond is far below any dt the lab accepts).
EVENT_SLACK = 1e-6


@dataclass(frozen=True)
class Try:
    """A one-click experiment from a scene's help text ("try this" card in the panel): a label,
    the settings it applies (names as `--set` takes them), and one line on what to watch for.
    A card with `compare` is a comparison: the scene's defaults plus `settings` in every pane,
    plus each variant's own settings in its pane (`--compare`, app/compare.py)."""

    label: str
    settings: Mapping[str, Any]
    watch: str
    compare: tuple[Mapping[str, Any], ...] = ()

    def changes(self) -> str:
        """What the card sets, as `--set` writes it: 'material=leather, integrator=...'; a
        comparison's variants joined by ' vs '."""
        shared = ", ".join(f"{k}={setting_text(v)}" for k, v in self.settings.items())
        if not self.compare:
            return shared
        versus = " vs ".join(variant_text(v) for v in self.compare)
        return versus + (f" (all: {shared})" if shared else "")

    def describe(self) -> str:
        """The card's whole promise in one line: what it sets (the rest at the defaults) and
        what to watch for."""
        return f"{self.label}: sets {self.changes()} (the rest at the defaults). {self.watch}"


def setting_text(value: Any) -> str:
    """A setting's value as `--set` writes it (on/off for effects and switches)."""
    return ("on" if value else "off") if isinstance(value, bool) else f"{value}"


def variant_text(settings: Mapping[str, Any]) -> str:
    """A variant as `--compare` takes it: 'substeps=1,iterations=10'."""
    return ",".join(f"{k}={setting_text(v)}" for k, v in settings.items())


@dataclass
class InputEvent:
    """A mouse or key event in the format of `--input` files and `--record`.

    kind: "mouse_down" | "mouse_up" | "mouse_move" | "key_down" | "key_up", or what a scene's
    panel form sends (app/form.py): "edit" (`field` set to the text `value`), "save" and
    "open" (the name typed, in `value`; "" cancels).
    pos: world coordinates (pixels at zoom 1, y down); button: 1 left, 3 right; key: pygame key name.
    """

    kind: str
    pos: tuple[float, float] = (0.0, 0.0)
    button: int = 0
    key: str = ""
    t: float = 0.0
    field: str = ""
    value: str = ""

    def to_json(self) -> dict:
        d: dict[str, Any] = {"t": round(self.t, 9), "type": self.kind}
        if self.kind.startswith("mouse"):
            d["pos"] = [round(float(self.pos[0]), 2), round(float(self.pos[1]), 2)]
            if self.kind != "mouse_move":
                d["button"] = self.button
        elif self.kind == "edit":
            d["field"], d["value"] = self.field, self.value
        elif self.kind in ("save", "open"):
            d["name"] = self.value
        else:
            d["key"] = self.key
        return d


class Scene:
    """Base class of every scene. Subclasses set the class attributes and override hooks."""

    name: str = ""
    title: str = ""
    category: str = ""
    params: tuple[Param, ...] = ()
    effects: tuple[Effect, ...] = ()
    world_size: tuple[int, int] = (960, 720)   # the area the scene draws in, world pixels
    background: tuple[int, int, int] = (22, 24, 30)
    metrics_box: bool = True    # False: the scene draws its own table, the window shows no strip
    aliases: dict[str, str] = {}  # other names `--set` accepts, e.g. {"bend": "bending"}
    presets: dict[str, tuple[str, ...]] = {}   # a setting that, at any value but "custom", sets
                                   # these (a material's sliders): a comparison's labels omit them
    tries: tuple[Try, ...] = ()   # "try this" cards: one-click experiments from the help text
    comparisons: tuple[Try, ...] = ()   # cards that are comparisons (Try.compare): the panel's
                                        # "Compare side by side"; --try finds them too
    color_key: tuple[tuple[tuple[int, int, int], str], ...] = ()   # (colour, what it means): the
                                                                   # HUD shows it as a key
    color_key_details: bool = False   # True: the key is long (a line per species): it goes on
                                      # the HUD's second page (F4), not the first
    content_fills: bool = False   # True: the scene lays itself out in screen pixels in the room
                                  # it gets (charts, tables): fit_to(size) tells it the room
    snapshot_skip: tuple[str, ...] = ()   # attributes the default snapshot leaves out (caches)
    draws_own_error: bool = False   # True: draw() shows a SceneError it raised (the exercises),
                                    # so the window adds no message with the same text
    metric_units: Mapping[str, Unit] = {}   # how the HUD and the strip write a metric, e.g.
                                            # {"energy": Unit("J", 1 / 256**2)} (app/units.py)
    error_metric: str | None = None   # the metric that is the scene's error against its
    error_label: str = ""             # reference (a compare pane shows it), and what it is

    def __init__(self, overrides: Mapping[str, Any] | None = None):
        self.p, self.on = self.resolve(overrides or {})
        self.time = 0.0      # simulated seconds since build
        self.steps = 0       # fixed steps since build
        self.build_world()

    # ----- declarations ---------------------------------------------------------------------
    @classmethod
    def all_params(cls) -> tuple[Param, ...]:
        """The scene's params followed by the common ones it does not re-declare."""
        own = {p.name for p in cls.params}
        return tuple(cls.params) + tuple(p for p in COMMON_PARAMS if p.name not in own)

    @classmethod
    def param(cls, name: str) -> Param | None:
        name = cls.canonical(name)
        return next((p for p in cls.all_params() if p.name == name), None)

    @classmethod
    def effect(cls, name: str) -> Effect | None:
        name = cls.canonical(name)
        return next((e for e in cls.effects if e.name == name), None)

    @classmethod
    def setting_names(cls) -> list[str]:
        """Every name `--set` accepts: params, effects, then aliases."""
        return [p.name for p in cls.all_params()] + [e.name for e in cls.effects] + list(cls.aliases)

    @classmethod
    def canonical(cls, name: str) -> str:
        """The param or effect an alias stands for (the name itself if it is no alias)."""
        return cls.aliases.get(name, name)

    @classmethod
    def check_setting(cls, key: str, value: Any) -> Any:
        """Validate one `--set KEY=VALUE` (param or effect); return the parsed value."""
        prm = cls.param(key)
        if prm is not None:
            return prm.parse(value)
        eff = cls.effect(key)
        if eff is not None:
            try:
                return Param(eff.name, True, bool).parse(value)
            except ParamError:
                strength = f" (its strength is the parameter '{eff.amount}')" if eff.amount else ""
                raise ParamError(f"effect '{eff.name}' got {shown_text(value)}: an effect is on or "
                                 f"off; accepted values are on, off, true, false, yes, no, 1, 0"
                                 f"{strength}") from None
        from app.outputs import listed
        raise ParamError(f"scene '{cls.name}' has no parameter or effect {shown_text(key)}; "
                         "accepted: " + listed(cls.setting_names(), key,
                                               rest="all in docs/scenes.md"))

    @classmethod
    def check_combination(cls, values: Mapping[str, Any]) -> None:
        """Refuse (ParamError) a combination of valid values that does not fit together, e.g.
        more balls lifted than a cradle has, or a cloth so big that one step would take
        seconds. Called before building (constructor, command line) and by set() (the panel)."""

    @classmethod
    def own_settings(cls, overrides: Mapping[str, Any]) -> dict[str, Any]:
        """The part of `overrides` that names this scene's params, effects or aliases (a
        `--set` given to `--scene all` applies where it means something)."""
        return {k: v for k, v in overrides.items() if k in cls.setting_names()}

    @classmethod
    def resolve(cls, overrides: Mapping[str, Any]) -> tuple[dict[str, Any], set[str]]:
        """Param values and the set of effects on, with `overrides` applied and checked: the one
        validation behind the constructor, the command line and the panel. Raises ParamError
        for a value not accepted, a name given twice (once by an alias) or values that do not
        fit together."""
        values = {prm.name: prm.default for prm in cls.all_params()}
        on = {e.name for e in cls.effects if e.default}
        seen: dict[str, str] = {}
        for key, value in overrides.items():
            name = cls.canonical(key)
            if name in seen:
                raise ParamError(f"'{seen[name]}' and '{key}' name the same setting of "
                                 f"{cls.name}; give it once")
            seen[name] = key
            parsed = cls.check_setting(key, value)
            if cls.param(name) is not None:
                values[name] = parsed
            else:
                (on.add if parsed else on.discard)(name)
        cls.check_combination(values)
        return values, on

    @classmethod
    def find_card(cls, label: str) -> Try | None:
        """The "try this" card called `label` (case and surrounding spaces do not matter)."""
        want = " ".join(label.split()).casefold()
        return next((c for c in cls.tries + cls.comparisons
                     if " ".join(c.label.split()).casefold() == want), None)

    def apply_card(self, card: Try) -> None:
        """A "try this" card: the scene's defaults plus the card's settings, whatever was set or
        clicked before, and the world rebuilt from them (a fresh start: what the card says to
        watch for then holds). Raises ParamError, changing nothing, if the card's settings are
        refused. The window's click and `--try` both come here."""
        self.p, self.on = type(self).resolve(card.settings)
        self.reset()

    def settings(self) -> dict[str, Any]:
        """Every param's value and every effect's on/off state, by name."""
        return {**self.p, **{e.name: e.name in self.on for e in self.effects}}

    def set(self, key: str, value: Any) -> bool:
        """Change a param or effect while running (the panel, tests). A bad value raises
        ParamError and leaves everything as it was; a change that needs it rebuilds the scene.
        Returns True if the scene was rebuilt."""
        parsed = self.check_setting(key, value)
        key = self.canonical(key)
        if self.param(key) is not None:
            self.check_combination({**self.p, key: parsed})
            changed, self.p[key] = self.p[key] != parsed, parsed
            rebuild = changed and self.param(key).rebuild
        else:
            changed = (key in self.on) != parsed
            (self.on.add if parsed else self.on.discard)(key)
            rebuild = changed and self.effect(key).rebuild
        if rebuild:
            self.reset()
        elif changed:
            self.settings_changed({key})
        return rebuild

    # ----- time -----------------------------------------------------------------------------
    @property
    def dt(self) -> float:
        return 1.0 / self.p["hertz"]

    def advance(self) -> None:
        """One fixed step of dt: `substeps` calls of step(dt / substeps), then after_step()."""
        n = self.p["substeps"]
        dt = self.dt
        h = dt / n
        for _ in range(n):
            self.step(h)
        self.time += dt
        self.steps += 1
        self.after_step()

    def build_world(self) -> None:
        self.time = 0.0
        self.steps = 0
        self.rng = np.random.default_rng(self.p["seed"])
        self.random = random.Random(self.p["seed"])
        self.build()

    def reset(self) -> None:
        """Rebuild the world from the current params and effects (the R key)."""
        self.build_world()

    # ----- hooks (override what you use) ------------------------------------------------------
    def build(self) -> None:
        """Create the world from self.p and self.on."""

    def step(self, h: float) -> None:
        """Advance the world by h seconds (one substep)."""

    def after_step(self) -> None:
        """Once per fixed step, after its substeps (observe, compare with a reference, count)."""

    def settings_changed(self, names: set[str]) -> None:
        """Called after set() changed these params or effects without a rebuild (self.p and
        self.on already hold the new values)."""

    def draw(self, surface, view) -> None:
        """Draw the world on a pygame surface through `view` (app.draw.view.View)."""

    def blowup_hint(self) -> str:
        """After a blow-up (rolled back): what to change, in the scene's own terms (e.g. the
        predicted step limit). "" means the shell's general advice (smaller dt, more substeps)."""
        return ""

    def blowup_headline(self) -> str:
        """After a blow-up: why, in a few words a class reads from the back ("27x past its
        limit"); the hint's whole paragraph goes on the second page (F4).
        "" says only when it blew up."""
        return ""

    def content_bounds(self) -> tuple[float, float, float, float]:
        """The world rectangle (x, y, w, h) that draw() covers; the layout keeps the HUD, the
        metrics strip and the panel off it. Default: the whole world_size."""
        return (0.0, 0.0, float(self.world_size[0]), float(self.world_size[1]))

    def fit_to(self, size: tuple[float, float]) -> None:
        """The room (w, h) the content gets, in world units (at least world_size in one
        direction and more in the other), told before content_bounds() to a scene whose
        `content_fills`: it returns (0, 0, w, h) then, and lays out its panels in the screen
        rectangle the view maps that to."""

    def handle_event(self, event: InputEvent) -> None:
        """React to a mouse or key event (positions already in world coordinates)."""

    def panel_form(self) -> Any:
        """An app.form.Form: fields of the scene's own the panel shows (what is typed there
        comes back as "edit" and "save" events), or None (the default: no form)."""
        return None

    def metrics(self) -> dict[str, float]:
        """Scene-specific numbers (names are part of the contract in DESIGN.md)."""
        return {}

    def hud_lines(self) -> list:
        """What a class reads every frame, below the shell's status line: a few lines (a
        verdict, the one number the scene is about). Strings, or app.draw.hud.Line for colour."""
        return []

    def hud_details(self) -> list:
        """The HUD's second page (F4), after hud_lines(): what a class need not read every
        frame (the mouse controls, counts, the derivation of a limit)."""
        return []

    def real_time_words(self) -> str:
        """'' while this scene's physics alone keeps up with real time; else, in its own terms,
        how far behind it is and what would catch up (a HUD line; the window then leaves out its
        own 'slower than real time: physics takes ...', which would say it twice)."""
        return ""

    def shown(self, name: str, value: Any) -> str:
        """Metric `name` with this value as the screen writes it, in the unit `metric_units`
        declares (the HUD and the metrics strip both use it: one unit per quantity)."""
        return shown_in(value, self.metric_units.get(name, PLAIN))

    def json_unit(self, name: str) -> str:
        """The unit metric `name` has in --json and --csv ("px", "s", "1" for a ratio, "count";
        "" if unknown): the reference's entry (app/docs/texts.py) for the scene of this name.
        A scene whose metrics are not in that table (a scene file) says its own."""
        from app.docs.texts import unit_of
        return unit_of(self.name, name)

    def effect_costs(self) -> dict[str, float]:
        """Milliseconds per step spent on each active effect, where the scene measures it."""
        return {}

    def reference_error(self) -> tuple[str, str, Any] | None:
        """(what it is, metric name, value) of the scene's error against its reference, for a
        compare pane's label: by default the metric `error_metric`; None if the scene has no
        reference."""
        if self.error_metric is None:
            return None
        return (self.error_label or self.error_metric, self.error_metric,
                self.metrics().get(self.error_metric))

    no_energy_words = "it keeps no energy account"   # why, when a scene has no energy bars

    def energies(self):
        """The energy bars (app.energy.Energies: the parts, the start, the zero of each, where
        energy goes), or None for a scene that keeps no energy account."""
        return None

    def arrows(self) -> Arrows | None:
        """The bodies or particles that get velocity and force arrows (app/vectors.py), or None:
        the scene has none. Called only while the arrows overlay is on."""
        return None

    def state_arrays(self) -> Iterable[np.ndarray]:
        """The arrays that make up the physical state (used by state_hash and is_finite)."""
        return ()

    def state_hash(self) -> str:
        """A hash of the physical state: equal in two runs with the same inputs."""
        return hash_arrays(*self.state_arrays())

    def is_finite(self) -> bool:
        """True while every state value is finite."""
        return all(bool(np.isfinite(a).all()) for a in self.state_arrays())

    def snapshot(self) -> Any:
        """A copy of the state, for rolling back after the simulation goes non-finite.
        The default deep-copies every attribute but the settings (self.p, self.on: a rollback
        keeps what the panel shows) and those named in `snapshot_skip`; None means 'rebuild'."""
        skip = {"p", "on", *self.snapshot_skip}
        return copy.deepcopy({k: v for k, v in vars(self).items() if k not in skip})

    def restore(self, snap: Any) -> None:
        """Go back to a state returned by snapshot() (a copy of it, so it can be restored again)."""
        if snap is None:
            self.reset()
            return
        vars(self).update(copy.deepcopy(snap))


def hash_arrays(*arrays: np.ndarray) -> str:
    """SHA-256 (first 16 hex digits) of the arrays' exact bytes, shapes and dtypes."""
    h = hashlib.sha256()
    for a in arrays:
        a = np.ascontiguousarray(a)
        h.update(str((a.shape, a.dtype.str)).encode())
        h.update(a.tobytes())
    return h.hexdigest()[:16]


def docstring_help(scene_cls: type[Scene]) -> str:
    """The scene's docstring, dedented, for the help overlay."""
    import inspect
    return inspect.cleandoc(scene_cls.__doc__ or scene_cls.title)


__all__ = ["Scene", "Param", "Effect", "Try", "ParamError", "Arrows", "setting_text",
           "variant_text", "SceneError", "InputEvent", "EVENT_SLACK", "SHELL_KEYS",
           "Unit",
           "COMMON_PARAMS",
           "common",
           "hash_arrays", "docstring_help", "shown_text", "plain_number"]
