"""The formulas on the F4 page (app/equations.py): each one renders, and where one step of the
code can show it, the code does what the formula says."""

import math

import numpy as np
import pygame
import pymunk
import pytest

import scenes
from app.equations import (INTEGRATOR_UPDATES, PYMUNK_STEP, VERLET_CLOTH, Equation,
                           equations_for)
from app.physics.cloth import Cloth


@pytest.fixture(scope="module", autouse=True)
def _pygame():
    pygame.init()
    yield


def _all_equations() -> list[Equation]:
    eqs = []
    for cls in scenes.SCENES:
        scene = cls()
        eqs += equations_for(scene)
    return eqs + list(INTEGRATOR_UPDATES.values())


def test_every_scene_shows_its_formulas_and_every_formula_renders():
    from app.draw.formula import formula_surface
    for cls in scenes.SCENES:
        assert equations_for(cls()), f"{cls.name} has no formulas on its F4 page"
    for eq in _all_equations():
        image = formula_surface(eq.tex, 20, (235, 235, 235))       # ValueError if unparsable
        w, h = image.get_size()
        assert 20 <= h <= 120 and w > 2 * h, (eq.caption, image.get_size())


def test_the_mass_spring_cloth_shows_the_update_of_the_integrator_in_use():
    cls = next(c for c in scenes.SCENES if c.name == "mass_spring_cloth")
    for name, update in INTEGRATOR_UPDATES.items():
        eqs = equations_for(cls({"integrator": name, "hertz": 600}))
        assert update in eqs
        assert any("2}{\\omega_{max}" in e.tex for e in eqs) == (name != "implicit_euler")


def test_the_formula_box_fits_its_room_at_both_text_sizes():
    from app.draw.formula_box import formula_box
    from app.draw.text import TEXT
    cls = next(c for c in scenes.SCENES if c.name == "mass_spring_cloth")
    scene = cls()
    screen = pygame.Surface((1024, 768))
    area = pygame.Rect(0, 0, 700, 700)
    for scale in (1.0, 1.6):
        TEXT.scale = scale
        try:
            box = formula_box(screen, area, pygame.Rect(8, 8, 300, 400), 650, scene)
        finally:
            TEXT.scale = 1.0
        assert area.contains(box) and box.bottom == 650, (scale, box)


def test_the_verlet_cloth_steps_as_its_formula_says():
    """x' = x + (1 - drag)^(60 h) (x - x_prev) + a h^2, for free particles (no rods relaxed)."""
    rng = np.random.default_rng(3)
    c = Cloth(2, 2, 20.0, pins="none", effects={"structural"}, dtype=np.float64)
    c.set_effects({"structural", "gravity", "drag"})
    c.iterations = 0
    c.x += rng.normal(0, 3, c.x.shape)
    c.x_prev = c.x - rng.normal(0, 2, c.x.shape)
    h = 1 / 240
    x, x_prev = c.x.copy(), c.x_prev.copy()
    a = np.zeros_like(x)
    a[1] = c.gravity
    want = x + (1 - c.drag) ** (60 * h) * (x - x_prev) + a * h * h
    c.step(h)
    assert np.allclose(c.x, want, rtol=0, atol=1e-9)
    assert "60h" in VERLET_CLOTH.tex


def test_pymunk_steps_as_the_formula_on_its_scenes_pages_says():
    """x' = x + h v, then v' = v damping^h + h (g + F/m): Chipmunk moves the body with the
    velocity the last step left, then updates the velocity (no contact, no joint here)."""
    space = pymunk.Space()
    space.gravity = (30.0, 900.0)
    space.damping = 0.4
    body = pymunk.Body(2.0, 10.0)
    body.position, body.velocity = (10.0, 20.0), (50.0, -70.0)
    space.add(body, pymunk.Circle(body, 5))
    force = (100.0, -40.0)
    body.apply_force_at_local_point(force)
    h = 1 / 60
    v = (np.array([50.0, -70.0]) * 0.4 ** h
         + h * (np.array([30.0, 900.0]) + np.array(force) / 2.0))
    x = np.array([10.0, 20.0]) + h * np.array([50.0, -70.0])
    space.step(h)
    assert np.allclose(body.velocity, v, atol=1e-9) and np.allclose(body.position, x, atol=1e-9)
    assert "damping}^{\\,h}" in PYMUNK_STEP.tex


def test_symplectic_euler_steps_as_its_formula_says():
    from app.physics.forces import Gravity
    from app.physics.integrators import symplectic_euler
    from app.physics.particles import ParticleSystem
    ps = ParticleSystem(np.array([[0.0, 0.0], [3.0, 4.0]]), np.array([[1.0, 2.0], [0.0, -5.0]]),
                        np.array([1.0, 2.0]))
    ps.forces.append(Gravity((0.0, 900.0)))
    x, v, h = ps.x.copy(), ps.v.copy(), 0.01
    symplectic_euler(ps, h)
    v1 = v + h * np.array([0.0, 900.0])
    assert np.allclose(ps.v, v1) and np.allclose(ps.x, x + h * v1)
    assert math.isfinite(h)
