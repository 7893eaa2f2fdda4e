"""The projector's controls (issue 26): --size and --fullscreen, F11, zoom with the wheel, pan
with the middle button, 0 to fit again, the view held still under a drag, and the window's loop
as one coroutine (what a browser build needs). Headless, with SDL's dummy driver (conftest.py).
"""

from __future__ import annotations

import asyncio

import pygame
import pytest

from app.__main__ import main
from app.draw.view import Camera, View
from app.window import Window, run_window
from tests.test_window import Tiny, key, mouse, open_window


# --- the command line -----------------------------------------------------------------------
@pytest.mark.parametrize("bad", ["1920", "1920x", "x1080", "axb", "1920x1080x2", "-1920x1080",
                                 "100x100", "99999x1080", "1920 x 1080", "１９２０x1080"])
def test_a_bad_size_is_one_line_and_exit_2(bad, capsys):
    assert main([f"--size={bad}"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--size" in err and "accepted: WIDTHxHEIGHT" in err


@pytest.mark.parametrize("opt", [["--size", "1024x768"], ["--fullscreen"]])
def test_size_and_fullscreen_are_the_windows_only(opt, capsys):
    assert main(["--headless", "--scene", "cloth", "--steps", "2", *opt]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and opt[0] in err and "--width" in err


def test_run_window_opens_the_size_asked_for(monkeypatch, tmp_path):
    import scenes
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    shot = tmp_path / "w.png"
    assert run_window("tiny", {}, screenshot=str(shot), seconds=0.1, size=(1024, 768)) == 0
    assert pygame.image.load(str(shot)).get_size() == (1024, 768)


# --- F11 ------------------------------------------------------------------------------------
def test_f11_goes_full_screen_and_back_to_the_window_size(tmp_path):
    w = open_window(Tiny, tmp_path, size=(800, 600), frames=1)
    desktop = pygame.display.get_desktop_sizes()[0]
    key(w, pygame.K_F11)
    assert w.fullscreen and w.screen.get_size() == tuple(desktop)
    w.update(1 / 60)
    w.render()                                  # laid out again for the new size
    assert w.scene_view.panel.rect.right == desktop[0]
    key(w, pygame.K_F11)
    assert not w.fullscreen and w.screen.get_size() == (800, 600)


def test_f11_works_in_the_menu_and_over_the_help(tmp_path):
    w = open_window(Tiny, tmp_path, size=(800, 600), frames=1)
    key(w, pygame.K_h)                         # the help
    key(w, pygame.K_F11)
    assert w.fullscreen and w.show_help
    key(w, pygame.K_F11)
    w.open_menu()
    key(w, pygame.K_F11)
    assert w.fullscreen
    key(w, pygame.K_F11)


# --- the camera -----------------------------------------------------------------------------
def test_camera_zoom_keeps_the_point_under_the_pointer_and_reset_fits_again():
    fitted = View.fit_bounds((0, 0, 400, 300), (10, 20, 800, 600))
    rect, cam = (10, 20, 800, 600), Camera()
    assert cam.apply(fitted, rect) is fitted
    p = (300, 250)
    under = fitted.to_world(p)
    cam.zoom_at(fitted, rect, p, 2.0)
    v = cam.apply(fitted, rect)
    assert v.scale == pytest.approx(2 * fitted.scale)
    assert v.to_world(p) == pytest.approx(under)
    cam.pan(fitted, (40, -10))                 # the world follows the pointer
    v2 = cam.apply(fitted, rect)
    assert v2.pt(under) == (p[0] + 40, p[1] - 10)
    cam.zoom_at(fitted, rect, p, 1e6)
    assert cam.zoom == 40.0                    # clamped
    cam.reset()
    assert cam.fitted and cam.apply(fitted, rect) is fitted


def wheel(w: Window, pos, y: int) -> None:
    w.handle_pygame_event(pygame.event.Event(pygame.MOUSEWHEEL, x=0, y=y, flipped=False,
                                             precise_x=0.0, precise_y=float(y), pos=pos))


def test_wheel_zooms_middle_drag_pans_and_0_fits_the_view_again(tmp_path):
    w = open_window(Tiny, tmp_path, size=(1024, 768), frames=2)
    sv = w.scene_view
    fitted = sv.layout.view
    p = sv.layout.free.center
    under = fitted.to_world(p)
    seen = len(sv.scene.seen)
    wheel(w, p, 1)
    w.update(1 / 60)
    w.render()                  # the HUD's new line "zoom x1.2" may re-fit the picture once
    fitted, under = sv.layout.fitted, sv.view.to_world(p)
    wheel(w, p, 2)
    w.update(1 / 60)
    w.render()
    assert sv.view.scale == pytest.approx(fitted.scale * 1.2 ** 3)
    assert sv.view.to_world(p) == pytest.approx(under, abs=1e-6)
    assert any("zoom x1.7" in str(getattr(x, "text", x)) for x in sv.hud_lines())
    mouse(w, pygame.MOUSEBUTTONDOWN, p, button=2)
    mouse(w, pygame.MOUSEMOTION, (p[0] + 50, p[1] + 30))
    mouse(w, pygame.MOUSEBUTTONUP, (p[0] + 50, p[1] + 30), button=2)
    w.update(1 / 60)
    w.render()
    assert sv.view.pt(under) == (p[0] + 50, p[1] + 30)
    assert len(sv.scene.seen) == seen          # zoom and pan never reach the scene
    key(w, pygame.K_0)
    w.update(1 / 60)
    w.render()
    assert sv.view.scale == pytest.approx(fitted.scale) and sv.camera.fitted
    # a click after zooming lands where the pointer is, in world coordinates
    wheel(w, p, 2)
    w.update(1 / 60)
    w.render()
    mouse(w, pygame.MOUSEBUTTONDOWN, (p[0] + 20, p[1]))
    assert sv.scene.seen[-1].pos == pytest.approx(sv.view.to_world((p[0] + 20, p[1])), abs=0.01)


def test_the_wheel_over_the_panel_scrolls_the_panel_not_the_view(tmp_path):
    w = open_window(Tiny, tmp_path, size=(1024, 768), frames=1)
    sv = w.scene_view
    wheel(w, (sv.panel.rect.centerx, 300), 3)
    assert sv.camera.fitted


def test_compare_zooms_every_pane_alike(tmp_path):
    from app.compare import Variant
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1280, 800)), [Tiny], screenshot_dir=tmp_path)
    assert w.open_compare(Tiny, {}, [Variant("g=10", {"g": "10"}), Variant("g=500",
                                                                             {"g": "500"})])
    for _ in range(2):
        w.update(1 / 60)
        w.render()
    cv = w.scene_view
    scales = [p.layout.view.scale for p in cv.grid.panes]
    b = cv.grid.panes[1].layout
    wheel(w, b.free.center, 2)
    w.update(1 / 60)
    w.render()
    assert [p.layout.view.scale for p in cv.grid.panes] == pytest.approx(
        [s * 1.44 for s in scales])


