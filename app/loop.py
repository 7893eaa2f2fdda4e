"""The fixed-timestep clock: how many physics steps a frame runs.

Physics always advances in steps of the same dt = 1/hertz (a constant step is what keeps a
simulation stable and repeatable). Real time arrives in frames of varying length, so the clock keeps
an *accumulator* of time not yet simulated and runs as many whole steps as fit:

    acc += frame_seconds * slow_motion
    n = floor(acc / dt);  acc -= n * dt

Slow motion scales how much simulated time a frame advances; dt never changes. A cap on the steps
per frame stops the "spiral of death" (a slow frame asks for more steps, which make the next frame
slower, ...): past the cap the backlog is dropped and the simulation simply runs slower than real
time for a moment. Paused, no time accumulates; a single step runs exactly one step.
"""

from __future__ import annotations

from dataclasses import dataclass

SLOW_MOTION = (1.0, 0.5, 0.25, 0.125)   # x1, x1/2, x1/4, x1/8
FPS_CAP = 60                # the window draws at most this many frames a second


@dataclass
class FixedStepClock:
    """The loop's settings and state (Box2D's SampleContext, arcade's fixed update)."""

    max_steps_per_frame: int = 8
    paused: bool = False
    slow_index: int = 0
    accumulator: float = 0.0
    _single_step: bool = False
    dropped_steps: int = 0     # steps skipped by the frame cap, for the HUD

    @property
    def slow_motion(self) -> float:
        return SLOW_MOTION[self.slow_index]

    def slower(self) -> None:
        self.slow_index = min(self.slow_index + 1, len(SLOW_MOTION) - 1)

    def faster(self) -> None:
        self.slow_index = max(self.slow_index - 1, 0)

    def toggle_pause(self) -> None:
        self.paused = not self.paused
        self.accumulator = 0.0

    def single_step(self) -> None:
        """Pause (if running) and ask for exactly one step on the next frame."""
        self.paused = True
        self._single_step = True
        self.accumulator = 0.0

    def steps_for_frame(self, frame_seconds: float, dt: float) -> int:
        """Return how many steps of `dt` to run for a frame that took `frame_seconds`."""
        if self.paused:
            if self._single_step:
                self._single_step = False
                return 1
            return 0
        self.accumulator += max(frame_seconds, 0.0) * self.slow_motion
        n = int(self.accumulator // dt)
        if n > self.max_steps_per_frame:
            self.dropped_steps += n - self.max_steps_per_frame
            n = self.max_steps_per_frame
            self.accumulator = 0.0
        else:
            self.accumulator -= n * dt
        return n
