"""The tables falling_balls keeps beside its list of balls, laid out so that a ball added or
removed costs plain Python and no NumPy call (each costs 1-2 us in the step's loop):
  * every ball has a slot for life (self._slots, in the order of self.balls; self._slot_of by
    body id): its last known centre sits in row `slot` of self._xy, so taking a ball out moves
    no other ball's row (slots are handed out in turn and packed again when they run out);
  * who is awake (Awake) is kept as Chipmunk keeps it: a list of body ids in the order of its
    array of awake bodies, which appends a new body and fills a removed one's place with the
    last (cpArrayDeleteObj). The same moves on Python lists and on the bytes of the ids and of
    the flags let the usual check (ball_checks.py) go on after a ball came or went, with no
    read;
  * the flags' bytes themselves (fast_of, _changed: BallChecks._fast; rows_finite).
"""

from __future__ import annotations

import math
import sys

import numpy as np

_ORDER = sys.byteorder                          # (Awake.plus: an id's bytes)
_NO_IDS = (b"", np.empty(0, dtype=np.int64))   # (slot_index's last: ids as bytes, slots)


# Arrays kept by the number of awake rows (and pose), up to SIZES_KEPT sizes, then made afresh
# (in 6,000 steps of pivoting_l, 16 kept made 160 new flag arrays and 160 new Lines, one by
# size and the L's row; 64 kept, a Line by size alone: 50 and 49). A size's arrays take ~250
# bytes a row, so fewer are kept when the size coming in is large: ROWS_KEPT // n sizes, never
# fewer than 16 (so ROWS_KEPT rows' worth only below 512 rows: 16 sizes of 5000 rows are ~20 MB
# at that rate; 64 had kept up to 74 MB for a 5000-ball pile with its spawner on). Counted as a
# size comes in: the sizes kept before it may be larger.
SIZES_KEPT = 64
ROWS_KEPT = 8192


