"""Issue 26's last views an instructor would not show a class: the collision scenes' strip (a
thin rim on a ball in two thirds of empty picture), ... Each test is layout geometry: bounds,
rectangles, pixels counted; cheap."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest

from app.draw.view import View
from scenes import get_scene


@pytest.mark.parametrize("name", ["cloth_collisions", "mass_spring_collisions"])
def test_the_view_closes_in_on_a_strip_draped_on_the_ball_and_a_reset_widens_it(name):
    """At the start the view holds the strip as wide as it falls (649 px of world for a ball
    236 across); draped, it held the same and left the strip a rim on a small ball (content
    share .30 at 1024x768). After 4 s the bounds are at most 60 % as wide, and still hold every
    particle and the ball; a reset starts wide again."""
    scene = get_scene(name)({})
    start = scene.content_bounds()
    for _ in range(240):
        scene.advance()
    x, y, w, h = scene.content_bounds()
    assert w <= 0.6 * start[2], (start, (x, y, w, h))
    pts = scene.cloth.x
    assert x <= pts[0].min() and pts[0].max() <= x + w and y <= pts[1].min() and \
        pts[1].max() <= y + h
    ball = scene.obstacles[0]
    assert x <= ball.cx - ball.radius and ball.cx + ball.radius <= x + w
    assert y <= ball.cy - ball.radius and ball.cy + ball.radius <= y + h
    scene.reset()
    assert scene.content_bounds() == pytest.approx(start)


def test_a_strip_seen_edge_on_is_drawn_as_a_band_not_two_hairlines():
    """Two rows 10 px apart drawn 2 px wide read, draped on a ball, as the ball's rim: each row
    of a strip is drawn at least STRIP_WIDTH (4) px wide at text scale 1."""
    from app.draw.cloth_draw import STRIP_WIDTH, draw_cloth
    scene = get_scene("cloth_collisions")({})
    c = scene.cloth
    surface = pygame.Surface((1000, 400))
    surface.fill((0, 0, 0))
    draw_cloth(surface, View(1.0, (0.0, 0.0)), c)
    x = int(round((c.x[0, 0, 3] + c.x[0, 0, 4]) / 2))        # between two rungs
    y0 = int(c.x[1, 0, 3])
    column = pygame.surfarray.array3d(surface)[x, y0 - 10: y0 + 25].sum(axis=1)
    assert np.count_nonzero(column) >= 2 * STRIP_WIDTH, column


def test_the_labs_answer_under_an_error_gets_the_room_below_the_message_at_f2():
    """An exercise stopped by an error shows its message and, below it, the lab's answer in
    orange. Fitted as a 4:3 box under the HUD, the answer was a ~130 px strip at 1024x768 with
    F2; now message and answer lay out in all the room the HUD leaves: the answer gets at
    least a third of the window's height, and starts just below the message."""
    from app.draw import hud
    from app.draw.layout import draw_scene, scene_layout
    from app.draw.text import TEXT
    from app.exercises.live import exercise_scene
    from app.scene import SceneError
    scene = exercise_scene("verlet")({})
    with pytest.raises(SceneError, match="NotImplementedError"):
        scene.advance()
    surface = pygame.Surface((1024, 768))
    area = pygame.Rect(0, 0, 656, 768)               # the world area left of the F2 panel
    lines = [hud.Line(scene.title, hud.ACCENT_COLOR), "t = 0.00 s | dt = 1/60 s",
             *scene.hud_lines()]
    TEXT.scale = 1.6
    try:
        layout = scene_layout(area, scene, lines, strip=False)
        draw_scene(surface, layout, scene, lines)
    finally:
        TEXT.scale = 1.0
    demo = scene.demo_rect
    assert demo.height >= 768 // 3 and demo.width >= 0.9 * layout.free.width, (demo, layout)
    assert demo.top - layout.hud.bottom <= 300       # no empty band above the message


