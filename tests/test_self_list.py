"""Self-collision's Verlet list (app/physics/self_list.py): at every substep the pairs it hands
out are exactly the pairs a fresh search finds, over a hanging cloth, a crumpled one landing
and settling, the fold card, a cloth dragged by the mouse, restores of a snapshot and changes
of self_distance and of the rod sets; and the positions it leads to are the plain search's, to
float32 rounding (the pairs the same, only the order of the sums differs). Cheap: small cloths."""

import numpy as np
import pytest

from app.physics import cloth_contact, self_list
from app.physics.neighbours import Scratch, fine_pairs
from app.scene import InputEvent
from scenes.cloth import ClothScene
from scenes.cloth_collisions import FOLD, ClothCollisionsScene


def pair_set(i, j):
    return set(zip(np.minimum(i, j).tolist(), np.maximum(i, j).tolist()))


@pytest.fixture
def checked(monkeypatch):
    """Every call of the list is checked against a fresh search (close_ij on the same cloth, as
    a set, no pair twice); returns the counts (calls, reuses of the list, pairs handed out) and
    the lists seen."""
    seen = {"calls": 0, "reused": 0, "pairs": 0, "lists": []}
    listed = cloth_contact.listed_pairs

    def check(lst, x, distance, key, search, scratch):
        reuses = lst.reuses
        i, j, tests = listed(lst, x, distance, key, search, scratch)
        i, j = i.copy(), j.copy()                   # (work arrays: the search below reuses them)
        got = pair_set(i, j)
        assert len(got) == len(i)
        fresh = search(distance)                    # close_ij(cloth, distance, "grid")
        assert got == pair_set(fresh[0], fresh[1])
        seen["calls"] += 1
        seen["reused"] += lst.reuses - reuses
        seen["pairs"] += len(i)
        if not any(lst is s for s in seen["lists"]):
            seen["lists"].append(lst)
        return i, j, tests
    monkeypatch.setattr(cloth_contact, "listed_pairs", check)
    return seen


def steps(scene, n):
    for _ in range(n):
        scene.advance()


def lmb(scene, kind, pos):
    scene.handle_event(InputEvent(kind, tuple(map(float, pos)), 1))


def test_the_list_hands_out_exactly_the_pairs_a_fresh_search_finds(checked):
    # the fold card: folded, it lands and lies still (the list reused for many steps)
    card = ClothCollisionsScene({**FOLD, "self_collision": True})
    steps(card, 90)
    assert checked["reused"] > 40 and checked["pairs"] > 5000
    # its top layer's end dragged slowly (1 px a step, less than half the skin) along the bottom
    # layer: it meets new partners, and only the measured sum of its moves tells when
    lst = card.cloth.contact.self_list
    grab = card.cloth.x[:, 0, -1].astype(float)
    lmb(card, "mouse_down", grab)
    builds = lst.builds
    for k in range(1, 41):
        lmb(card, "mouse_move", grab + (k, 0.0))
        steps(card, 1)
    lmb(card, "mouse_up", grab + (40.0, 0.0))
    assert 5 < lst.builds - builds < 30             # (a list built every few steps)
    steps(card, 5)
    assert f"list reused {lst.reuses}, built {lst.builds}" in " ".join(map(str, card.hud_lines()))
    # a crumpled cloth falling onto the floor, landing, settling (the list reused); while a
    # list with a skin is in use: self_distance raised, shear and bending switched on (a key
    # change each), a restore of a snapshot taken while it fell
    heap = ClothScene({"rows": 16, "cols": 16, "pins": "none", "start": "crumpled",
                       "obstacles": "floor", "self_collision": True})
    lst = heap.cloth.contact.self_list
    steps(heap, 10)
    snap = heap.snapshot()
    for change in (lambda: heap.set("self_distance", 1.0),
                   lambda: (heap.set("shear", True), heap.set("bending", True)),
                   lambda: heap.restore(snap)):
        for _ in range(300):                        # on until a list is being reused
            steps(heap, 1)
            if lst.skin > 0 and lst.age > 0:
                break
        assert lst.skin > 0 and lst.age > 0
        builds = lst.builds
        change()
        steps(heap, 1)
        assert lst.builds == builds + 1             # rebuilt at once
    steps(heap, 5)
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
    lists = checked["lists"]
    assert len(lists) == 3 and all(lst.builds > 1 and lst.reuses > 1 for lst in lists)