def test_the_view_holds_still_while_a_drag_moves_the_content(tmp_path):
    """The content's bounds follow the scene, except under a drag: the pinned row must not jump
    under the pointer (issue 26, defect 11)."""
    w = open_window(Tiny, tmp_path, size=(1024, 768), frames=2)
    sv = w.scene_view
    moving = {"b": (0.0, 0.0, 200.0, 200.0)}
    sv.scene.content_bounds = lambda: moving["b"]
    w.update(1 / 60)
    w.render()
    p = sv.layout.free.center
    mouse(w, pygame.MOUSEBUTTONDOWN, p)
    before = sv.view.scale
    moving["b"] = (0.0, 0.0, 400.0, 400.0)      # the content grows while dragged
    w.update(1 / 60)
    w.render()
    assert sv.view.scale == before
    mouse(w, pygame.MOUSEBUTTONUP, p)
    w.update(1 / 60)
    w.render()
    assert sv.view.scale == pytest.approx(before / 2, rel=0.05)


# --- the loop -------------------------------------------------------------------------------
def test_the_window_loop_is_one_coroutine_that_yields_once_a_frame(monkeypatch, tmp_path):
    import scenes
    from app.window import window as win
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    assert asyncio.iscoroutinefunction(win.window_main)
    yields, frames = [], []
    real_sleep, real_flip = asyncio.sleep, pygame.display.flip

    async def counted_sleep(delay, *a):
        yields.append(delay)
        return await real_sleep(0)

    def counted_flip():
        frames.append(1)
        real_flip()
        if len(frames) == 4:                   # the user closes the window (Ctrl+C here)
            raise KeyboardInterrupt
    monkeypatch.setattr(win.asyncio, "sleep", counted_sleep)
    monkeypatch.setattr(pygame.display, "flip", counted_flip)
    assert run_window("tiny", {}) == 130     # Ctrl+C: exit code 130, one line (issue 27)
    assert len(frames) == 4 and len(yields) == 3 and set(yields) == {0}


