"""Self-collision's Verlet list (app/physics/self_list.py): at every substep the pairs it hands
out are exactly the pairs a fresh search finds, over a hanging cloth, a crumpled one landing
and settling, the fold card, a cloth dragged by the mouse, restores of a snapshot and changes
of self_distance and of the rod sets; and the positions it leads to are the plain search's, to
float32 rounding (the pairs the same, only the order of the sums differs). Cheap: small cloths."""

import numpy as np
import pytest

from app.physics import cloth_contact, self_list
from app.physics.cloth_contact import close_ij
from app.scene import InputEvent
from scenes.cloth import ClothScene
from scenes.cloth_collisions import FOLD, ClothCollisionsScene


def pair_set(i, j):
    return set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))


@pytest.fixture
def checked(monkeypatch):
    """Every call of the list is checked against a fresh close_ij (as a set, no pair twice);
    returns the counts (calls, reuses of the list, pairs handed out)."""
    seen = {"calls": 0, "reused": 0, "pairs": 0}
    listed = cloth_contact.listed_pairs

    def check(lst, x, distance, key, search, scratch):
        reuses = lst.reuses
        i, j, tests = listed(lst, x, distance, key, search, scratch)
        got = pair_set(i, j)
        assert len(got) == len(i)
        c = CLOTHS[-1]
        fresh = close_ij(c, distance, "grid")
        assert got == pair_set(fresh[0], fresh[1])
        seen["calls"] += 1
        seen["reused"] += lst.reuses - reuses
        seen["pairs"] += len(i)
        return i, j, tests
    monkeypatch.setattr(cloth_contact, "listed_pairs", check)
    return seen


CLOTHS: list = []          # the cloth being checked (the check reads its active rod sets)


def steps(scene, n):
    CLOTHS.append(scene.cloth)
    for _ in range(n):
        scene.advance()


def lmb(scene, kind, pos):
    scene.handle_event(InputEvent(kind, tuple(map(float, pos)), 1))


def test_the_list_hands_out_exactly_the_pairs_a_fresh_search_finds(checked):
    # the fold card: folded, it lands and lies still (the list reused for many steps)
    card = ClothCollisionsScene({**FOLD, "self_collision": True})
    steps(card, 90)
    assert checked["reused"] > 40 and checked["pairs"] > 5000
    lst = card.cloth.contact.self_list              # the HUD says how the list is doing
    assert f"list reused {lst.reuses}, built {lst.builds}" in " ".join(map(str, card.hud_lines()))
    # a crumpled cloth falling onto the floor, landing, settling; then restored to a snapshot
    # taken while it fell, run on, self_distance changed, shear and bending switched on
    heap = ClothScene({"rows": 16, "cols": 16, "pins": "none", "start": "crumpled",
                       "obstacles": "floor", "self_collision": True, "substeps": 2})
    steps(heap, 10)
    snap = heap.snapshot()
    steps(heap, 60)
    heap.restore(snap)
    steps(heap, 5)
    heap.set("self_distance", 1.0)
    steps(heap, 5)
    heap.set("shear", True)
    heap.set("bending", True)
    steps(heap, 10)
    # a cloth hanging, then one of its particles dragged across it by the mouse and let go
    hang = ClothScene({"rows": 12, "cols": 12, "self_collision": True})
    steps(hang, 20)
    grab = hang.cloth.x[:, 11, 3].astype(float)
    lmb(hang, "mouse_down", grab)
    for k in range(25):
        lmb(hang, "mouse_move", grab + np.array([4.0, -6.0]) * k)
        steps(hang, 1)
    lmb(hang, "mouse_up", grab + np.array([4.0, -6.0]) * 25)
    steps(hang, 10)
    lists = [c.contact.self_list for c in CLOTHS[-3:]]
    assert min(lst.builds for lst in lists) > 1 and min(lst.reuses for lst in lists) > 1
    CLOTHS.clear()


@pytest.mark.parametrize("scene_of, settings, run", [
    (ClothCollisionsScene, {**FOLD, "self_collision": True}, 120),
    (ClothScene, {"rows": 16, "cols": 16, "pins": "none", "start": "crumpled", "obstacles": "floor",
      "self_collision": True}, 180)], ids=["fold card", "heap"])
def test_the_list_moves_the_cloth_as_the_plain_search_does(monkeypatch, scene_of, settings, run):
    """Positions after a run with the list (reused in many steps: the fold lying on the floor,
    the 16 x 16 heap settled) and with a plain search every step (SKIN = 0: the pass as it was
    before the list) agree to 1e-6 of the cloth's size, some 16 float32 steps of a coordinate:
    the same pairs, only summed in another order. (Measured: bit for bit, as the sweeps sum in
    float64 and round to float32 once; not asserted, a rounding tie could tip one value.)"""
    runs = []
    for skin in (self_list.SKIN, 0.0):
        monkeypatch.setattr(self_list, "SKIN", skin)
        scene = scene_of(settings)
        for _ in range(run):
            scene.advance()
        runs.append((scene.cloth.x.astype(float), scene.cloth.contact.self_list.reuses))
    (with_list, reuses), (plain, none) = runs
    assert reuses > 10 and none == 0
    size = np.ptp(plain.reshape(2, -1), axis=1).max()
    assert np.abs(with_list - plain).max() <= 1e-6 * size