def test_a_narrow_panes_hud_shrinks_a_little_rather_than_break_a_phrase():
    """Two panes at 1024x768 with F2 are 325 px wide: 'physics 2.19 ms/step' broke into
    'physics' / '2.19 ms/step' (issue 26). The HUD's text gives up to a fifth of its size so
    that no short phrase breaks, and stays larger than the normal size."""
    from app.draw import hud
    from app.draw.layout import PHRASE_SHRINK, scene_layout
    from app.draw.text import TEXT, font
    scene = get_scene("cloth")({})
    lines = [hud.Line("A: iterations=2", hud.ACCENT_COLOR),
             "physics 12.19 ms/step | largest stretch 41.7%"]
    TEXT.scale = 1.6
    try:
        layout = scene_layout(pygame.Rect(0, 164, 325, 604), scene, lines, strip=False)
        rows = hud.wrap(lines[1], font(layout.hud_text), layout.hud_width - 2 * 8)
        size = layout.hud_text * TEXT.scale
    finally:
        TEXT.scale = 1.0
    assert "physics 12.19 ms/step" in rows and "largest stretch 41.7%" in rows, rows
    assert size >= PHRASE_SHRINK * 1.6 * hud.HUD_SIZE - 1 > hud.HUD_SIZE


def test_the_integrator_lab_at_1024x768_with_f2_gives_a_short_chart_up_to_the_picture():
    """At 1024x768 with F2 the lab gets a ~640x540 room under the HUD: the energy chart was a
    110 px panel (a 50 px plot with one label, its lines flat), the table's text shrank to 17 px
    glyphs, the springs and the phase portrait had 240 px. A chart too short to read is left
    out (the table has E/E0, the phase portrait the spiral): the pictures get at least 60 % of
    the room's height and the table 19 px glyphs. At normal text the same room keeps a chart,
    and a 1920x1080 room at F2 keeps it beside the table."""
    from app.draw.integrator_lab import LabDrawing, chart_least, table_rows
    from app.draw.text import TEXT, font
    scene = get_scene("integrators")({})
    for _ in range(30):
        scene.advance()
    d, rows = LabDrawing(), table_rows(scene)
    try:
        TEXT.scale = 1.6
        room = pygame.Rect(8, 197, 640, 540)
        r = d.layout(room, rows)
        assert r.energy.height == 0, r
        assert min(r.systems.height, r.phase.height) >= 0.6 * room.height, r
        assert font(r.table_size).get_height() >= 19, r.table_size
        assert r.table.bottom <= room.bottom and r.systems.bottom < r.table.top, r
        wide = d.layout(pygame.Rect(8, 130, 1390, 880), rows)
        assert wide.energy.height >= chart_least() and wide.energy.top == wide.table.top, wide
        TEXT.scale = 1.0
        r = d.layout(pygame.Rect(8, 95, 680, 645), rows)
        assert r.energy.height >= chart_least(), r
    finally:
        TEXT.scale = 1.0


@pytest.mark.parametrize("name", ["mass_spring_cloth", "trampoline", "pivoting_l",
                                  "double_pendulum", "mass_spring_collisions",
                                  "falling_balls", "particle_dance"])
def test_every_phrase_of_the_hud_fits_a_row_at_1024x768_with_f2(name, tmp_path):
    """A row breaks between phrases (' | ', '; ', two spaces), and inside a phrase only when it
    is wider than the row: at 1024x768 with F2 the scenes' lines were single long phrases that
    broke mid-thought ("energy -48.53 J (0 at the start;" / "-0.07079 J in 1 s)", "coupling
    impulse 14.87 kg px/s" / "this step", "0.1 px past: a" / "soft joint", "0.67 px apart" /
    "after 4.5 s"). Every phrase of the scene's own lines now fits the HUD's row as the
    layout wraps it there, so no row breaks inside one."""
    from app.draw.text import TEXT, font
    from app.draw.wrap import PHRASE_GAP
    from tests.test_window import open_window
    w = open_window(get_scene(name), tmp_path, size=(1024, 768))
    for _ in range(30):
        w.update(1 / 60)
    if name == "pivoting_l":                  # the longest line: the slide past its max
        top = w.scene.slide.max
        w.scene.slide_distance = lambda: top + 0.2
    TEXT.scale = 1.6
    try:
        w.scene_view.pane.forget()
        w.render()
        layout = w.scene_view.layout
        f, room = font(layout.hud_text), layout.hud_width - 2 * 8
        timing = w.scene.real_time_words()          # (wall-clock: left out, as a test must)
        phrases = [p.strip() for x in w.scene.hud_lines()
                   if not timing or getattr(x, "text", str(x)) != timing
                   for p in PHRASE_GAP.split(getattr(x, "text", str(x)))[::2]]
        wide = [(p, f.size(p)[0]) for p in phrases if f.size(p)[0] > room]
    finally:
        TEXT.scale = 1.0
    assert len(phrases) >= 2 and not wide, (room, wide)