@pytest.mark.parametrize("scene_of, settings, run", [
    (ClothCollisionsScene, {**FOLD, "self_collision": True}, 120),
    (ClothScene, {"rows": 16, "cols": 16, "pins": "none", "start": "crumpled", "obstacles": "floor",
      "self_collision": True, "substeps": 3}, 180)], ids=["fold card", "heap"])
@pytest.mark.parametrize("nudged", [False, True], ids=["as built", "nudged"])
def test_the_list_moves_the_cloth_as_the_plain_search_does(monkeypatch, scene_of, settings, run,
                                                           nudged):
    """At every pass of a run with the list (reused in many steps: the fold lying on the floor,
    the 16 x 16 heap settled), the pass through the list and a plain search's pass (a fresh list:
    no skin), from the same positions, leave every particle at the same place to float32
    rounding: 8 steps of the largest coordinate (the same pairs, only summed in another order).
    Pass by pass, not the two runs' ends: the sums round in float32, and a crumpled heap is
    chaotic (one step of a coordinate grows to pixels within 15 steps of the bench's cloth).
    So the run is any of its trajectories: nudged, every y one float32 step up at the start.
    The heap at 3 substeps, where it stands: at 1 it is crushed (615 of its 710 pairs still
    closer than 95 % of self_distance after 180 steps; 92 of 159 at 3), and how often its list
    was reused in the 180 steps ranged 0-64 over 25 starts one float32 step apart (41-282 at 3)."""
    worst, plain = [], cloth_contact.self_collide

    def both(c, h):
        start, kept = c.x.copy(), c.contact.self_list
        c.contact.self_list = self_list.PairList()      # a fresh list: a plain search
        plain(c, h)
        searched = c.x.copy()
        c.x[...], c.contact.self_list = start, kept
        plain(c, h)                                     # through the run's list
        rounding = np.spacing(np.abs(searched).max())
        worst.append(float(np.abs(c.x - searched).max() / rounding))
    monkeypatch.setattr(cloth_contact, "self_collide", both)
    scene = scene_of(settings)
    if nudged:
        for a in (scene.cloth.x, scene.cloth.x_prev):
            a[1] = np.nextafter(a[1], np.inf)
    for _ in range(run):
        scene.advance()
    assert scene.cloth.contact.self_list.reuses > 10
    assert len(worst) == run * scene.p["substeps"]
    assert max(worst) <= 8, max(worst)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_the_list_matches_every_pair_far_from_the_origin_and_at_the_boundary(dtype):
    """Synthetic clouds jiggled in small steps (the list reused), far from the origin (float32's
    spacing there is 1/128 px, against R = 0.2 px and a skin of 0.15 px) and across 2^16, with
    pairs exactly R apart: the pairs handed out are those of the grid's search and those of an
    all-pairs reference computed apart (the same float operations, all n^2 / 2 pairs), at
    every call (one particle crosses the cloud: the list is rebuilt as it goes); and a float64
    reference agrees away from the boundary."""
    rng = np.random.default_rng(7)
    reused = 0
    for R, off in ((0.2, 1e5), (0.5, 65536.0 - 1.0), (6.4, -3e4)):
        n = 150
        x = (off + rng.random((2, n)) * 4 * R).astype(dtype)
        x[0, 0] = dtype(off - 1.5 * R)
        x[0, 1:11], x[1, 1:11] = x[0, 11:21] + dtype(R), x[1, 11:21]   # (R exact: 0.5 only)
        lst, scratch, search_scratch = self_list.PairList(), Scratch(), Scratch()
        iu, ju = np.triu_indices(n, 1)
        for _ in range(40):
            i, j, _ = self_list.close_pairs(lst, x, R, ("synthetic",),
                                            lambda d: fine_pairs(x[0], x[1], d, search_scratch),
                                            scratch)
            got = pair_set(i, j)
            grid = pair_set(*fine_pairs(x[0], x[1], R, Scratch())[:2])
            dx, dy = x[0, ju] - x[0, iu], x[1, ju] - x[1, iu]
            near = dx * dx + dy * dy < dtype(R * R)
            assert got == grid == pair_set(iu[near], ju[near])
            d = np.hypot(*(x[:, ju].astype(float) - x[:, iu].astype(float)))
            sure, maybe = d < R * (1 - 1e-6), d < R * (1 + 1e-6)
            assert pair_set(iu[sure], ju[sure]) <= got <= pair_set(iu[maybe], ju[maybe])
            x += (rng.standard_normal(x.shape) * 0.01 * R).astype(dtype)
            x[0, 0] += dtype(0.1 * R)       # one particle crossing the cloud (rebuilt every 4)
        reused += lst.reuses
    assert reused > 30


