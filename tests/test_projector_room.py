"""Issue 26, the room a class sees: the timeline's scrub bar in a strip of its own (it was drawn
over the bottom of every scene), the panel's width at F2 in a small window, and what compare
mode's cloth panes get at one common scale. Layout geometry, cheap."""

from __future__ import annotations

import pygame
import pytest

from tests.test_window import Tiny, open_window


@pytest.mark.parametrize("large", [False, True])
def test_the_scrub_bar_has_its_own_strip_and_the_view_does_not_move_when_it_appears(tmp_path,
                                                                                     large):
    """The bar was drawn over the bottom ~30 px of the scene's area (the collisions exercise's
    floor at 1024x768 with F2). Its strip is kept from the first frame: the bar is outside the
    scene's room (at most in the area's bottom margin, which the content never takes), and the
    view fitted before the bar appeared is the one after."""
    from app.draw.text import TEXT
    w = open_window(Tiny, tmp_path, size=(1024, 768), frames=1, large_text=large)
    try:
        sv = w.scene_view
        assert sv.timeline_bar() is None                  # nothing kept yet: no bar
        before = sv.layout
        view = (before.view.scale, before.view.offset, before.area.copy(), before.free.copy())
        for _ in range(40):                       # past KEY_EVERY: a second snapshot, the bar
            w.update(1 / 60)
            w.render()
        bar, after = sv.timeline_bar(), sv.layout
        assert bar is not None and bar.width > 300
        assert not bar.colliderect(after.free) and not bar.colliderect(after.content_rect())
        assert after.area.bottom - bar.top <= 8           # at most the area's bottom margin
        assert (after.view.scale, after.view.offset, after.area, after.free) == view
        assert w.screen.get_rect().contains(bar) and sv.timeline_strip().contains(bar)
    finally:
        TEXT.scale = 1.0


@pytest.mark.parametrize("size, width, scale", [((1024, 768), 320, 1.5), ((1920, 1080), 512, 1.6)])
def test_at_f2_the_panel_leaves_a_small_window_to_the_scene_and_keeps_every_control(
        tmp_path, size, width, scale):
    """At F2 the panel took 36 % of a 1024-wide window (368 px). Now at most 30 % of the window
    and never narrower than at normal text (320 px), its text as large as its top row allows
    (1.5x there; 1920 keeps 512 px and 1.6x): every button's label whole, the material
    drop-down opening inside the window with all six wherever the panel is scrolled (it
    opened off the window's top once scrolled up: its direction was fixed where it was built),
    no label cut."""
    from app.draw.text import TEXT
    from scenes import get_scene
    from tests.test_projector import _pump
    w = open_window(get_scene("mass_spring_cloth"), tmp_path, size=size, frames=1,
                    large_text=True)
    try:
        sv = w.scene_view
        panel = sv.panel
        assert panel.rect.width == width and panel.scale == scale
        assert sv.world_area().width == size[0] - width
        theme = sv.manager.get_theme()
        for b in [panel.pause_button, panel.reset_button, panel.help_button, panel.plot_button,
                  panel.arrows_button, *panel.cards]:
            font = theme.get_font(b.combined_element_ids)
            assert font.size(b.text)[0] + 12 <= b.rect.width, b.text        # not cut
            assert b.rect.right <= size[0]
        d = panel.dropdowns["material"]
        built_at = d.rect.top
        for top in (size[1] - 2 * d.rect.height, d.rect.height):   # scrolled to the bottom, top
            panel.container.vert_scroll_bar.set_scroll_from_start_percentage(
                max(0.0, (built_at - top) / panel._height))
            pygame.event.clear()     # (another test's resize events would rebuild the panel)
            _pump(w)
            assert sv.panel is panel and 0 <= d.rect.top and d.rect.bottom <= size[1]
            pygame.event.clear()
            for kind in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP):   # open, then close
                w.handle_pygame_event(pygame.event.Event(kind, pos=d.rect.center, button=1))
                _pump(w)
            shown = d.current_state.options_selection_list
            assert pygame.Rect((0, 0), size).contains(shown.rect), (top, shown.rect)
            assert len(shown.item_list) == 6
            for kind in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP):
                w.handle_pygame_event(pygame.event.Event(kind, pos=(5, 5), button=1))
                _pump(w)
    finally:
        TEXT.scale = 1.0