def test_a_real_ctrl_c_in_the_window_says_the_window_closed(monkeypatch, capsys):
    # once (hostile run, seed 27): asyncio.run turns SIGINT into a cancel of the window's
    # coroutine, so the window's own Ctrl-C line never printed; the command line's did, saying
    # that files that were there are as they were, while --record had just replaced one
    import os
    import signal
    import scenes
    from app.window import window as win
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is not Python's here (asyncio.run would not take it over)")
    monkeypatch.setattr(scenes, "SCENES", [Tiny])
    frames, real_flip = [], pygame.display.flip

    def flip():
        frames.append(1)
        real_flip()
        if len(frames) == 3:
            os.kill(os.getpid(), signal.SIGINT)
    monkeypatch.setattr(pygame.display, "flip", flip)
    try:
        assert run_window("tiny", {}) == 130
    except KeyboardInterrupt:
        pytest.fail("the window let the Ctrl-C through (asyncio.run raised it)")
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "the window closed as Esc would close it" in err, err


# --- ready for the browser: SciPy only where it is needed -----------------------------------
def _run_python(code: str) -> str:
    import os
    import subprocess
    import sys
    env = {**os.environ, "SDL_VIDEODRIVER": "dummy", "SDL_AUDIODRIVER": "dummy"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_no_scene_but_the_implicit_cloth_imports_scipy():
    out = _run_python("""
import sys, pygame
pygame.display.init(); pygame.font.init()
from app.window import Window
from scenes import SCENES
w = Window(pygame.display.set_mode((1024, 768)), SCENES)
for cls in SCENES:
    if cls.name.startswith('mass_spring'):      # the implicit cloth, with or without obstacles
        continue
    assert w.open_scene(cls)
    for _ in range(3):
        w.update(1 / 60); w.render()
print('scipy' in sys.modules)
""")
    assert out.strip().splitlines()[-1] == "False"


def test_the_implicit_cloth_runs_without_scipy_and_the_direct_solve_says_it_needs_it():
    out = _run_python("""
import sys
sys.modules['scipy'] = None          # as in a browser build: not installed
import numpy as np
from scenes import get_scene
cls = get_scene('mass_spring_cloth')
s = cls({'rows': '12', 'cols': '12'})
for _ in range(30):
    s.step(s.dt)
m = s.metrics()
assert m['cg_failures'] == 0 and 0 < m['max_stretch'] < 0.5, m
from app.physics.cloth_matrix import ClothMatrix, DiagonalMatrix
import gc
cm = [o for o in gc.get_objects() if isinstance(o, ClothMatrix)][0]
assert isinstance(cm.matrix, DiagonalMatrix)
try:
    cm.factorize(np.ones(cm.n, bool))
except ImportError as e:
    print('refused:', e)
""")
    assert "refused: the direct solve (solver=direct, and CG's fallback) needs SciPy" in out


def test_the_numpy_diagonals_multiply_as_scipy_does():
    import numpy as np
    from scipy import sparse
    from app.physics.cloth_matrix import DiagonalMatrix
    rng = np.random.default_rng(26)
    n, offsets = 50, np.array([-7, -1, 0, 2, 9])
    data = rng.normal(size=(offsets.size, n))
    x = rng.normal(size=n)
    expected = sparse.dia_matrix((data, offsets), shape=(n, n)) @ x
    assert np.allclose(DiagonalMatrix(data, offsets, (n, n)) @ x, expected, rtol=1e-13)


# --- issue 26, defect 1 and 3: F2 kept where the class reads ----------------------------------
def _compare_window(tmp_path, scene, variants, size, large_text=True, frames=40):
    from app.compare import Variant
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode(size), [scene], screenshot_dir=tmp_path,
               large_text=large_text)
    assert w.open_compare(scene, {}, [Variant(v, dict(kv.split("=") for kv in v.split(",")))
                                        for v in variants])
    for _ in range(frames):
        w.update(1 / 60)
        w.render()
    return w