def test_the_list_backs_off_where_it_never_pays(monkeypatch):
    """Particles moving 10 px a substep against R = 1 (no skin lasts): after MISSES plain
    searches in a row the next WAIT substeps search with no displacement test (before, one every
    substep: 11 of 12); once they stop, the list is built with a skin and reused again."""
    tested = []
    real = self_list.moved
    monkeypatch.setattr(self_list, "moved", lambda lst, x: tested.append(1) or real(lst, x))
    lst, x = self_list.PairList(), np.zeros((2, 10), np.float32)
    x[0] = np.arange(10) * 3.0

    def search(d):
        return fine_pairs(x[0], x[1], d, Scratch())
    for step in range(12):
        x += 10.0
        self_list.close_pairs(lst, x, 1.0, ("k",), search, Scratch())
    assert lst.builds == 12 and len(tested) == 3        # substeps 2, 3 and 8
    assert (self_list.MISSES, self_list.WAIT) == (2, 4)
    for step in range(2 * self_list.WAIT + 4):
        self_list.close_pairs(lst, x, 1.0, ("k",), search, Scratch())
    assert lst.reuses > 0


def test_the_list_backs_off_longer_each_time_a_skin_did_not_last():
    """A particle shaking back and forth (0.5 px a substep against R = 1 and a skin of 0.75,
    so no list with a skin outlives a substep) while its net move over a few substeps is nil:
    measured over the back-off's substeps it looks still, and a list with a skin was built
    every ~7 substeps, each a search over R + skin that was never reused (the 64 x 64 heap
    settled at 1 substep: ~40 in 300 steps, the grid's search 2.75 ms each over R + skin against
    1.11 over R). After such a list the
    back-off now lasts COOL substeps, twice as long after each one in a row: a few in 200."""
    x = np.zeros((2, 10), np.float32)
    x[0] = np.arange(10) * 3.0
    skinned = []

    def search(d):
        skinned.append(d > 1.0)
        return fine_pairs(x[0], x[1], d, Scratch())
    lst = self_list.PairList()
    for step in range(200):
        x[0, 0] += 0.5 if step % 2 else -0.5
        i, j, _ = self_list.close_pairs(lst, x, 1.0, ("k",), search, Scratch())
        assert pair_set(i, j) == pair_set(*fine_pairs(x[0], x[1], 1.0, Scratch())[:2])
    assert lst.reuses == 0 and 1 <= sum(skinned) <= 6
    assert (self_list.COOL, self_list.COOL_MAX) == (8, 256)