def sizes_full(sizes: dict, n: int) -> bool:
    """Whether a table of arrays kept by size, about to take n rows more, is full (clear it)."""
    return len(sizes) >= min(SIZES_KEPT, max(16, ROWS_KEPT // max(n, 1)))


def slot_table(n: int) -> np.ndarray:
    """An empty table of centres for n balls and room for as many more."""
    return np.zeros((max(64, 2 * n + 2), 2))


def _nan_fails_box() -> bool:
    """Whether a NaN or an inf anywhere in a row makes its box flags false in _usual_check's
    product (NaN * 0 is NaN in every BLAS that multiplies through; one that skips zero weights
    would not propagate a NaN from the angle or velocities: then the runner's own check stays
    on)."""
    M = np.zeros((6, 5))
    M[0, 0], M[0, 1], M[1, 2], M[1, 3], M[0, 4], M[1, 4] = -1.0, 1.0, -1.0, 1.0, 0.5, -0.8
    limits = np.full(5, 1e9)
    for n in (1, 2, 5, 16, 65, 300):
        for col in range(6):
            for bad in (math.nan, math.inf, -math.inf):
                rows = np.ones((n, 6))
                rows[n // 2, col] = bad
                with np.errstate(invalid="ignore"):
                    if (rows.dot(M) <= limits)[n // 2, :4].all():
                        return False
    return True


_NAN_FAILS = _nan_fails_box()


def rows_finite(b: bytes, L_row: int | None) -> bool:
    """Whether the flags' bytes b (5 a row) of rows whose balls are all in the box (their key
    says so) also say that every row is finite: a NaN or inf anywhere in a row fails its box
    flags (_NAN_FAILS), so the balls' are; the L's too if its box flags hold. Then the runner's
    non-finite check need not look at these rows again (~1.75 us a step)."""
    return _NAN_FAILS and (L_row is None or b[5 * L_row:5 * L_row + 4] == b"\1\1\1\1")


class Awake:
    """The bodies awake after the last check, row by row in the batch's order (Chipmunk's array
    of awake bodies): what the next read is compared with, and which ball each row is."""

    __slots__ = ("ids", "slots", "L_row", "balls", "key", "_arrays")

    def __init__(self, ids: list[int], slots: list[int], L_row: int | None, balls: int,
                 key: bytes, arrays: tuple | None = None):
        self.ids = ids          # each row's body id
        self.slots = slots      # each row's ball slot, -1 for a row that is no ball (the L)
        self.L_row = L_row      # the L's row (None: the L is not awake: static or asleep)
        self.balls = balls      # how many rows are balls
        self.key = key          # the ids' bytes and the first static body's id (8 bytes more)
        self._arrays = arrays

    def arrays(self) -> tuple[np.ndarray | None, np.ndarray]:
        """(the rows that are balls, None if every row is; their slots), as arrays, made once
        (for writing a read's centres into self._xy)."""
        if self._arrays is None:
            slots = np.array(self.slots, dtype=np.int64)
            rows = None
            if self.balls != len(slots):
                rows = np.flatnonzero(slots >= 0)
                slots = slots[rows]
            self._arrays = (rows, slots)
        return self._arrays

    def plus(self, body: int, slot: int) -> "Awake":
        """The same with a new ball's body last (Chipmunk appends a new body to its array)."""
        key = self.key
        return Awake(self.ids + [body], self.slots + [slot], self.L_row, self.balls + 1,
                     key[:-8] + body.to_bytes(8, _ORDER, signed=True) + key[-8:])

    def without(self, body: int, flags: bytes) -> tuple["Awake", bytes] | None:
        """(the same without this body, the flags' bytes (5 a row) without its row): as
        cpArrayDeleteObj takes it out of Chipmunk's array, the last row moves into its place.
        None if the body is not among them."""
        try:
            i = self.ids.index(body)
        except ValueError:
            return None
        last = len(self.ids) - 1
        ids, slots = self.ids[:last], self.slots[:last]     # (copies but of the last row)
        balls = self.balls - (self.slots[i] >= 0)
        key, L_row = self.key, self.L_row
        if i < last:
            ids[i], slots[i] = self.ids[last], self.slots[last]
            key = key[:8 * i] + key[8 * last:8 * last + 8] + key[8 * i + 8:8 * last] + key[-8:]
            flags = flags[:5 * i] + flags[5 * last:] + flags[5 * i + 5:5 * last]
            L_row = i if L_row == last else L_row
        else:
            key, flags = key[:8 * last] + key[-8:], flags[:5 * last]
        return Awake(ids, slots, L_row, balls, key), flags


class BallTables:
    """The slot tables of FallingBallsScene (restored() builds them; ball_checks.BallChecks
    reads them)."""

    def _index_changed(self) -> None:
        """Forget the lookups made from the slots (a ball came or went)."""
        self._last = _NO_IDS
        self._ball_of = None                      # (each slot's place in self.balls), lazily

    def slot_index(self, ids: np.ndarray) -> np.ndarray:
        """For body ids (n,) from a batch read: the slot of each ball, -1 if it is not a ball (a
        static body, the L): a dict lookup per id (kept as balls come and go: a binary search
        in sorted ids costs several NumPy calls more, and the sort again after every change);
        not even that while the batch order stays the same."""
        last_ids, last_k = self._last
        key = ids.tobytes()                 # (a bytes compare: np.array_equal costs 4x)
        if key == last_ids:
            return last_k
        get = self._slot_of.get
        k = np.array([get(i, -1) for i in ids.tolist()], dtype=np.int64)
        self._last = (key, k)
        return k

    def ball_index(self, ids: np.ndarray) -> np.ndarray:
        """For body ids (n,) from a batch read: the index of each in self.balls, -1 if it is not
        a ball."""
        if self._ball_of is None:
            ball_of = np.full(self._used + 1, -1, dtype=np.int64)   # (slot -1: the last, -1)
            ball_of[self._slots] = np.arange(len(self._slots))
            self._ball_of = ball_of
        return self._ball_of[self.slot_index(ids)]

    def new_slot(self, body_id: int, pos: tuple[float, float]) -> int:
        """A slot for a new ball (the next one not yet handed out), with its id and centre."""
        slot = self._used
        if slot == len(self._xy):
            slot = self.pack_slots()
        self._used = slot + 1
        self._slot_of[body_id] = slot
        xy = self._xy
        xy[slot, 0], xy[slot, 1] = pos          # (two numbers: a tuple into a row costs more)
        return slot

    def pack_slots(self) -> int:
        """The slots ran out: give the balls slots 0, 1, ... again in tables with room for as
        many more (the awake rows' slots renamed with them); returns the first free slot."""
        self.flush_xy()
        live = np.array(self._slots, dtype=np.int64)
        n = len(live)
        xy = slot_table(n)
        xy[:n] = self._xy[live]
        self._xy, self._used = xy, n
        rename = {old: new for new, old in enumerate(self._slots)}
        self._slots = list(range(n))
        self._slot_of = {body: rename[slot] for body, slot in self._slot_of.items()}
        awake = self._awake
        if awake is not None:
            self._awake = Awake(awake.ids, [rename.get(s, -1) for s in awake.slots],
                                awake.L_row, awake.balls, awake.key)
        self._index_changed()
        return n

    def remove_slots(self, slots: list[int]) -> None:
        """remove_balls for the balls in these slots, their indices listed in this order (the
        set remove_balls makes of them is built in it: the order the space loses them in)."""
        if len(slots) <= 8:                 # (map: a comprehension is a call of its own)
            self.remove_balls(list(map(self._slots.index, slots)))
        else:
            place = {s: k for k, s in enumerate(self._slots)}
            self.remove_balls([place[s] for s in slots])


def fast_of(pose: tuple[float, float, float], b: bytes, L_row: int | None,
            key: bytes | None = None) -> tuple:
    """BallChecks._fast (ball_checks.py): (the L's pose, the awake rows' flags' bytes b (5 a row,
    each 0 or 1), their key: b less the L's row (a moving L's centre is on its own arm's line:
    its flag flips with rounding); the key None if a ball is outside the box or not finite: then
    the next step looks again). key: the caller's, if it has it."""
    if key is None:
        key = b if L_row is None else b[:5 * L_row] + b[5 * L_row + 5:]
    # every ball's four box flags true (each centre inside the world's box): every fifth byte
    # from the first, the second, the third and the fourth (plain Python, no NumPy call)
    if 0 in key[0::5] or 0 in key[1::5] or 0 in key[2::5] or 0 in key[3::5]:
        return pose, b, None
    return pose, b, key


def _changed(old: bytes, new: bytes) -> list[tuple[int, int]]:
    """(row, column) of each flag that differs between two flags' bytes (the last step's and
    this one's), in order. A few: the bytes as two integers, XOR, and its set bits read off one
    by one (plain Python, a fraction of a NumPy call each); many (a bit read is O(size) then):
    NumPy."""
    x = int.from_bytes(old, "little") ^ int.from_bytes(new, "little")
    if not x & (x - 1):                    # (one flag: the usual case, a ball crossed a line)
        return [divmod((x.bit_length() - 1) >> 3, 5)] if x else []
    if x.bit_count() > 16:
        diff = np.frombuffer(old, dtype=np.uint8) != np.frombuffer(new, dtype=np.uint8)
        return [divmod(i, 5) for i in np.flatnonzero(diff).tolist()]
    out = []
    while x:
        low = x & -x                       # (each flag is one byte, 0 or 1: bit 8 i is flag i)
        out.append(divmod((low.bit_length() - 1) >> 3, 5))
        x ^= low
    return out