def _texts(lines) -> list[str]:
    return [getattr(x, "text", str(x)) for x in lines or ()]


@pytest.mark.parametrize("size", [(1024, 768), (1920, 1080)])
def test_a_held_pane_says_one_headline_and_its_text_is_the_size_of_its_neighbours(tmp_path,
                                                                                   size):
    from app.draw.text import TEXT
    from scenes import get_scene
    cls = get_scene("mass_spring_cloth")
    w = _compare_window(tmp_path, cls, ["integrator=symplectic_euler",
                                        "integrator=implicit_euler"], size)
    try:
        cv = w.scene_view
        assert 0 in cv.runner.held
        a = _texts(cv.grid.used[0])
        headline = cv.runner.held_headline[0]
        assert headline in a and cv.runner.held[0] not in a
        own = getattr(cv.scenes[0].hud_lines()[0], "text", str(cv.scenes[0].hud_lines()[0]))
        assert own not in a                      # nor the scene's own headline: one headline
        assert headline.startswith("Blew up at 0.0") and "x past its limit; held (F4: why)" in \
            headline
        sizes = {p.layout.hud_text for p in cv.grid.panes}
        assert len(sizes) == 1                   # one text size in every pane
        w.toggle_details()                       # F4: the whole paragraph
        w.update(1 / 60)
        w.render()
        assert cv.runner.held[0] in _texts(cv.grid.used[0])
    finally:
        TEXT.scale = 1.0


def _tag_rows_end_at_word_ends(tag: str, rows: list[str]) -> bool:
    """Rows of a wrapped tag each end where a word ends (a space, or after '=' or ',')."""
    at = 0
    for row in rows[:-1]:
        at = tag.index(row, at) + len(row)
        if not (tag[at - 1] in "=," or tag[at:at + 1] == " "):
            return False
    return True


@pytest.mark.parametrize("size, large", [((1024, 768), True), ((1920, 1080), True),
                                         ((1024, 768), False)])
def test_four_panes_at_f2_are_two_by_two_one_text_size_and_no_tag_cut_mid_word(tmp_path, size,
                                                                              large):
    """Issue 26, defect 3: four panes at F2 went to one row of four narrow columns (three in
    small text, one large) and a tag broke mid-word ('integrator=implicit_e' / 'uler'); a held
    pane's advice left its cloth a 10 px stamp at 1024x768 (now its brief lines)."""
    from app.draw import hud
    from app.draw.panes import CRAMPED_FREE
    from app.draw.text import TEXT, font
    from scenes import get_scene
    w = _compare_window(tmp_path, get_scene("mass_spring_cloth"),
                        ["integrator=symplectic_euler", "integrator=implicit_euler",
                         "integrator=rk4", "integrator=verlet"], size, large, frames=6)
    try:
        cv = w.scene_view
        cells = cv.grid.cells
        assert len({c.left for c in cells}) == 2 and len({c.top for c in cells}) == 2   # 2x2
        assert len({p.layout.hud_text for p in cv.grid.panes}) == 1
        brief = cv.pane_lines(brief=True)
        for p, lines, short in zip(cv.grid.panes, cv.grid.used, brief):
            tag = lines[0].text
            rows = hud.wrap(tag, font(p.layout.hud_text), p.layout.hud_width - 2 * 8)
            assert _tag_rows_end_at_word_ends(tag, rows), rows
            assert p.layout.hud.bottom <= p.layout.area.bottom        # the box in its pane
            # the picture gets CRAMPED_FREE of the pane, or the HUD is down to its brief lines
            assert p.layout.free.height >= CRAMPED_FREE * p.layout.area.height or \
                _texts(lines) == _texts(short)
        from app.draw.panes import HEADER_SHARE_FOUR
        g = cv.grid                               # the header leaves the two rows their room
        assert g.header.height <= HEADER_SHARE_FOUR * size[1] or \
            g.header_size * TEXT.scale <= hud.HUD_SIZE + 1
        if not large:                             # (a held pane's advice: brief at 1024x768)
            assert _texts(cv.grid.used[0]) == _texts(brief[0])
        assert 0 in cv.runner.held                # (pane A blew up and is held)
    finally:
        TEXT.scale = 1.0
    rows = hud.wrap("B: integrator=implicit_euler", font(28), font(28).size("B: integrator=impl")[0])
    assert rows == ["B:", "integrator=", "implicit_euler"]
    assert _tag_rows_end_at_word_ends("B: integrator=implicit_euler", rows)
    assert not _tag_rows_end_at_word_ends("B: integrator=implicit_euler",
                                          ["B: integrator=implicit_e", "uler"])