@pytest.mark.parametrize("card", ["Catch and throw a ball", "A box in a hammock"])
def test_the_trampolines_view_holds_the_band_the_drop_and_the_floor_not_the_empty_world(card):
    """The trampoline was fitted as the whole 960x720 world: at 1024x768 with F2 the band was
    a 330 px strip under a blank sky. Its bounds are now the band with its slack, the body's
    way down and the floor: at most 80 % of the world's width, and they hold the body where
    it starts, the floor and every particle of the band for 2 s of the card's run."""
    from scenes.trampoline import FLOOR_Y
    cls = get_scene("trampoline")
    scene = cls({})
    scene.apply_card(cls.find_card(card))
    x, y, w, h = scene.content_bounds()
    assert w <= 0.8 * scene.world_size[0], (x, y, w, h)
    body = scene.shape.bb
    assert x <= body.left and body.right <= x + w and y <= body.bottom, (body, (x, y, w, h))
    assert y + h >= FLOOR_Y
    for _ in range(120):
        scene.advance()
        pts = scene.cloth.x
        assert x <= pts[0].min() and pts[0].max() <= x + w, (card, scene.time)
        assert y <= pts[1].min() and pts[1].max() <= y + h, (card, scene.time)


def test_the_spring_columns_names_go_on_two_rows_rather_than_shrink():
    """At 1024x768 (normal text) the six names under the springs fitted one row only at 11 px
    glyphs; two staggered rows take them at full size (SMALL_SIZE), inside the panel, apart."""
    from app.draw.integrator_lab import SHORT, SMALL_SIZE, LabDrawing
    from app.draw.text import font
    scene = get_scene("integrators")({})
    for _ in range(10):
        scene.advance()
    d = LabDrawing()
    d.draw(pygame.Surface((1024, 768)), pygame.Rect(8, 95, 680, 645), scene)
    names = [(r, t) for r, t in d.labels if t in SHORT.values() and r.top < d.rects.table.top]
    assert len(names) == 6 and all(d.rects.systems.contains(r) for r, _ in names), names
    assert all(r.height >= font(SMALL_SIZE).get_height() for r, _ in names), names
    assert not any(a.colliderect(b) for i, (a, _) in enumerate(names) for b, _ in names[i + 1:])


def test_the_integrator_labs_springs_are_drawn_wider_on_a_projector_screen():
    """The coils were 1 px hairlines at any size: at 1920x1080 (springs ~250 px long) they are
    at least 2 px wide, and the pixels of RK4's colour in the systems panel grow with them
    (a fresh scene at t = 0: nothing chaotic);
    in a 1024x768 room at F2 they stay 1 px (coils 8 px apart)."""
    from app.draw.integrator_lab import LabDrawing
    from app.draw.text import TEXT
    scene = get_scene("integrators")({})
    d = LabDrawing()
    rk4 = next(r.color for r in scene.runs if r.name == "rk4")

    def coloured(room):
        surface = pygame.Surface((1920, 1080))
        d.draw(surface, room, scene)
        box = d.rects.systems
        pixels = pygame.surfarray.pixels3d(surface)[box.left:box.right, box.top:box.bottom]
        return int(np.count_nonzero((pixels == rk4).all(axis=-1)))
    big = coloured(pygame.Rect(8, 130, 1390, 880))
    assert d.spring_width >= 2
    from app.draw import integrator_lab   # the same frame with the coils 1 px wide, as before
    thin = integrator_lab.SPRING_LINE
    try:
        integrator_lab.SPRING_LINE = 0.1
        hairline = coloured(pygame.Rect(8, 130, 1390, 880))
    finally:
        integrator_lab.SPRING_LINE = thin
    assert big >= 1.3 * hairline, (big, hairline)   # (the bob, the same in both, counts too)
    TEXT.scale = 1.6
    try:
        coloured(pygame.Rect(8, 197, 640, 540))
    finally:
        TEXT.scale = 1.0
    assert d.spring_width == 1


