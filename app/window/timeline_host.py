"""The timeline in the window: `[` and `]`, the scrub bar along the bottom of the scene, and what
the HUD says about it (app/timeline.py keeps the snapshots; the runner goes back and forth).

A scrub is an input event like any other (a key "[" or "]"), so `--record` writes it and a
headless replay scrubs the same way; a click on the bar is written as the presses it stands for.
"""

from __future__ import annotations

import pygame

from app.draw import hud
from app.draw.energy_bars import draw_energy
from app.draw.text import font, px
from app.loop import SLOW_MOTION
from app.runner import WATCH_SECONDS
from app.scene import InputEvent

BAR_COLOR = (60, 66, 76)
KEPT_COLOR = (110, 130, 160)
NOW_COLOR = (255, 220, 90)
PYMUNK_RESUME = ("went on from a timeline snapshot: pymunk's copy leaves out its contact and "
                 "joint caches, so the next steps may differ slightly from the first run")


class TimelineHost:
    """A mixin for SceneView: `self.runner`, `self.clock`, `self.deliver` and `scene_area()`
    come from the view."""

    _bar: pygame.Rect | None = None

    def scrub_back(self) -> None:
        """[: one timeline snapshot back (pauses)."""
        self._scrub("[")

    def scrub_forward(self) -> None:
        """]: one timeline snapshot forward (pauses)."""
        self._scrub("]")

    def _scrub(self, key: str, times: int = 1) -> None:
        for _ in range(times):
            self.deliver(InputEvent("key_down", key=key))
            self.deliver(InputEvent("key_up", key=key))
        self.clock.paused = True
        self.clock.accumulator = 0.0

    # --- B and N: a blow-up the class can watch ----------------------------------------------
    def replay_blowup(self) -> None:
        """N: WATCH_SECONDS before the last rollback, again, at x1/4, into the same blow-up."""
        if not self.runner.replay_blowup():
            self.window.flash("N replays a blow-up's last second: turn on B (watch blow-ups), "
                              "then let one happen", topic="timeline")
            return
        self.banner = ""
        self.clock.slow_index = SLOW_MOTION.index(0.25)
        self.clock.accumulator = 0.0
        self.clock.paused = False

    def sync_watch(self) -> None:
        for r in self.runners():
            if hasattr(r, "watch_blowups"):
                r.watch_blowups = self.window.watch_blowups

    # --- the bar ---------------------------------------------------------------------------
    def timeline_bar(self) -> pygame.Rect | None:
        """The scrub bar's rectangle (the bottom of the scene area), or None (nothing kept)."""
        tl = self.runner.timeline
        if tl is None or len(tl.keys) < 2:
            return None
        area = self.scene_area()
        h = max(8, px(10))
        return pygame.Rect(area.left + px(12), area.bottom - h - px(6), area.width - px(24), h)

    def timeline_mouse(self, ev: pygame.event.Event) -> bool:
        """A click on the scrub bar: go to the snapshot under it (True: the click was the
        bar's, not the scene's)."""
        bar = self._bar
        if ev.type != pygame.MOUSEBUTTONDOWN or ev.button != 1 or bar is None or \
                not bar.inflate(0, px(8)).collidepoint(ev.pos):
            return False
        tl = self.runner.timeline
        n = len(tl.keys)
        target = round((ev.pos[0] - bar.left) / max(bar.width, 1) * (n - 1))
        now = tl.index_now()
        if tl.at is None and self.scene.time > tl.keys[-1].time + 1e-9:
            now = n                                    # live, past the newest snapshot
        if target < now:
            self._scrub("[", now - target)
        elif target > now:
            self._scrub("]", target - now)
        return True

    def draw_over(self, screen: pygame.Surface, layout) -> None:
        """What the view draws over its scene: E's energy bars and the scrub bar."""
        self.sync_watch()
        if self.window.energy_bars:
            draw_energy(screen, self.scene, layout)
        self.draw_timeline(screen)

    def draw_timeline(self, screen: pygame.Surface) -> None:
        self._bar = bar = self.timeline_bar()
        if bar is None:
            return
        tl = self.runner.timeline
        pygame.draw.rect(screen, BAR_COLOR, bar, border_radius=bar.height // 2)
        n = len(tl.keys)
        x = bar.left + round(tl.index_now() / (n - 1) * bar.width)
        if tl.at is None:
            x = bar.right
        pygame.draw.rect(screen, KEPT_COLOR, (bar.left, bar.top, x - bar.left, bar.height),
                         border_radius=bar.height // 2)
        pygame.draw.circle(screen, NOW_COLOR, (x, bar.centery), bar.height)
        f = font(hud.HUD_SIZE * 3 // 4)
        label = f"{tl.kept_seconds:.0f} s kept  [ ]"
        img = f.render(label, True, hud.DIM_COLOR)
        screen.blit(img, (bar.right - img.get_width(), bar.top - img.get_height() - 2))

    def timeline_notes(self) -> list:
        """The HUD's word on the timeline: where the scene is in it while scrubbed, and a pymunk
        world's copy after going on from a snapshot."""
        tl = self.runner.timeline
        if tl is None:
            return []
        lines = []
        if tl.at is not None:
            back = tl.keys[-1].time - tl.keys[tl.at].time
            lines.append(hud.Line(f"timeline: t = {tl.keys[tl.at].time:.2f} s, {back:.2g} s "
                                  f"before the newest snapshot; Space goes on from here, "
                                  f"[ ] step back and forth", hud.ACCENT_COLOR))
        elif self.banner and self.runner.replay_from is not None:
            lines.append(hud.Line("N: watch its last second again, at x1/4", hud.ACCENT_COLOR))
        elif self.runner.shiver_start is not None:
            lines.append(hud.Line(f"BLOWING UP since t = {self.runner.shiver_start:.2f} s (B: "
                                  f"watched for up to {WATCH_SECONDS:g} s, then rolled back)",
                                  hud.ERROR_COLOR))
        elif self.runner.resumed_copy and self.scene.time - tl.keys[0].time < 2 * tl.every:
            lines.append(hud.Line(PYMUNK_RESUME, hud.DIM_COLOR))
        return lines


__all__ = ["TimelineHost"]
