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
    scene's area, and the view fitted before the bar appeared is the one after."""
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
        assert not bar.colliderect(after.area) and not bar.colliderect(after.free)
        assert not bar.colliderect(after.content_rect())
        assert (after.view.scale, after.view.offset, after.area, after.free) == view
        assert w.screen.get_rect().contains(bar) and sv.timeline_strip().contains(bar)
    finally:
        TEXT.scale = 1.0
