"""Opening the window's display: full screen or a size, and a clear error where there is none
(SDL falls back to an invisible window without saying so)."""

from __future__ import annotations

import os
import sys

import pygame


class _quiet_stderr:
    """Silence file descriptor 2 (C libraries' messages) inside a `with` block."""

    def __enter__(self):
        sys.stderr.flush()
        self.saved = os.dup(2)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 2)
        os.close(devnull)

    def __exit__(self, *exc):
        os.dup2(self.saved, 2)
        os.close(self.saved)
        return False


def open_display(size: tuple[int, int], fullscreen: bool = False) -> pygame.Surface:
    """Open the window (full screen at the desktop's size with `fullscreen`); raise
    pygame.error if there is no usable display."""
    if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY")
                                                 or os.environ.get("WAYLAND_DISPLAY")):
        with _quiet_stderr():     # SDL's own probing prints "XDG_RUNTIME_DIR is invalid" lines
            pygame.display.init()
    else:
        pygame.display.init()
    driver = pygame.display.get_driver()
    # SDL quietly falls back to an invisible 'offscreen' window when there is no display; that
    # is no window for a person, unless someone asked for it (tests, SDL_VIDEODRIVER=dummy).
    if driver in ("offscreen", "dummy") and os.environ.get("SDL_VIDEODRIVER", "") != driver:
        raise pygame.error(f"SDL found no display (it fell back to the '{driver}' driver; "
                           "is DISPLAY set?)")
    if fullscreen:
        return pygame.display.set_mode((0, 0), pygame.FULLSCREEN)
    return pygame.display.set_mode(size, pygame.RESIZABLE)


__all__ = ["open_display"]