def test_four_panes_header_is_one_line_of_title_and_clock_and_the_wheel_refits_nothing(tmp_path):
    """Compare mode's header gave the title and the clock a row each: four cloth panes at
    1920x1080, height-bound, were a row shorter than they need be (share .49, now .52). Title
    and clock are one line (it breaks at its ' | ' where the width is short), and the zoom is
    said on it too: as a line of its own it made the header taller, which re-fitted every pane
    under the pointer as the wheel turned (the point under the pointer moved)."""
    from app.draw.text import font
    from scenes import get_scene
    from tests.test_projector import _compare_window, wheel
    w = _compare_window(tmp_path, get_scene("cloth"), ["iterations=2", "iterations=5",
                                                       "iterations=10", "iterations=50"],
                        (1920, 1080), large_text=False, frames=2)
    cv = w.scene_view
    first = cv.header_lines()[0].text
    assert first.startswith("Verlet cloth: 4 panes compare iterations | t = ")
    rows = font(cv.grid.header_size).get_linesize()
    assert cv.grid.header.height <= 2 * rows + 16          # the line and the colour key
    scales = [p.layout.view.scale for p in cv.grid.panes]
    wheel(w, cv.grid.panes[1].layout.free.center, 2)
    w.update(1 / 60)
    w.render()
    assert "zoom x1.4 (0 fits)" in cv.header_lines()[0].text
    assert [p.layout.view.scale for p in cv.grid.panes] == pytest.approx(
        [s * 1.44 for s in scales])


def test_four_cloth_panes_at_f2_in_a_small_window_are_as_large_as_two_in_one_text_size(tmp_path):
    """Four panes at 1024x768 with F2: the header gives up some of F2's growth (1.17x) to leave
    the two rows their height, while the panes' boxes kept 1.4x and three rows, so each cloth
    was a tenth smaller than in two panes (0.305 against 0.334 px per px). The panes' text is
    at most the header's and their first page brief: the same cloth at the same scale in two
    and in four panes, and one text size in the whole comparison."""
    from app.draw.text import TEXT
    from scenes import get_scene
    from tests.test_projector import _compare_window
    scales = {}
    try:
        for n in (2, 4):
            w = _compare_window(tmp_path, get_scene("cloth"), [f"iterations={k}" for k in
                                                               (2, 5, 10, 50)[:n]],
                                (1024, 768), large_text=True, frames=2)
            grid = w.scene_view.grid
            scales[n] = min(p.layout.view.scale for p in grid.panes)
            if n == 4:
                assert grid.header_size * TEXT.scale < 1.6 * 28          # the header gave up
                assert all(p.layout.hud_text <= round(grid.header_size) for p in grid.panes)
                assert all(p.layout.hud.bottom <= p.layout.area.bottom for p in grid.panes)
    finally:
        TEXT.scale = 1.0
    assert scales[4] >= 0.99 * scales[2], scales


def test_a_pane_on_its_brief_lines_puts_every_pane_on_them():
    """At 1024x768 with F2, cotton's pane gave its headline four rows while leather's, brief,
    gave it none: the two cloths sat at two heights and two HUDs of two kinds. Brief in one
    pane, brief in all (on the first page)."""
    from app.draw import hud
    from app.draw.panes import PaneGrid
    from app.draw.text import TEXT
    from scenes import get_scene
    scenes = [get_scene("cloth")({"iterations": k}) for k in (2, 20)]
    long = "cotton, implicit Euler: h = 16.667 ms = 33x symplectic Euler's limit " * 4
    lines = [[hud.Line("A: iterations=2"), "physics 1.2 ms/step", long],
             [hud.Line("B: iterations=20"), "physics 3.4 ms/step", "20 sweeps/step"]]
    brief = [ln[:2] for ln in lines]
    TEXT.scale = 1.6
    try:
        grid = PaneGrid(scenes)
        grid.fit(pygame.Rect(0, 0, 704, 768), None, lines, False, brief)
    finally:
        TEXT.scale = 1.0
    assert grid.used[0] is brief[0] and grid.used[1] is brief[1]
    a, b = (p.layout for p in grid.panes)
    assert a.free.top - a.area.top == b.free.top - b.area.top and a.view.scale == b.view.scale
