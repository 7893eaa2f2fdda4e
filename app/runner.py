"""One runner for a scene's stepping: the window and `--headless` both advance scenes through it.

A `SceneRunner` owns what happens between "run n fixed steps" and the scene's hooks:

  * fixed steps, each `scene.advance()` (substeps x step, then after_step), optionally within a
    wall-time budget (the window drops the rest so it stays responsive);
  * per-step timing of the physics alone (drawing excluded): the mean of the recent steps for
    the HUD (held while paused: no step, no new figure), and for the headless summary the
    median of every step's time, kept in bounded memory (`StreamingMedian`: a ten-minute soak
    costs no more memory than a ten-step run);
  * input events: an event is delivered before the first step that starts at or after its time
    (t <= session time + EVENT_SLACK), where the session time is the sum of the dt of every step
    run since the runner started (R does not restart it, so a recording stays in order);
  * the finite check after every step; in the window, snapshots every SNAPSHOT_EVERY steps and a
    rollback when the state goes NaN/inf (or past a scene's blow-up bounds) to the oldest of the
    last SNAPSHOTS_KEPT snapshots: a blow-up grows for a while before it is caught, and the
    snapshot just before the catch may already be a wreck (a cloth stretched 300-fold, finite);
  * `SceneError` (a student's exercise code failed): stepping stops and `error` holds the message.

Because live events (the window) and replayed ones (`--input`) go through the same `deliver` and
the same step loop, a recorded demo replays headless to the same state by construction.
"""

from __future__ import annotations

import math
import statistics
import time
from collections import deque
from dataclasses import dataclass, replace
from typing import Any, Callable

import numpy as np

from app.scene import EVENT_SLACK, SHELL_KEYS, InputEvent, Scene, SceneError
from app.timeline import SCRUB_KEYS, Timeline

WATCH_SECONDS = 1.0          # B: a blow-up goes on for up to this long before the rollback
SNAPSHOT_EVERY = 30          # steps between last-good snapshots (window rollback)
SNAPSHOTS_KEPT = 3           # a rollback goes to the oldest: 60 to 90 steps before the blow-up
RECENT_STEPS = 60            # steps in the HUD's mean of the physics time

NONFINITE_TEXT = ("The simulation went non-finite (NaN/inf, or past the scene's blow-up bounds) "
                  "at t={bad:.3f} s: rolled back to "
                  "t={good:.3f} s and paused. {advice}")


def advice(scene: Scene) -> str:
    """What to try after a blow-up: the scene's own hint if it has one, else a smaller dt or
    more substeps, while they can still grow."""
    hint = scene.blowup_hint()
    if hint:
        return hint
    room = [text for name, text in (("hertz", "a smaller dt (raise hertz)"),
                                    ("substeps", "more substeps"))
            if scene.p[name] < scene.param(name).hi]
    if room:
        return "Try " + " or ".join(room) + "."
    return ("hertz and substeps are at their largest: these settings are past what this "
            "solver can hold (change the others).")


def deliver(scene: Scene, event: InputEvent) -> bool:
    """Give one event to the scene, live or replayed, by the same rule: R resets the scene, the
    other shell keys (pause, help, ...) never reach it, everything else goes to its
    handle_event. Returns True if the scene was reset."""
    if event.kind.startswith("key") and event.key in SHELL_KEYS:
        if event.kind == "key_down" and event.key == "r":
            scene.reset()
            return True
        return False
    scene.handle_event(event)
    return False


def _resets(event: InputEvent) -> bool:
    """The R key pressed: deliver() resets the scene."""
    return event.kind == "key_down" and event.key == "r"