def test_three_panes_at_f2_put_the_header_in_the_fourth_cell_and_grow(tmp_path):
    """Issue 26, defect 11: three cloth panes at 1024x768 with F2 were ~150 px cloths under a
    ~200 px header band, the fourth cell empty. The header goes into that cell: the panes take
    the whole height (the smallest cloth's box 237x139 px before, now 300x175 or more)."""
    from app.draw.text import TEXT
    from scenes import get_scene
    w = _compare_window(tmp_path, get_scene("cloth"), ["iterations=2", "iterations=10",
                                                       "iterations=50"], (1024, 768), frames=2)
    try:
        grid = w.scene_view.grid
        assert grid.corner and min(c.top for c in grid.cells) == 0
        assert not any(grid.header.colliderect(c) for c in grid.cells)
        assert grid.header.bottom <= 768 and grid.header.left > max(c.left for c in grid.cells)
        boxes = [p.layout.content_rect().clip(p.layout.area) for p in grid.panes]
        assert min(b.height for b in boxes) >= 170 and min(b.width for b in boxes) >= 290
    finally:
        TEXT.scale = 1.0


@pytest.mark.parametrize("large", [False, True])
def test_the_plot_picker_opens_over_the_panel_not_over_a_pane(tmp_path, large):
    """Issue 26, defect 10: at 1920x1080 in compare mode the metric list covered pane B (its
    hint, one line as wide as half the window, made the box that wide)."""
    from app.draw.text import TEXT
    from app.window.plot_picker import PlotPicker
    from scenes import get_scene
    from tests.test_window import key
    w = _compare_window(tmp_path, get_scene("cloth"), ["iterations=2", "iterations=20"],
                        (1920, 1080), large_text=large, frames=1)
    try:
        key(w, pygame.K_p)
        w.update(1 / 60)
        w.render()
        picker = w.current_view
        assert isinstance(picker, PlotPicker) and picker.box.width > 0
        cells = picker.under.grid.cells
        assert len(cells) == 2 and not any(picker.box.colliderect(c) for c in cells)
        assert picker.box.bottom <= 1080 and len(picker.rows) == len(picker.items())
    finally:
        TEXT.scale = 1.0


def test_a_gif_of_repeated_frames_says_how_many_it_stores(tmp_path):
    """Issue 26, defect 7: '37 frames, 1.2 s' for a GIF that holds 9 (a still scene)."""
    from PIL import Image
    from app.clips import open_clip
    still = pygame.Surface((64, 48))
    still.fill((30, 60, 90))
    writer = open_clip(str(tmp_path / "still.gif"), (64, 48), 30)
    for k in range(37):
        if k == 20:
            still.fill((200, 10, 10))
        writer.add_surface(still)
    clip = writer.close()
    with Image.open(tmp_path / "still.gif") as gif:
        assert gif.n_frames == clip.frames == 2           # counted back from the file
    assert clip.seconds == pytest.approx(37 / 30, abs=0.05)   # the still frames held longer
    assert "2 frames" in clip.text()


