"""The timeline: the last 30 s of a run kept as snapshots, to go back, look again and go on.

Every KEY_EVERY simulated seconds the runner keeps `scene.snapshot()` (the same copy a rollback
uses) with its time and step count; the oldest go when the kept span passes SPAN seconds or the
kept snapshots pass MEMORY_CAP bytes (estimated from the arrays and bodies they hold), so a big
cloth keeps a shorter span, never more memory. `[` goes back one snapshot, `]` forward, and a
click on the scrub bar jumps; the scene pauses there and Space goes on from that state, dropping
the snapshots after it (that future was the old run's).

Is the run from there the same as if it had never been scrubbed? For the hand-written physics
(NumPy arrays copied whole) yes, bit for bit: the state hash after N steps is the one the first
run had (tests/test_timeline.py). pymunk cannot promise it: copying a Space leaves out
Chipmunk's contact and joint caches (the impulses it warm-starts from), so the first steps after
a restore differ slightly from the first run, and the HUD says so on resuming a pymunk scene.
"""

from __future__ import annotations

import sys
import time
from collections import deque
from dataclasses import dataclass
from typing import Any

import numpy as np

SPAN = 30.0              # seconds of the run kept
KEY_EVERY = 0.5          # simulated seconds between snapshots
MEMORY_CAP = 200e6       # bytes the snapshots may take (estimated): a big cloth keeps less span
SCRUB_KEYS = {"[": -1, "]": +1}


@dataclass
class Key:
    time: float
    steps: int
    snap: Any
    nbytes: int


def estimate_bytes(obj: Any, _seen: set | None = None, _depth: int = 0) -> int:
    """Bytes a snapshot holds, estimated: NumPy arrays by their buffers, containers by their
    items, a pymunk Space by its bodies and shapes (~300 bytes each), anything else by
    sys.getsizeof. An estimate (what Python's allocator adds is not counted)."""
    seen = _seen if _seen is not None else set()
    if id(obj) in seen or _depth > 12:
        return 0
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        return int(obj.nbytes)
    if isinstance(obj, dict):
        return sys.getsizeof(obj) + sum(estimate_bytes(k, seen, _depth + 1)
                                        + estimate_bytes(v, seen, _depth + 1)
                                        for k, v in obj.items())
    if isinstance(obj, (list, tuple, set, frozenset, deque)):
        return sys.getsizeof(obj) + sum(estimate_bytes(v, seen, _depth + 1) for v in obj)
    kind = type(obj).__module__ or ""
    if kind.startswith("pymunk") and hasattr(obj, "bodies"):
        return 300 * (len(obj.bodies) + len(obj.shapes) + len(obj.constraints))
    if hasattr(obj, "__dict__") and not kind.startswith(("pymunk", "pygame")):
        return sys.getsizeof(obj) + estimate_bytes(vars(obj), seen, _depth + 1)
    return sys.getsizeof(obj)


class Timeline:
    """Snapshots of one scene's run (see the module docstring). `at` is the index of the
    snapshot the scene was put back to, or None while the run is live."""

    def __init__(self, span: float = SPAN, every: float = KEY_EVERY,
                 memory_cap: float = MEMORY_CAP):
        self.span, self.every, self.memory_cap = span, every, memory_cap
        self.keys: deque[Key] = deque()
        self.at: int | None = None
        self.seconds_spent = 0.0          # wall time spent taking snapshots
        self.taken = 0
        self.next_time = 0.0

    # --- keeping ---------------------------------------------------------------------------
    def clear(self) -> None:
        self.keys.clear()
        self.at = None
        self.next_time = 0.0

    def due(self, scene) -> bool:
        return scene.time + 1e-9 >= self.next_time

    def keep(self, scene) -> None:
        """Keep the scene's state now (the runner calls it after a step when `due`)."""
        t0 = time.perf_counter()
        if self.at is not None:                   # going on from a past state: drop its future
            while len(self.keys) > self.at + 1:
                self.keys.pop()
            self.at = None
        if self.keys and self.keys[-1].time >= scene.time - 1e-9:
            self.keys.pop()                        # the same instant again (a restore)
        snap = scene.snapshot()
        self.keys.append(Key(scene.time, scene.steps, snap, estimate_bytes(snap)))
        while len(self.keys) > 2 and (self.keys[-1].time - self.keys[0].time > self.span
                                      or self.nbytes > self.memory_cap):
            self.keys.popleft()
        self.next_time = scene.time + self.every
        self.seconds_spent += time.perf_counter() - t0
        self.taken += 1

    @property
    def nbytes(self) -> int:
        return sum(k.nbytes for k in self.keys)

    @property
    def kept_seconds(self) -> float:
        return self.keys[-1].time - self.keys[0].time if len(self.keys) > 1 else 0.0

    @property
    def ms_per_snapshot(self) -> float:
        return 1e3 * self.seconds_spent / self.taken if self.taken else 0.0

    # --- going back and forth ----------------------------------------------------------------
    def index_now(self) -> int:
        return self.at if self.at is not None else len(self.keys) - 1

    def seek(self, scene, index: int) -> bool:
        """Put the scene back to snapshot `index` (clamped); False if there is none to go to."""
        if not self.keys:
            return False
        index = max(0, min(len(self.keys) - 1, index))
        key = self.keys[index]
        scene.restore(key.snap)
        scene.time, scene.steps = key.time, key.steps
        self.at = index
        self.next_time = key.time + self.every
        return True

    def point_at(self, scene) -> None:
        """The scene was put back to its own time (a rollback): the snapshots after it stay (the
        blow-up, frame by frame with `]`), the newest one at or before it is where it is now."""
        at = [i for i, k in enumerate(self.keys) if k.time <= scene.time + 1e-9]
        if at and at[-1] < len(self.keys) - 1:
            self.at = at[-1]
            self.next_time = self.keys[self.at].time + self.every

    def step(self, scene, direction: int) -> bool:
        """`[` (-1) or `]` (+1): one snapshot back or forward. From a live run, `[` goes to the
        snapshot before now (the newest, if the scene has moved on since it)."""
        if not self.keys:
            return False
        if self.at is None:
            newest = self.keys[-1]
            back = len(self.keys) - 1 if scene.time > newest.time + 1e-9 else len(self.keys) - 2
            return direction < 0 and self.seek(scene, back)
        return self.seek(scene, self.at + direction)

    def text(self) -> str:
        """'timeline: 30 s in 61 snapshots, ~12 MB, 0.4 ms each' (the F4 page's line)."""
        mb = self.nbytes / 1e6
        return (f"timeline: {self.kept_seconds:.3g} s in {len(self.keys)} snapshots, "
                f"~{mb:.3g} MB, {self.ms_per_snapshot:.2g} ms each ([ ]: back, forward)")


__all__ = ["Timeline", "SCRUB_KEYS", "SPAN", "KEY_EVERY", "MEMORY_CAP", "estimate_bytes"]