class StreamingMedian:
    """The median of a stream of positive numbers (the wall seconds of every step) in bounded
    memory. The first EXACT values are kept as they are, so a short run's median is exact; past
    that, every value is counted in a histogram of log-spaced bins BIN_RATIO wide from LOW to HIGH
    seconds (values outside go to the end bins), whose median is the middle of the bin that holds
    it: within half a bin (0.25 %) of the exact median. Memory: EXACT floats and 5,500 counts,
    whatever the run's length (a list of every step grew by ~30 bytes a step: +9 MB over a
    ten-minute soak)."""

    EXACT = 4096
    LOW, HIGH, BIN_RATIO = 1e-9, 1e3, 1.005

    def __init__(self) -> None:
        self.count = 0
        self.exact: list[float] | None = []
        self.bins: list[int] | None = None
        self._log_ratio = math.log(self.BIN_RATIO)
        self._size = int(math.log(self.HIGH / self.LOW) / self._log_ratio) + 1

    def add(self, value: float) -> None:
        self.count += 1
        if self.exact is not None:
            self.exact.append(value)
            if len(self.exact) <= self.EXACT:
                return
            values, self.exact, self.bins = self.exact, None, [0] * self._size
            for v in values:
                self._count(v)
            return
        self._count(value)

    def _count(self, value: float) -> None:
        k = int(math.log(max(value, self.LOW) / self.LOW) / self._log_ratio)
        self.bins[min(k, self._size - 1)] += 1

    def median(self) -> float | None:
        """The median so far (None before the first value)."""
        if self.exact is not None:
            return statistics.median(self.exact) if self.exact else None
        half, seen = (self.count + 1) / 2, 0
        for k, n in enumerate(self.bins):
            seen += n
            if seen >= half:
                return self.LOW * self.BIN_RATIO ** (k + 0.5)
        return None

    def __len__(self) -> int:
        return self.count


@dataclass
class Rollback:
    """What a rollback did: the time the state went bad and the time it went back to."""
    bad_t: float
    good_t: float
    advice: str = ""
    headline: str = ""      # the scene's few words on why (Scene.blowup_headline)

    def text(self) -> str:
        return NONFINITE_TEXT.format(bad=self.bad_t, good=self.good_t, advice=self.advice)

    def short_text(self) -> str:
        """The same in one line a class reads (the window's first page; F4: text())."""
        why = f": {self.headline}" if self.headline else ""
        return (f"Blew up at {self.bad_t:.3f} s{why}; rolled back to {self.good_t:.3f} s and "
                "paused (F4: why and what to try)")