# --- issue 26, defect 4: the panel ------------------------------------------------------------
def _pump(w: Window, n: int = 2) -> None:
    for _ in range(n):
        w.update(1 / 60)
        w.render()
        for ev in pygame.event.get():
            w.handle_pygame_event(ev)


@pytest.mark.parametrize("size", [(1024, 768), (1920, 1080)])
def test_a_drop_down_opens_inside_the_window_and_no_gap_sits_above_parameters(tmp_path, size):
    from scenes import get_scene
    w = open_window(get_scene("mass_spring_cloth"), tmp_path, size=size, frames=2)
    panel = w.scene_view.panel
    d = panel.dropdowns["material"]
    # (the F11 tests leave the display's resize events queued: _pump would hand them to this
    # window, which rebuilds its panel and drops `d`; in the same xdist worker it failed)
    pygame.event.clear()
    for kind in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP):
        w.handle_pygame_event(pygame.event.Event(kind, pos=d.rect.center, button=1))
        _pump(w)
    shown = d.current_state.options_selection_list
    assert pygame.Rect((0, 0), size).contains(shown.rect)        # every material visible
    assert len(shown.item_list) == 6 and shown.rect.height >= 6 * 20
    # the box under the cards is as tall as its text: no 200-300 px gap above "Parameters"
    box = panel.watch_box.rect
    assert box.height <= panel._watch_height(panel._watch_shown) + 1
    assert d.rect.top - box.bottom < 100


def test_the_watch_box_grows_with_a_cards_text_and_moves_the_rest(tmp_path):
    from scenes import get_scene
    cls = get_scene("mass_spring_cloth")
    w = open_window(cls, tmp_path, size=(1024, 768), frames=1)
    panel = w.scene_view.panel
    d = panel.dropdowns["material"]
    gap, before = d.rect.top - panel.watch_box.rect.bottom, panel.watch_box.rect.height
    card = max(cls.tries, key=lambda c: len(c.watch))
    panel.show_watch(card)
    w.render()
    assert panel.watch_box.rect.height > before
    assert d.rect.top - panel.watch_box.rect.bottom == gap      # moved with it
    # each slider's handle with it, on its track (once: moved twice, a box's growth off it)
    for ctl in panel.numbers.values():
        s = ctl.slider
        assert s.rect.contains(s.sliding_button.rect), (ctl.prm.name, s.rect, s.sliding_button.rect)
    panel.show_watch(None, clicked=True)
    for ctl in panel.numbers.values():
        assert ctl.slider.rect.contains(ctl.slider.sliding_button.rect), ctl.prm.name


def test_a_wheel_notch_scrolls_the_panel_three_rows(tmp_path):
    from scenes import get_scene
    w = open_window(get_scene("mass_spring_cloth"), tmp_path, size=(1024, 768), frames=1)
    panel = w.scene_view.panel
    assert panel.container.vert_scroll_bar.scroll_wheel_speed == 3.0 * panel._row_step >= 100


# --- issue 26, defect 6: a shared press that misses a pane says so ---------------------------
def test_a_press_that_misses_a_panes_cloth_says_which_panes_caught_it(tmp_path):
    from scenes import get_scene
    w = _compare_window(tmp_path, get_scene("cloth"), ["iterations=1,g=5000", "g=0"], (1280, 800),
                        large_text=False, frames=60)
    cv = w.scene_view
    a, b = cv.scenes
    import numpy as np
    view, free = cv.grid.panes[0].layout.view, cv.grid.panes[0].layout.free
    xa, xb = a.cloth.x.reshape(2, -1).T, b.cloth.x.reshape(2, -1).T
    seen = [i for i, p in enumerate(xa) if free.collidepoint(view.pt(p))]
    i = max(seen, key=lambda i: np.hypot(*(xa[i] - xb[i])))   # A's particle farthest from B's
    assert np.hypot(*(xa[i] - xb[i])) > 3 * a.grab_radius
    assert np.hypot(*(xb - xa[i]).T).min() > a.grab_radius     # nothing of B's under it
    pos = view.pt(xa[i])
    mouse(w, pygame.MOUSEBUTTONDOWN, pos)
    assert a.cloth.grabbed is not None and b.cloth.grabbed is None
    said = [m.text for m in w.messages if m.topic == "drag"]
    assert said == ["the press caught the cloth in A only: in B it is not under that point "
                    "(every pane gets the same world point)"]
    mouse(w, pygame.MOUSEBUTTONUP, pos)
    # a press that catches both says nothing
    top = a.cloth.x[:, 0, 5]
    mouse(w, pygame.MOUSEBUTTONDOWN, cv.grid.panes[0].layout.view.pt(top))
    assert a.cloth.grabbed is not None and b.cloth.grabbed is not None


