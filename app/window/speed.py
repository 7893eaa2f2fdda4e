"""Frames per second, and why the simulation runs slower than real time when it does.

The window's clock drops steps in two ways: the loop's cap on steps per frame (app/loop.py; it
keeps a slow frame from asking for more steps, which make the next frame slower) and the step
budget (physics time per frame, so the window stays responsive). `SpeedWatch` remembers the last
frame that dropped steps and says, in words, what was slow: the physics, the cap (at high hertz:
it binds on any machine, however fast), the drawing, or the rest (the display, other programs),
and what to change.
"""

from __future__ import annotations

import math
from collections import deque

from app.loop import FPS_CAP      # the window draws at most this many frames a second

SETTLE_FRAMES = 20          # frames after opening a scene or a new layout whose hiccups (the
                            # build, the first draw, font loading) are not "slower than real time"
SHOWN_SECONDS = 1.0         # how long the HUD keeps saying it after the last slow frame


class SpeedWatch:
    """The frame rate of the last second, and the cause of the last frame that dropped steps."""

    def __init__(self):
        self.frames: deque[float] = deque()     # wall times of the last second's frames
        self.slow: tuple[float, str] | None = None   # (wall time, why) of the last slow frame
        self.settle = SETTLE_FRAMES

    def restart(self, forget: bool = False) -> None:
        """A new layout or scene: its first frames' hiccups do not count; `forget`: nor does
        the slow frame said before (a rollback: the steps it spoke of were undone)."""
        self.settle = SETTLE_FRAMES
        if forget:
            self.slow = None

    def frame(self, wall: float) -> None:
        self.frames.append(wall)
        while self.frames and self.frames[0] < wall - 1.0:
            self.frames.popleft()

    @property
    def fps(self) -> float:
        if len(self.frames) < 2:
            return 0.0
        span = self.frames[-1] - self.frames[0]
        return (len(self.frames) - 1) / span if span > 0 else 0.0

    def watch(self, wall: float, frame: float, physics: float, draw: float, dropped: bool,
              capped: bool, clock, scene, scene_speaks: bool = True) -> None:
        """Look at a frame of `frame` seconds (physics and drawing seconds of it) that dropped
        steps (`capped`: the loop's cap dropped some) and remember why it was slow.
        `scene_speaks`: the scene's HUD shows its own real_time_words() (one scene: yes; compare
        mode's panes show a line each, and `scene` is one of several: no, the window says it)."""
        if self.settle > 0:
            self.settle -= 1
            return
        if not dropped:
            return
        ms = lambda s: f"{1000 * s:.0f} ms"          # noqa: E731
        # the cap is the cause when even a frame at full speed asks for more steps than it
        # runs; after a long frame it is only the symptom of what made the frame long
        cap_binds = scene.p["hertz"] * clock.slow_motion / FPS_CAP > clock.max_steps_per_frame
        if physics >= draw and physics >= 0.3 * frame:
            if scene_speaks and scene.real_time_words():   # the HUD says it, in its terms
                self.slow = None
                return
            why = f"physics takes {ms(physics)} of a {ms(frame)} frame: {_fewer(scene)} catch up"
        elif capped and cap_binds:
            why = cap_text(clock, scene)
        elif draw >= 0.3 * frame:
            why = (f"drawing takes {ms(draw)} of a {ms(frame)} frame (physics {ms(physics)}): "
                   "a smaller window or fewer effects drawn catch up")
        else:
            why = (f"the display or the machine is slow: a {ms(frame)} frame, of which physics "
                   f"{ms(physics)} and drawing {ms(draw)}")
        self.slow = (wall, why)

    def line(self, wall: float) -> str | None:
        """'slower than real time: ...' while the last slow frame is recent, else None."""
        if self.slow is not None and wall - self.slow[0] < SHOWN_SECONDS:
            return "slower than real time: " + self.slow[1]
        return None


def _fewer(scene) -> str:
    """'fewer iterations, substeps or hertz': the knobs of this scene that cut the physics."""
    knobs = [k for k in ("particles", "iterations", "substeps", "hertz") if k in scene.p]
    if not knobs:
        return "a lighter setting would"
    return "fewer " + (", ".join(knobs[:-1]) + " or " if len(knobs) > 1 else "") + knobs[-1]


def cap_text(clock, scene) -> str:
    """Why time runs slow when the loop's cap on steps per frame binds at full frame rate (on
    any machine, however fast), and what to change."""
    cap, hz = clock.max_steps_per_frame, scene.p["hertz"]
    need = hz * clock.slow_motion / FPS_CAP                # steps a full-speed frame asks for
    most = max(1, int(cap * FPS_CAP / clock.slow_motion))  # the hertz that fits under the cap
    text = (f"the loop runs at most {cap} steps a frame (app/loop.py): hertz {hz} asks for "
            f"{need:.1f} per frame at {FPS_CAP} fps, so time runs at {cap / need:.2f}x real "
            f"time on any machine. For real time: hertz {most} or less")
    k = math.ceil(hz / most)
    sub = scene.p["substeps"] * k
    if k > 1 and sub <= scene.param("substeps").hi and hz % k == 0:
        text += f", or the same h with hertz {hz // k} x substeps {sub}"
    return text
