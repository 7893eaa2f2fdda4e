"""Compare mode: one scene run side by side at two to four settings, in lockstep.

    python -m app --scene cloth --compare iterations=2 iterations=20
    python -m app --headless --scene cloth --json \
        --compare substeps=1,iterations=10 substeps=10,iterations=1

Each VARIANT is one or more KEY=VALUE joined by commas; the `--set` values are shared by every
pane, each variant's own go on top (a key may not be in both). The variants are checked as `--set`
is (the same Scene.resolve), and must differ.

Lockstep: every pane starts from the same initial state (the same seed, built the same way) and
the panes advance on one clock. The clock ticks by the smallest dt among them; at each tick every
pane runs the fixed steps that end by then (with the same hertz: one step each, so step k of every
pane starts at the same simulated time). Input events (replayed or live) are delivered to every
pane at once, before the same tick, in world coordinates: a drag on one pane drags in all.

A pane that goes non-finite (or raises SceneError) is stopped alone: in the window it is rolled
back to its last good state and held there, its pane saying why, while the others go on (R
restarts them all from the same state); headless it stops and reports `"finite": false` while
the others run to the end.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Any, Mapping, Sequence

from app.outputs import shown
from app.runner import Rollback, SceneRunner, deliver
from app.scene import (EVENT_SLACK, InputEvent, ParamError, Scene, SceneError, setting_text,
                       shown_text)

MIN_VARIANTS, MAX_VARIANTS = 2, 4
TAGS = "ABCD"          # the panes' names, in the order given
HELD_TEXT = ("Blew up at t = {bad:.3f} s (NaN/inf, or past the scene's blow-up bounds): rolled "
             "back to t = {good:.3f} s and held here while the other panes go on (R restarts "
             "them all). {advice}")
HELD_HEADLINE = "Blew up at {bad:.3f} s{why}; held (F4: why)"


@dataclass(frozen=True)
class Variant:
    """One pane's own settings: `text` as given (`--compare`'s word, or a card's), `settings`
    the KEY=VALUE pairs in it (values as given: strings from the command line)."""

    text: str
    settings: Mapping[str, Any]


def parse_variant(text: str) -> Variant:
    """'substeps=1,iterations=10' -> Variant. Raises ParamError (one line) on a malformed one."""
    settings: dict[str, str] = {}
    if not text.strip():
        raise ParamError("--compare: an empty variant; accepted: KEY=VALUE[,KEY=VALUE...], "
                         "e.g. iterations=2")
    for pair in text.split(","):
        key, sep, value = pair.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ParamError(f"--compare {shown(text)}: {shown(pair.strip())} is not KEY=VALUE; "
                             "accepted: "
                             "KEY=VALUE[,KEY=VALUE...], e.g. substeps=1,iterations=10")
        if key in settings:
            raise ParamError(f"--compare {shown(text)}: {shown(key)} is given twice; give it once")
        settings[key] = value.strip()
    return Variant(text, settings)


def resolve_variants(cls: type[Scene], shared: Mapping[str, Any],
                     variants: Sequence[Variant]) -> list[dict[str, Any]]:
    """The overrides each pane is built from (shared plus the variant's own), checked as `--set`
    is. Raises ParamError for: fewer than 2 or more than 4 variants, a key in both --set and a
    variant, a setting or value the scene refuses, two variants that are the same settings."""
    if not MIN_VARIANTS <= len(variants) <= MAX_VARIANTS:
        raise ParamError(f"--compare takes {MIN_VARIANTS} to {MAX_VARIANTS} variants; got "
                         f"{len(variants)}")
    shared_names = {cls.canonical(k): k for k in shared}
    overrides, resolved = [], []
    for k, v in enumerate(variants, 1):
        which = f"variant {k} of {len(variants)}"      # its value is echoed once, by the error
        for key in v.settings:
            if cls.canonical(key) in shared_names:
                raise ParamError(f"{shown_text(key)} is in --set and in {which}; give it "
                                 "once: in --set for every pane, or in each variant")
        merged = {**shared, **v.settings}
        try:
            values, on = cls.resolve(merged)
        except ParamError as e:
            raise ParamError(f"{which}: {e}") from None
        overrides.append(merged)
        resolved.append((values, on))
    for i in range(len(resolved)):
        for j in range(i):
            if resolved[i] == resolved[j]:
                raise ParamError(f"variants {shown_text(variants[j].text)} and "
                                 f"{shown_text(variants[i].text)} are the same settings; "
                                 "accepted: variants that differ in at least one")
    return overrides


def differing(scenes: Sequence[Scene]) -> list[str]:
    """The settings (params and effects) whose values are not the same in every pane, in the
    scene's order."""
    all_settings = [s.settings() for s in scenes]
    names = list(all_settings[0])
    first = all_settings[0].items()
    try:                  # the names in any pane's (name, value) pairs that pane A lacks, or
        # the reverse: a few set operations (a compare frame asks three times per pane)
        pairs = set().union(*(first ^ a.items() for a in all_settings[1:]))
    except TypeError:     # (a value that cannot be hashed: compared one by one)
        return [n for n in names
                if any(a.get(n) != all_settings[0].get(n) for a in all_settings)]
    differ = {n for n, _ in pairs}
    return [n for n in names if n in differ]


def labels(scenes: Sequence[Scene]) -> list[str]:
    """Each pane's label: what differs ('iterations=2, substeps=1': a space after each comma,
    so a narrow pane can wrap it). A setting a pane's preset sets (Scene.presets: its
    material's mass, tension, ...) is left out: 'material=silk' says it."""
    names = differing(scenes)
    out = []
    for s in scenes:
        now = s.settings()
        implied = {n for key, sets in s.presets.items() if now.get(key, "custom") != "custom"
                   for n in sets}
        out.append(", ".join(f"{n}={_short(now[n])}" for n in names if n not in implied)
                   or "(same settings)")
    return out


def as_variant(settings: Mapping[str, Any]) -> str:
    """Settings as --compare takes them, numbers short: 'g=500,shear=on'."""
    return ",".join(f"{k}={_short(v)}" for k, v in settings.items())


def _short(value: Any) -> str:
    """A value as a label writes it: 500 for 500.0, on/off for a switch."""
    if isinstance(value, float):
        return format(value, ".10g")
    return setting_text(value)


def shared_and_own(scenes: Sequence[Scene]) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """What the panes' settings are now, as a command line gives them: the settings every pane
    shares that differ from the defaults (--set), and each pane's own (its variant)."""
    cls = type(scenes[0])
    defaults, on = cls.resolve({})
    base = {**defaults, **{e.name: e.name in on for e in cls.effects}}
    names = differing(scenes)
    now = scenes[0].settings()
    shared = {k: v for k, v in now.items() if k not in names and base.get(k) != v}
    return shared, [{n: s.settings()[n] for n in names} for s in scenes]


class CompareRunner:
    """Steps several scenes in lockstep (see the module docstring); one SceneRunner per pane
    does the timing, the finite check and (in the window) the snapshots and the rollback.

    Reads like a SceneRunner where the window and the headless runner need it: `steps` (ticks
    run), `clock` (session seconds, for recordings and replays), `deliver`, `run`, `error`."""

    def __init__(self, scenes: Sequence[Scene], events: list[InputEvent] | None = None,
                 rollback: bool = False, keep_all_times: bool = False):
        self.runners = [SceneRunner(s, None, rollback=rollback, keep_all_times=keep_all_times,
                                    timeline=False)     # the timeline is one scene's: no cost
                        for s in scenes]
        self.events = sorted(events or [], key=lambda e: e.t)
        self.next_event = 0
        self.steps = 0          # ticks since the runner started (R included)
        self.clock = 0.0        # session seconds: the sum of every tick
        self.world = 0.0        # simulated seconds since the panes last started together
        self.held: dict[int, str] = {}     # pane -> why it stopped (a rollback's text)
        self.held_headline: dict[int, str] = {}   # pane -> the same in one line (first page)

    @property
    def scenes(self) -> list[Scene]:
        return [r.scene for r in self.runners]

    @property
    def tick(self) -> float:
        """The clock's tick: the smallest dt among the panes."""
        return min(s.dt for s in self.scenes)

    @property
    def error(self) -> str | None:
        """A SceneError's message if every pane stopped on one (then nothing runs)."""
        errors = [r.error for r in self.runners]
        return errors[0] if all(errors) else None

    @property
    def stopped(self) -> bool:
        return all(k in self.held or r.stopped for k, r in enumerate(self.runners))

    # --- events -----------------------------------------------------------------------------
    def deliver(self, event: InputEvent) -> bool:
        """Deliver one event to every pane now (R resets them all); stamp it with the session
        time. Returns True if the panes were restarted."""
        event.t = self.clock
        reset = False
        for runner in self.runners:
            try:
                reset = deliver(runner.scene, replace(event)) or reset
            except SceneError as e:         # that pane stops, the others go on
                runner.fail(e)
        if reset:
            self.restart(rebuild=False)
        return reset

    def deliver_due(self) -> int:
        n = 0
        while (self.next_event < len(self.events)
               and self.events[self.next_event].t <= self.clock + EVENT_SLACK):
            self.deliver(replace(self.events[self.next_event]))
            self.next_event += 1
            n += 1
        return n

    @property
    def events_left(self) -> list[InputEvent]:
        return self.events[self.next_event:]

    def clear_error(self) -> None:
        for runner in self.runners:
            runner.clear_error()

    def restart(self, rebuild: bool = True) -> None:
        """Start every pane again together from its settings' initial state (R, a rebuild, a
        card): the clock's world time back to 0, held panes released, errors cleared."""
        for runner in self.runners:
            if rebuild:
                runner.scene.reset()
            runner.clear_error()
            runner.rebuilt()
        self.world = 0.0
        self.held.clear()
        self.held_headline.clear()

    # --- stepping ---------------------------------------------------------------------------
    def run(self, n: int, budget: float | None = None) -> tuple[int, dict[int, Rollback]]:
        """Run up to n ticks (each after the events due before it), within `budget` wall
        seconds (after at least one tick). Return the ticks run and the rollbacks done, by pane
        (each of those panes is now held)."""
        start = time.perf_counter()
        rollbacks: dict[int, Rollback] = {}
        for i in range(n):
            if i and budget is not None and time.perf_counter() - start > budget:
                return i, rollbacks
            self.deliver_due()
            if self.stopped:
                return i, rollbacks
            self.world += self.tick
            self.clock += self.tick
            self.steps += 1
            for k, runner in enumerate(self.runners):
                rb = self._catch_up(k, runner)
                if rb is not None:
                    rollbacks[k] = rb
                    self.held[k] = HELD_TEXT.format(bad=rb.bad_t, good=rb.good_t,
                                                    advice=rb.advice)
                    self.held_headline[k] = HELD_HEADLINE.format(
                        bad=rb.bad_t, why=f": {rb.headline}" if rb.headline else "")
        return n, rollbacks

    def _catch_up(self, k: int, runner: SceneRunner) -> Rollback | None:
        """Run pane k's steps that end by the clock's world time."""
        scene = runner.scene
        while k not in self.held and not runner.stopped and \
                scene.time + scene.dt <= self.world + EVENT_SLACK:
            ran, rb = runner.run(1)
            if rb is not None or not ran:
                return rb
        return None

    def step_ms(self, k: int) -> float | None:
        return self.runners[k].step_ms


__all__ = ["Variant", "parse_variant", "as_variant", "resolve_variants", "differing", "labels",
           "shared_and_own", "CompareRunner", "TAGS", "MIN_VARIANTS", "MAX_VARIANTS"]
