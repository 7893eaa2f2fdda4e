"""The timeline in the window: `[` and `]`, the scrub bar along the bottom of the scene, and what
the HUD says about it (app/timeline.py keeps the snapshots; the runner goes back and forth).

The bar has a strip of its own under the scene's room, kept from the scene's first frame (before
there is anything to scrub), so nothing of the scene is ever under the bar (it hid the collisions
exercise's floor at 1024x768 with F2) and the view does not jump when the bar appears.

A scrub is an input event like any other (a key "[" or "]"), so `--record` writes it and a
headless replay scrubs the same way; a click on the bar is written as the presses it stands for.
"""

from __future__ import annotations

import pygame

from app.draw import hud
from app.draw.energy_bars import draw_energy
from app.draw.layout import MARGIN
from app.draw.text import font, px
from app.loop import SLOW_MOTION
from app.runner import WATCH_SECONDS
from app.timeline import SPAN
from app.scene import InputEvent

BAR_COLOR = (60, 66, 76)
KEPT_COLOR = (110, 130, 160)
NOW_COLOR = (255, 220, 90)
PYMUNK_RESUME = ("went on from a timeline snapshot: pymunk's copy leaves out its contact and "
                 "joint caches, so the next steps may differ slightly from the first run")


class TimelineHost:
    """A mixin for SceneView: `self.runner`, `self.clock` and `self.deliver` come from the view,
    and `scene_area()` from the mixin after it (the room above the plot), less the bar's
    strip."""

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
    def scene_area(self) -> pygame.Rect:
        """The room for the scene: the view's (above the plot) less the scrub bar's strip, but
        for the scene's bottom margin (MARGIN: the layout keeps the content that far from the
        area's edge anyway), which may lie over the strip's top; on the second page (F4) the
        metrics strip sits on the area's bottom edge, and the whole strip is kept clear."""
        area = super().scene_area()
        strip = self.timeline_strip(area)
        if strip is not None:
            over = 0 if self.window.hud_details else min(MARGIN, strip.height)
            area.height = max(strip.top + over - area.top, 1)
        return area

    def timeline_strip(self, above: pygame.Rect | None = None) -> pygame.Rect | None:
        """The strip kept for the scrub bar along the bottom of `above` (the room above the
        plot), or None (no timeline: compare mode). It is there from the first frame, before
        there is anything to scrub, so the scene's view does not move when the bar appears."""
        if getattr(self.runner, "timeline", None) is None:
            return None
        area = super().scene_area() if above is None else above
        h = min(max(_bar_height(), _label_font().get_linesize()), area.height // 4)
        return pygame.Rect(area.left, area.bottom - h, area.width, h)

    def timeline_bar(self) -> pygame.Rect | None:
        """The scrub bar's rectangle (in its strip, left of its label), or None (nothing
        kept)."""
        tl = getattr(self.runner, "timeline", None)
        strip = self.timeline_strip()
        if tl is None or len(tl.keys) < 2 or strip is None:
            return None
        h = min(_bar_height(), strip.height)
        label = _label_font().size(_label(SPAN))[0]   # the widest: the bar never moves
        return pygame.Rect(strip.left + px(12), strip.centery - h // 2,
                           max(strip.width - label - 2 * h - px(32), 1), h)

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
        screen.fill(self.scene.background, self.timeline_strip())   # the scene's, under it too
        pygame.draw.rect(screen, BAR_COLOR, bar, border_radius=bar.height // 2)
        n = len(tl.keys)
        x = bar.left + round(tl.index_now() / (n - 1) * bar.width)
        if tl.at is None:
            x = bar.right
        pygame.draw.rect(screen, KEPT_COLOR, (bar.left, bar.top, x - bar.left, bar.height),
                         border_radius=bar.height // 2)
        pygame.draw.circle(screen, NOW_COLOR, (x, bar.centery), bar.height * 3 // 4 + 1)
        img = _label_font().render(_label(tl.kept_seconds), True, hud.DIM_COLOR)   # right of it
        screen.blit(img, (bar.right + bar.height + px(8), bar.centery - img.get_height() // 2))

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


def _bar_height() -> int:
    return max(6, px(7))


def _label_font():
    return font(hud.HUD_SIZE // 2)        # a hint: small, so the strip costs the scene little


def _label(seconds: float) -> str:
    return f"{seconds:.0f} s kept  [ ]"


__all__ = ["TimelineHost"]