def test_the_implicit_cloths_ratio_says_now_and_at_rest_when_they_differ():
    """Issue 26, defect 9: '27x' (a held explicit pane, at rest) beside '33x' (the implicit
    pane, draped) with nothing saying why."""
    from app.runner import SceneRunner
    from scenes import get_scene
    s = get_scene("mass_spring_cloth")({})
    SceneRunner(s).run(150)                     # draped: stiffer than at rest
    line = s.hud_lines()[0]
    h, now, rest = s.dt, s.explicit_limit(), s.watch.rest("symplectic_euler")
    assert now < rest
    assert (f"{round(h / now)}x symplectic Euler's limit ({round(h / rest)}x at rest)"
            in line), line
    assert "J (0 at the start" in s.hud_lines()[1]         # the energy names its zero


# --- issue 26, defect 10: the live plot -------------------------------------------------------
def test_the_live_plot_gives_a_second_unit_its_own_axis_and_names_a_line_out_of_view():
    from app.draw import live_plot as lp
    surface = pygame.Surface((700, 300))
    ts = [k / 10 for k in range(50)]
    energy = lp.Line("energy (J)", (200, 200, 200), ts, [-800.0 + k for k in range(50)],
                     unit="J")
    stretch = lp.Line("max_stretch (%)", (100, 200, 100), ts, [5 + 0.1 * k for k in range(50)],
                      unit="%")
    held = lp.Line("A energy (J)", (100, 100, 250), [0.0, 0.1], [1.0, 2.0], unit="J")
    drawn = lp.draw_plot(surface, surface.get_rect(), [energy, stretch, held], 12.0, 10.0)
    assert drawn["y"] and drawn["y2"]                      # J on the left, % on the right
    assert all(r.left > max(q.right for q in drawn["y"]) for r in drawn["y2"])
    # the stretch spans its own axis: its line is not flat at the bottom of the energy's scale
    pixels = pygame.PixelArray(surface)
    rows = {y for x in range(surface.get_width()) for y in range(surface.get_height())
            if surface.unmap_rgb(pixels[x, y]) == (100, 200, 100, 255)}
    del pixels
    assert max(rows) - min(rows) > 50
    # the held pane's line, which ended before the view: the legend says so
    lines_drawn = []
    real = lp._draw_legend
    lp._draw_legend = lambda s, rows, pos, f: lines_drawn.extend(ln.label for r in rows for ln in r)
    try:
        lp.draw_plot(surface, surface.get_rect(), [energy, held], 12.0, 10.0)
    finally:
        lp._draw_legend = real
    assert "A energy (J) (none in view)" in lines_drawn


def test_a_colour_key_wraps_into_even_rows_never_one_item_alone():
    """Issue 26, defect 11: the stretch legend wrapped '>20%' alone onto a second row."""
    from app.draw import hud
    from app.draw.text import font
    keys = tuple(((0, 0, 200), t) for t in ("<0.2%", "<0.5", "<1", "<2", "<5", "<10", "<20",
                                             ">20%"))
    f = font(hud.HUD_SIZE)
    full = sum(hud._key_width(f, k) for k in keys)
    rows = hud._key_rows(keys, f, int(full * 0.9))        # just too narrow for one row
    assert len(rows) == 2 and min(len(r) for r in rows) >= 3
    assert all(sum(hud._key_width(f, k) for k in r) <= int(full * 0.9) for r in rows)
    assert hud._key_rows(keys, f, full + 1) == [list(keys)]


