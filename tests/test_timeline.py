"""The timeline ([ and ]): going back to a snapshot and on from it gives, for the hand-written
physics, the very run that was first seen (the same state hash); the kept span and memory are
bounded; a scrub is an input event, so a recording replays it headless."""

import pytest

import scenes
from app.runner import SceneRunner, run_scene
from app.scene import InputEvent
from app.timeline import KEY_EVERY, Timeline

BY_NAME = {c.name: c for c in scenes.SCENES}
EXACT = ("cloth", "mass_spring_cloth", "integrators", "particle_dance")


def _settings(name):
    return {"particles": 400} if name == "particle_dance" else {}


@pytest.mark.parametrize("name", EXACT)
def test_going_back_and_on_is_the_run_first_seen(name):
    cls = BY_NAME[name]
    first = SceneRunner(cls(_settings(name)), timeline=True)
    first.run(150)
    want = first.scene.state_hash()
    again = SceneRunner(cls(_settings(name)), timeline=True)
    again.run(100)
    assert again.scrub(-1) and again.scrub(-1)          # two snapshots back
    assert again.scene.steps < 100
    hash_there = again.scene.state_hash()
    again.scrub(+1)
    again.scrub(-1)                                     # forward and back: the same state
    assert again.scene.state_hash() == hash_there       # (a snapshot is never stepped in place)
    again.run(150 - again.scene.steps)
    assert again.scene.steps == 150 and again.scene.state_hash() == want


def test_the_span_and_the_memory_are_bounded():
    cls = BY_NAME["integrators"]
    r = SceneRunner(cls(), timeline=True)
    r.run(int(45 / cls().dt))                            # 45 s of run
    tl = r.timeline
    assert tl.kept_seconds <= tl.span + KEY_EVERY and tl.kept_seconds >= tl.span - KEY_EVERY
    small = Timeline(memory_cap=1)                       # a cap below one snapshot: two kept
    scene = BY_NAME["cloth"]()
    for _ in range(90):
        scene.advance()
        if small.due(scene):
            small.keep(scene)
    assert len(small.keys) == 2 and small.nbytes > 1
    assert "snapshots" in small.text() and small.ms_per_snapshot > 0


def test_a_pymunk_world_says_it_went_on_from_a_copy():
    r = SceneRunner(BY_NAME["newtons_cradle"](), timeline=True)
    r.run(200)
    assert not r.resumed_copy and r.scrub(-1) and r.resumed_copy
    r.rebuilt()
    assert not r.resumed_copy


def test_a_recorded_scrub_replays_headless_to_the_same_state():
    cls = BY_NAME["cloth"]
    events = [InputEvent("key_down", key="[", t=1.2), InputEvent("key_up", key="[", t=1.2),
              InputEvent("key_down", key="[", t=1.2), InputEvent("key_up", key="[", t=1.2)]
    window_like = SceneRunner(cls(), [InputEvent(e.kind, key=e.key, t=e.t) for e in events],
                              rollback=True)
    window_like.run(150)
    headless = run_scene(cls(), 150, events)
    assert headless.timeline is not None               # made for the replay that scrubs
    assert headless.scene.state_hash() == window_like.scene.state_hash()
    assert headless.scene.time < 150 * cls().dt - 0.6  # it went back 0.7 s (1.2 -> 0.5)
    assert run_scene(cls(), 10).timeline is None       # a plain headless run keeps none


def test_after_a_rollback_the_blow_up_stays_to_be_stepped_through():
    cls = BY_NAME["mass_spring_cloth"]
    scene = cls({"integrator": "symplectic_euler", "material": "leather"})
    r = SceneRunner(scene, rollback=True)
    r.timeline = Timeline(every=1 / 60)                 # a snapshot a step: it blows up fast
    r.rebuilt()
    rollback = None
    for _ in range(600):
        _, rollback = r.run(1)
        if rollback is not None:
            break
    assert rollback is not None
    tl = r.timeline
    assert tl.at is not None and tl.keys[-1].time > scene.time     # frames of the blow-up kept
    assert r.scrub(+1) and scene.time > rollback.good_t and scene.is_finite()


def test_a_watched_blow_up_goes_on_for_a_second_and_replays_the_same():
    """B: the leather card past its limit goes on, finite, for up to a second after the state
    left its bounds, then rolls back; N runs its last second again into the same blow-up."""
    from app.runner import WATCH_SECONDS
    cls = BY_NAME["mass_spring_cloth"]
    scene = cls({"integrator": "symplectic_euler", "material": "leather"})
    r = SceneRunner(scene, rollback=True)
    r.watch_blowups = True
    shivered, rollback = 0, None
    for _ in range(400):
        _, rollback = r.run(1)
        if rollback is not None:
            break
        if r.shiver_start is not None:
            shivered += 1
            assert not scene.is_finite()          # past its bounds, still drawn
    assert rollback is not None and shivered > 0
    assert rollback.bad_t - r.replay_from[1] <= WATCH_SECONDS + 2 * scene.dt
    assert shivered * scene.dt <= WATCH_SECONDS + scene.dt
    bad_t = rollback.bad_t
    assert r.replay_blowup() and scene.is_finite()
    again = None
    for _ in range(400):
        _, again = r.run(1)
        if again is not None:
            break
    assert again is not None and again.bad_t == pytest.approx(bad_t)   # the same blow-up
    r.watch_blowups = False
    scene2 = cls({"integrator": "symplectic_euler", "material": "leather"})
    r2 = SceneRunner(scene2, rollback=True)
    for _ in range(400):
        _, rb = r2.run(1)
        if rb is not None:
            break
    assert rb.bad_t < bad_t                     # off: rolled back as soon as it left its bounds


def test_the_f4_page_gives_the_timelines_span_memory_and_cost(tmp_path):
    import pygame
    from app.window import Window
    pygame.display.init()
    pygame.font.init()
    w = Window(pygame.display.set_mode((1024, 768)), scenes.SCENES, screenshot_dir=tmp_path)
    assert w.open_scene(BY_NAME["cloth"])
    w.scene_view.runner.run(80)
    line = w.scene_view.detail_lines()[-1]
    assert line.startswith("timeline: ") and "snapshots" in line and "MB" in line