class SceneRunner:
    """Steps one scene; see the module docstring. `keep_all_times` keeps the median of every
    step's wall seconds (`step_times`, for the headless summary); `rollback` takes snapshots
    and rolls back on a non-finite state instead of stopping (the window)."""

    failures = 0        # SceneErrors (a student's code raised) in this process: the window's
                        # exit code is 1 if one happened while it was open, as headless

    def __init__(self, scene: Scene, events: list[InputEvent] | None = None,
                 rollback: bool = False, keep_all_times: bool = False,
                 timeline: bool | None = None):
        self.scene = scene
        self.events = sorted(events or [], key=lambda e: e.t)   # stable: ties keep file order
        self.next_event = 0
        self.steps = 0                    # steps run since the runner started (R included)
        self.clock = 0.0                  # simulated seconds since then: sum of every step's dt
        self.finite = True
        self.error: str | None = None     # a SceneError's message; stepping stops
        self.rollback = rollback
        self.recent_ms: deque[float] = deque(maxlen=RECENT_STEPS)
        self.step_times: StreamingMedian | None = StreamingMedian() if keep_all_times else None
        self.on_reset: Callable[[], None] | None = None   # told when an event reset the scene
        # called with the runner after every finite step (the CSV, the arrows' force probe);
        # empty unless one of them is on, so they cost nothing off
        self.observers: list[Callable[["SceneRunner"], None]] = []
        self._good: deque[tuple[Any, float, int]] = deque(maxlen=SNAPSHOTS_KEPT)
        # the last 30 s as snapshots ([ and ]): the window's; headless only for a replay that
        # scrubs (a recording made in the window), so it costs nothing otherwise
        if timeline is None:
            timeline = rollback or any(e.kind == "key_down" and e.key in SCRUB_KEYS
                                       for e in self.events)
        self.timeline: Timeline | None = Timeline() if timeline else None
        self.resumed_copy = False   # went on from a timeline snapshot of a pymunk world
        # B (the window): let a blow-up go on, drawn, for up to WATCH_SECONDS before the rollback;
        # the last WATCH_SECONDS of steps are kept meanwhile, so N can replay them
        self.watch_blowups = False
        self.shiver_start: float | None = None
        self.replay_from: tuple[Any, float, int] | None = None
        self._recent: deque[tuple[Any, float, int]] = deque()
        self.rebuilt()

    # --- events ----------------------------------------------------------------------------
    def deliver(self, event: InputEvent) -> bool:
        """Deliver one event now, stamped with the session time (what a recording writes).
        Returns True if it reset the scene."""
        event.t = self.clock
        if event.key in SCRUB_KEYS and event.kind.startswith("key"):
            if event.kind == "key_down" and self.timeline is not None:
                self.scrub(SCRUB_KEYS[event.key])
            return False
        try:
            reset = deliver(self.scene, event)
        except SceneError as e:
            self.fail(e)
            return False
        if reset:
            self.rebuilt()
        return reset

    def deliver_due(self) -> int:
        """Deliver the replayed events due before the next step; return how many."""
        n = 0
        while (self.next_event < len(self.events)
               and self.events[self.next_event].t <= self.clock + EVENT_SLACK):
            event = self.events[self.next_event]
            self.next_event += 1
            n += 1
            if _resets(event) and self._reset_again():
                continue        # another R is due before anything else acts: its rebuild
                                # would throw this one's away (a file of 200,000 Rs: 1 rebuild)
            if self.deliver(replace(event)) and self.on_reset is not None:   # a copy: the file's
                self.on_reset()                                             # t stays as read
        return n

    def _reset_again(self) -> bool:
        """Whether, among the replayed events due before the next step, another R comes before
        any event that acts (anything but a shell key other than R or a scrub key, which
        deliver() passes by)."""
        events = self.events
        for k in range(self.next_event, len(events)):     # (no slice: a copy of the rest)
            event = events[k]
            if event.t > self.clock + EVENT_SLACK:
                return False
            if _resets(event):
                return True
            if not (event.kind.startswith("key") and event.key in SHELL_KEYS
                    and event.key not in SCRUB_KEYS):
                return False
        return False

    @property
    def events_left(self) -> list[InputEvent]:
        """Replayed events not delivered (they lie after the last step run)."""
        return self.events[self.next_event:]

    # --- stepping --------------------------------------------------------------------------
    @property
    def stopped(self) -> bool:
        """True when stepping cannot go on: the scene raised SceneError, or (without rollback)
        the state went non-finite."""
        return self.error is not None or not self.finite

    def run(self, n: int, budget: float | None = None) -> tuple[int, Rollback | None]:
        """Run up to n fixed steps, each after the events due before it. Stop early when the
        wall time spent passes `budget` seconds (after at least one step), on a SceneError, or
        on a non-finite state (rolled back, if the runner does rollbacks). Return the steps run
        and the rollback done, if any."""
        start = time.perf_counter()
        for i in range(n):
            if self.stopped:
                return i, None
            if i and budget is not None and time.perf_counter() - start > budget:
                return i, None
            self.deliver_due()
            if self.stopped:
                return i, None
            t0 = time.perf_counter()
            try:
                if self.shiver_start is None:
                    self.scene.advance()
                else:                                  # B: a watched blow-up overflows on purpose
                    with np.errstate(all="ignore"):
                        self.scene.advance()
            except SceneError as e:
                self.fail(e)
                return i, None
            seconds = time.perf_counter() - t0
            self.recent_ms.append(seconds * 1000.0)
            if self.step_times is not None:
                self.step_times.add(seconds)
            self.steps += 1
            self.clock += self.scene.dt
            if not self.scene.is_finite():
                if not self.rollback:
                    self.finite = False
                    return i + 1, None
                if self._shivers():
                    continue                      # B: the class watches it blow up
                return i + 1, self.roll_back()
            self.shiver_start = None
            if self.watch_blowups:
                self._keep_recent()
            if self.rollback and self.scene.steps % SNAPSHOT_EVERY == 0:
                self._keep_snapshot()
            if self.timeline is not None and self.timeline.due(self.scene):
                self.timeline.keep(self.scene)
            for observe in self.observers:
                observe(self)
        return n, None

    def fail(self, error: SceneError) -> None:
        """A SceneError from the scene: keep its message and stop stepping."""
        self.error = str(error) or type(error).__name__
        SceneRunner.failures += 1

    def clear_error(self) -> None:
        self.error = None

    # --- snapshots -------------------------------------------------------------------------
    def rebuilt(self) -> None:
        """The scene was (re)built: forget the old world's snapshot and step times."""
        self.recent_ms.clear()
        self.finite = True
        self._good.clear()
        if self.rollback:
            self._keep_snapshot()
        if self.timeline is not None:
            self.timeline.clear()
            self.timeline.keep(self.scene)
        self.resumed_copy = False
        self._recent.clear()                 # the old world's last second is not this one's
        self.replay_from, self.shiver_start = None, None

    # --- B: watching a blow-up, N: its last second again -------------------------------------
    def _shivers(self) -> bool:
        """With watch_blowups: True while a blow-up may go on (every value still finite, so it
        can be drawn, and less than WATCH_SECONDS since it began)."""
        if not self.watch_blowups:
            return False
        if self.shiver_start is None:
            self.shiver_start = self.scene.time - self.scene.dt
        finite = all(bool(np.isfinite(a).all()) for a in self.scene.state_arrays())
        return finite and self.scene.time - self.shiver_start < WATCH_SECONDS

    def _keep_recent(self) -> None:
        """One step's snapshot into the last WATCH_SECONDS (only while B is on)."""
        keep = max(1, math.ceil(WATCH_SECONDS / self.scene.dt))
        self._recent.append((self.scene.snapshot(), self.scene.time, self.scene.steps))
        while len(self._recent) > keep:
            self._recent.popleft()

    def replay_blowup(self) -> bool:
        """N: back to WATCH_SECONDS before the last rollback, to run into the blow-up again (the
        same steps: the hand-written physics repeats it bit for bit). False if there is none."""
        if self.replay_from is None:
            return False
        snap, t, steps = self.replay_from
        self.scene.restore(snap)
        self.scene.time, self.scene.steps = t, steps
        self._good.clear()
        self._keep_snapshot()
        self._recent.clear()
        self.finite, self.shiver_start = True, None
        return True

    def scrub(self, direction: int) -> bool:
        """One timeline snapshot back (-1) or forward (+1); the rollback's snapshots start again
        from there. True if the scene moved."""
        if self.timeline is None or not self.timeline.step(self.scene, direction):
            return False
        self._good.clear()
        if self.rollback:
            self._keep_snapshot()
        self.finite = True
        self.resumed_copy = bool(getattr(self.scene, "space", None) is not None)
        return True

    def _keep_snapshot(self) -> None:
        self._good.append((self.scene.snapshot(), self.scene.time, self.scene.steps))

    def roll_back(self) -> Rollback:
        """The state went NaN/inf: go back to the oldest snapshot kept (or rebuild)."""
        scene = self.scene
        bad_t = scene.time
        if self._recent:                       # what N replays: the last second before it
            self.replay_from = self._recent[0]
        self._recent.clear()
        self.shiver_start = None
        snap, t, steps = self._good[0] if self._good else (None, 0.0, 0)
        scene.restore(snap)
        if snap is not None:
            scene.time, scene.steps = t, steps
        if not scene.is_finite():     # a snapshot that shared arrays with the state: rebuild
            scene.reset()
            self.rebuilt()
        else:                         # the restored state is the one to come back to next time
            self._good.clear()
            self._keep_snapshot()
            if self.timeline is not None:   # its snapshots after here: the blow-up, to replay
                self.timeline.point_at(scene)
        return Rollback(bad_t, scene.time, advice(scene), scene.blowup_headline())

    # --- what the HUD and the summary read ---------------------------------------------------
    @property
    def step_ms(self) -> float | None:
        """Mean wall milliseconds of scene.advance() over the last RECENT_STEPS steps (a mean,
        like the scenes' per-effect costs, so the breakdown adds up to it); None before the
        first step. Unchanged while no step runs (paused)."""
        return statistics.fmean(self.recent_ms) if self.recent_ms else None


def run_scene(scene: Scene, steps: int, events: list[InputEvent] | None = None) -> SceneRunner:
    """Advance `scene` by `steps` fixed steps with the events replayed (headless): stops early
    if the state goes non-finite or the scene raises SceneError. Returns the runner."""
    runner = SceneRunner(scene, events, keep_all_times=True)
    runner.run(steps)
    return runner