# --- issue 26, defect 11: a small cloth reads as a cloth, the cradle's strings are smooth -------
@pytest.mark.parametrize("spacing_px, filled", [(3.0, True), (16.0, False)])
def test_a_cloth_a_few_pixels_a_cell_is_drawn_filled_not_as_a_moire_of_rods(spacing_px, filled):
    """Three cloth panes at 1024x768 with F2 drew ~150 px cloths as rods 3 px apart, each its own
    colour: a moire. Under FILL_BELOW px a cell the cloth is a filled mesh (no background shows
    through); at its usual size its rods are drawn apart."""
    import numpy as np
    from app.draw.cloth_draw import FILL_BELOW, draw_cloth
    from scenes.cloth import ClothScene
    scene = ClothScene()
    for _ in range(30):
        scene.step(1 / 60)
    c = scene.cloth
    view = View(spacing_px / c.spacing, (0.0, 0.0))
    assert (spacing_px < FILL_BELOW) == filled
    x0, y0, x1, y1 = (c.x[0].min(), c.x[1].min(), c.x[0].max(), c.x[1].max())
    size = (int(x1 * view.scale) + 20, int(y1 * view.scale) + 20)
    surface = pygame.Surface(size)
    surface.fill((0, 0, 0))
    draw_cloth(surface, view, c)
    # the middle of the cloth (30 % in from its bounding box at the sides and top: inside the sag)
    (a, b), (d, e) = view.pt((x0 + 0.3 * (x1 - x0), y0 + 0.3 * (y1 - y0))), \
        view.pt((x0 + 0.7 * (x1 - x0), y0 + 0.6 * (y1 - y0)))
    inner = pygame.surfarray.array3d(surface)[a:d, b:e]
    background = float(np.mean(inner.sum(axis=2) == 0))
    assert (background < 0.02) if filled else (background > 0.3), background
    if filled:                                # every 4th row and column as a seam: a woven grid
        from app.draw.cloth_draw import SEAM_COLOR
        seams = float(np.mean(np.all(inner == SEAM_COLOR, axis=2)))
        assert 0.05 < seams < 0.5, seams


@pytest.mark.skipif(not __import__("app.draw.pymunk_draw", fromlist=["_"])._AA_WIDTH,
                    reason="this pygame-ce's aaline takes no width (the quad fallback is drawn)")
def test_a_slanting_string_is_drawn_smooth_not_in_stair_steps():
    """The cradle's strings, nearly vertical, showed stair-step kinks (a filled quad's edges):
    now each row's ink is centred on the true line within a quarter pixel (it was 1 px off)."""
    import numpy as np
    from app.draw.pymunk_draw import rod
    surface = pygame.Surface((120, 340))
    surface.fill((0, 0, 0))
    rod(surface, (200, 200, 200), (60, 10), (67, 310), 4)
    ink = pygame.surfarray.array3d(surface)[..., 0].astype(float)     # (x, y)
    ys = np.arange(30, 290)
    centre = (ink[:, ys] * np.arange(120)[:, None]).sum(axis=0) / ink[:, ys].sum(axis=0)
    assert np.abs(centre - (60 + (ys - 10) * 7 / 300)).max() < 0.25
    assert ink[:, 150].sum() / 200 >= 3.5          # still a string ~4 px wide, not a hairline


def test_a_name_that_is_not_utf8_is_shown_with_escapes_not_a_crash():
    """`--record bad\\xff.json` (a hostile run): the HUD's 'REC recording to ...' line held a
    lone surrogate and pygame's font raised UnicodeEncodeError inside the window's layout."""
    from app.draw import hud
    from app.draw.text import font, printable, rendered, text_width
    name = "REC  recording to bad\udcff.json"
    f = font(18)
    assert printable(name) == "REC  recording to bad\\udcff.json"
    assert text_width(f, name) == f.size(printable(name))[0] > 0
    assert rendered(f, name, (255, 255, 255)).get_width() == text_width(f, name)
    from app.draw.hud import Line
    assert hud.box_size([Line(name)], 18, max_width=120)[0] > 0      # wrapped, not raised