@pytest.mark.parametrize("card", [None, "Two balls in", "A 5 px gap", "Two substeps",
                                  "Balls pressed together"])
def test_the_cradles_view_holds_its_swing_and_no_more(card):
    """The cradle's bounds held a 60-degree swing whatever the lift angle: at the default 30
    degrees the picture was a fifth smaller than the room allowed (content share .28 at
    1024x768). Now at most 85 % of that width at the defaults, and every ball stays inside
    them for 4 s of every card."""
    import math
    from scenes.newtons_cradle import RADIUS, STRING
    cls = get_scene("newtons_cradle")
    scene = cls({})
    if card:
        scene.apply_card(cls.find_card(card))
    x, y, w, h = scene.content_bounds()
    if card is None:
        wide = (np.ptp(scene.anchors[:, 0]) + 2 * (STRING * math.sin(math.radians(60)) +
                                                   RADIUS + 8))
        assert w <= 0.85 * wide, (w, wide)
    for _ in range(int(4 * scene.p["hertz"])):
        scene.advance()
        for b in scene.bodies:
            bx, by = b.position
            assert x <= bx - RADIUS and bx + RADIUS <= x + w, (card, scene.time, bx, (x, w))
            assert y <= by - RADIUS and by + RADIUS <= y + h, (card, scene.time, by, (y, h))


@pytest.mark.parametrize("name", ["cloth_collisions", "mass_spring_collisions"])
def test_a_rewind_shows_the_view_of_its_moment_not_the_start_closing_in_again(name):
    """The view that closes in on the strip (app/draw/follow.py) is kept in the scene's
    snapshot: restored to 2 s, the picture is the one of 2 s (both scenes' snapshots left it
    out, and a scrub back jumped to the start's wide bounds)."""
    scene = get_scene(name)({})
    for _ in range(120):
        scene.advance()
        scene.content_bounds()                  # (asked every frame, as the window does)
    snap, then, t, steps = scene.snapshot(), scene.content_bounds(), scene.time, scene.steps
    for _ in range(60):
        scene.advance()
        scene.content_bounds()
    scene.restore(snap)
    scene.time, scene.steps = t, steps          # (as the runner's rewind does)
    assert scene.content_bounds() == pytest.approx(then)


def test_a_view_first_asked_after_the_start_is_eased_not_the_start_nor_the_content():
    """A headless run asks for the picture once, at its end. That ask came back with the
    start's wide bounds (the strip draped in a third of the picture); then, for a while, with
    the content's own bounds, closer in than any window would be after half a second. It is
    eased from the start over all of t (TAU = 1 s): at 0.5 s still most of the way out."""
    from app.draw import follow
    start = get_scene("cloth_collisions")({}).content_bounds()
    for seconds, steps in ((0.5, 30), (1.5, 90)):
        scene, twin = get_scene("cloth_collisions")({}), get_scene("cloth_collisions")({})
        for _ in range(steps):
            scene.advance()
            twin.advance()
        w = scene.content_bounds()[2]
        twin._follow = (twin.time - 1e6, (0.0, 0.0, 1.0, 1.0))     # (eased all the way: the
        target = twin.content_bounds()[2]                           # content's own bounds)
        k = 1 - math.exp(-seconds / follow.TAU)
        assert target < w < start[2], (seconds, target, w, start[2])
        assert w == pytest.approx(start[2] + k * (target - start[2]), rel=0.05)
