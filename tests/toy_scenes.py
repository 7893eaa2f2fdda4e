"""Two tiny scenes for testing the shell itself (not registered in the app), and a way to close
a window after some frames."""

import numpy as np

from app.scene import Effect, Param, Scene


class Toy(Scene):
    """A ball under gravity. Left click puts it at the cursor."""

    name = "toy"
    title = "Toy ball"
    category = "Test"
    params = (Param("g", 900.0, float, 0.0, 5000.0, help="gravity, px/s^2"),
              Param("size", 3, int, 1, 10, help="a rebuild param"),
              Param("shape", "ball", str, choices=("ball", "box"), help="a choice"))
    effects = (Effect("gravity", True, "pull downwards", amount="g"),)

    def build(self):
        self.x = np.array([100.0, 100.0])
        self.v = np.array([self.rng.normal(), 0.0])
        self.builds = getattr(self, "builds", 0) + 1

    def step(self, h):
        if "gravity" in self.on:
            self.v[1] += self.p["g"] * h
        self.x += self.v * h

    def handle_event(self, event):
        if event.kind == "mouse_down" and event.button == 1:
            self.x[:] = event.pos
            self.v[:] = 0.0

    def metrics(self):
        return {"y": float(self.x[1])}

    def state_arrays(self):
        return (self.x, self.v)

    def snapshot(self):
        return (self.x.copy(), self.v.copy(), self.time, self.steps)

    def restore(self, snap):
        self.x, self.v, self.time, self.steps = snap[0].copy(), snap[1].copy(), snap[2], snap[3]


class Blowup(Toy):
    """Goes non-finite after 10 steps."""

    name = "blowup"
    title = "Blows up"

    def step(self, h):
        super().step(h)
        if self.steps >= 10:
            self.x[0] = np.inf


def close_the_window_after(monkeypatch, frames: int) -> None:
    """The window's event queue says QUIT after `frames` frames (as closing it would)."""
    import pygame
    real, calls = pygame.event.get, [0]

    def get(*args, **kwargs):
        calls[0] += 1
        events = real(*args, **kwargs)
        return events + [pygame.event.Event(pygame.QUIT)] if calls[0] >= frames else events
    monkeypatch.setattr(pygame.event, "get", get)


def key(w, k: int, up: bool = True) -> None:
    """Press (and release, unless up=False) key k in window w, as pygame delivers it."""
    import pygame
    name = pygame.key.name(k)
    w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, scancode=0,
                                             unicode=name if len(name) == 1 else ""))
    if up:
        w.handle_pygame_event(pygame.event.Event(pygame.KEYUP, key=k, mod=0, scancode=0,
                                                 unicode=""))
