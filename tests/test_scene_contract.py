"""The Scene contract's hooks (app/scene.py): when each is called, and the default snapshot."""

import numpy as np

from app.scene import Effect, Param, Scene
from scenes import SCENES


class Hooks(Scene):
    """Counts the hook calls; state is a position, a velocity and a list (a deep-copy check)."""

    name = "hooks"
    params = (Param("g", 10.0, float, 0.0, 100.0, rebuild=False),
              Param("size", 2, int, 1, 5))                          # rebuild=True
    effects = (Effect("drag", False), Effect("walls", False, rebuild=True))

    def build(self):
        self.x = np.zeros(2)
        self.v = np.zeros(2)
        self.history = []
        self.calls = {"step": 0, "after_step": 0, "settings_changed": []}
        self.builds = getattr(self, "builds", 0) + 1

    def step(self, h):
        self.calls["step"] += 1
        self.v[1] += self.p["g"] * h
        self.x += self.v * h

    def after_step(self):
        self.calls["after_step"] += 1
        self.history.append(float(self.x[1]))

    def settings_changed(self, names):
        self.calls["settings_changed"].append(set(names))

    def state_arrays(self):
        return (self.x, self.v)


def test_after_step_runs_once_per_fixed_step_after_its_substeps():
    s = Hooks({"substeps": 4})
    for _ in range(3):
        s.advance()
    assert s.calls["step"] == 12 and s.calls["after_step"] == 3
    assert len(s.history) == 3 and s.history[-1] == s.x[1]     # it saw the step's end state


def test_settings_changed_names_what_changed_and_not_on_rebuild_or_no_change():
    s = Hooks()
    assert s.set("g", 20.0) is False
    assert s.set("drag", True) is False
    assert s.set("g", 20.0) is False                    # the same value: nothing changed
    assert s.calls["settings_changed"] == [{"g"}, {"drag"}]
    builds = s.builds
    assert s.set("size", 3) is True                     # a rebuild: build() runs instead
    assert s.builds == builds + 1 and s.calls["settings_changed"] == []
    assert s.set("walls", True) is True and s.builds == builds + 2


def test_default_snapshot_restores_the_state_but_keeps_the_settings():
    s = Hooks()
    for _ in range(5):
        s.advance()
    snap = s.snapshot()
    x, v, history, t = s.x.copy(), s.v.copy(), list(s.history), s.time
    for _ in range(5):
        s.advance()
    s.set("g", 50.0)                                    # a panel change after the snapshot
    s.restore(snap)
    assert np.array_equal(s.x, x) and np.array_equal(s.v, v)
    assert s.history == history and s.time == t and s.steps == 5
    assert s.p["g"] == 50.0                             # what the panel shows is kept
    s.advance()
    s.restore(snap)                                     # a snapshot can be restored twice
    assert np.array_equal(s.x, x) and s.history == history


def test_every_registered_scene_rolls_back_to_the_same_hash():
    for cls in SCENES:
        s = cls()
        s.advance()
        snap, before = s.snapshot(), s.state_hash()
        for _ in range(3):
            s.advance()
        s.restore(snap)
        assert s.state_hash() == before, cls.name


def test_content_bounds_are_a_finite_rectangle_that_meets_the_world():
    for cls in SCENES:
        x, y, w, h = cls().content_bounds()
        W, H = cls.world_size
        assert all(np.isfinite((x, y, w, h))) and w > 0 and h > 0, cls.name
        assert x < W and y < H and x + w > 0 and y + h > 0, cls.name


def test_every_try_card_is_valid_and_its_label_fits_a_card():
    """A card's settings (and a comparison card's every variant) pass the scene's own validation,
    and its label fits the panel's card button at large text in the smallest window (25
    characters: the longest that did in the card's font, measured at 1024x640 with F2; a longer
    label is drawn in the smaller '#card_small' font: up to 30 characters; the window test
    test_no_card_label_is_cut_at_large_text_in_a_small_window measures it)."""
    for cls in SCENES:
        for card in (*cls.tries, *cls.comparisons):
            cls.resolve(card.settings)
            for variant in card.compare:
                cls.resolve({**card.settings, **variant})
            assert 0 < len(card.label) <= 30, (cls.name, card.label)
            assert card.watch.strip(), (cls.name, card.label)


def test_no_module_in_app_or_scenes_is_over_500_lines():
    """A reader finds what they look for in a file they can read through: no module of the app
    or of a scene over 500 lines (scenes/mass_spring_cloth.py was split: its words live in
    scenes/mass_spring_words.py)."""
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    long = {str(p.relative_to(root)): n for p in [*root.joinpath("app").rglob("*.py"),
                                                   *root.joinpath("scenes").rglob("*.py")]
            if (n := len(p.read_text().splitlines())) > 500}
    assert not long, long
