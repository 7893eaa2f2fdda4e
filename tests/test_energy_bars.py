"""The energy bars (E): each scene's parts add up to its own energy, the start is the energy the
run began with, what is lost is measured (not assumed), and the bars stay inside their pane."""

import math

import numpy as np
import pygame
import pytest

import scenes
from app.draw.energy_bars import bars, draw_energy_bars
from app.draw.text import TEXT
from app.energy import Energies

BY_NAME = {c.name: c for c in scenes.SCENES}
WITH_BARS = ("cloth", "cloth_collisions", "mass_spring_cloth", "mass_spring_collisions",
             "newtons_cradle", "double_pendulum", "particle_dance", "trampoline")


def _run(scene, seconds: float) -> None:
    for _ in range(int(round(seconds * scene.p["hertz"]))):
        scene.advance()


def test_which_scenes_have_bars_and_the_others_say_why():
    for cls in scenes.SCENES:
        scene = cls()
        e = scene.energies()
        assert (e is not None) == (cls.name in WITH_BARS), cls.name
        if e is None:
            assert scene.no_energy_words and "no energy account" not in scene.no_energy_words
        else:
            assert e.zero and e.losses and math.isfinite(e.total) and math.isfinite(e.start)


def test_the_mass_spring_bars_add_up_to_its_energy_metric():
    scene = BY_NAME["mass_spring_cloth"]()
    assert scene.energies().total == pytest.approx(0.0, abs=1e-6)     # at rest, start pose
    _run(scene, 1.0)
    e = scene.energies()
    assert e.total == pytest.approx(scene.metrics()["energy"], rel=1e-9, abs=1e-6)
    kinetic, springs, gravity = (v for _, v in e.parts)
    assert gravity < 0 < springs and kinetic >= 0          # it fell, it stretched
    assert e.lost > 0                                       # damping took some: measured, > 0


@pytest.mark.parametrize("name", ["newtons_cradle", "double_pendulum"])
def test_the_pymunk_bars_add_up_to_the_scenes_energy_and_start_at_release(name):
    scene = BY_NAME[name]()
    e0 = scene.energies()
    assert e0.start == pytest.approx(scene.energy()) and e0.lost == pytest.approx(0.0, abs=1e-6)
    _run(scene, 0.5)
    e = scene.energies()
    assert e.total == pytest.approx(scene.energy(), rel=1e-12)
    assert e.start == e0.start and all(math.isfinite(v) for _, v in e.parts)
    potential = dict(e.parts)["gravity"]
    assert potential >= -1e-6          # zero at the lowest pose: never below it


def test_the_verlet_cloth_starts_at_zero_and_falls_into_negative_potential():
    scene = BY_NAME["cloth"]()
    e = scene.energies()
    assert e.total == 0.0 and e.start == 0.0
    _run(scene, 0.5)
    e = scene.energies()
    kinetic, gravity = (v for _, v in e.parts)
    assert gravity < 0 and kinetic > 0
    # kinetic from (x - x_prev)/h, mass 1 a free particle: recomputed here independently
    c = scene.cloth
    h = scene.dt / scene.p["substeps"]
    free = c.w > 0
    v2 = ((c.x - c.x_prev) / h) ** 2
    assert kinetic == pytest.approx(0.5 * float((v2.sum(axis=0) * free).sum()), rel=1e-5)


def test_the_dance_bars_start_when_first_shown_and_rebase_on_a_new_rule():
    scene = BY_NAME["particle_dance"]({"particles": 300})
    _run(scene, 0.2)
    e = scene.energies()
    assert e.lost == pytest.approx(0.0, abs=1e-9)
    _run(scene, 0.5)
    assert scene.energies().start == e.start
    scene.set("attraction", scene.p["attraction"] * 0.5)
    assert scene.energies().lost == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("scale", [1.0, 1.6])
@pytest.mark.parametrize("size", [(1024, 768), (480, 360)])
def test_the_bars_stay_in_their_area_and_avoid_the_hud(scale, size):
    pygame.font.init()
    surface = pygame.Surface(size)
    area = surface.get_rect()
    e = Energies((("kinetic", 3.0), ("springs", 16.0), ("gravity", -64.0)), 0.0, "the start",
                 "damping", unit="J")
    TEXT.scale = scale
    try:
        hud_box = pygame.Rect(8, 8, area.width - 16, 120)
        box = draw_energy_bars(surface, area, e, avoid=hud_box)
    finally:
        TEXT.scale = 1.0
    assert box.top >= hud_box.bottom and area.contains(box.clip(area))
    assert box.right <= area.right
    names = [n for n, _, _ in bars(e)]
    assert names == ["kinetic", "springs", "gravity", "lost", "total"]
    assert dict((n, v) for n, v, _ in bars(e))["lost"] == pytest.approx(45.0)


def test_e_toggles_the_bars_and_a_scene_without_them_says_why(tmp_path):
    from app.window import Window
    pygame.display.init()
    pygame.font.init()
    screen = pygame.display.set_mode((1024, 768))
    w = Window(screen, scenes.SCENES, screenshot_dir=tmp_path)
    assert w.open_scene(BY_NAME["falling_balls"])
    w.handle_pygame_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_e, mod=0, scancode=0,
                                             unicode="e"))
    assert w.energy_bars
    assert any("no energy bars" in m.text and "balls appear" in m.text for m in w.messages)
    assert w.open_scene(BY_NAME["newtons_cradle"])
    w.render()                        # draws the bars: nothing raises, the flag stays on
    assert w.energy_bars and np.isfinite(w.scene.energies().total)
