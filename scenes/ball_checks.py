"""What falling_balls (and pivoting_l) check after every step: balls that tunneled through the
L's long arm, and balls that left the world (removed). A part of FallingBallsScene kept in a
module of its own (FallingBallsScene inherits BallChecks).

The usual step is cheap: while the same bodies stay awake, one product of their rows (x, y,
angle, vx, vy, w) with a (6, 5) matrix and one comparison give five flags a body (or, with the
L along x, comparisons alone: ball_bounds.py): its centre inside the world's box (x >= -2r, x <=
w + 2r, y >= -h, y <= h + 2r: four, the very comparisons of the exact test) and on or below the
arm's line. If the flags' bytes are the ones kept from the last step, no ball crossed the line
and none left: 3 NumPy calls however many balls (in the step's loop each costs 1-2 us; a ufunc's
max() or a comparison with a broadcast row costs several). A change (a ball that crossed the line, a
ball outside the box, a NaN) is found among the few flags that changed, and each goes to the
exact test on that ball alone (plain Python). A few balls falling asleep or waking (the L
static) take the short way: the awake rows mirrored as Chipmunk moves them, the usual check on
them, the usual tests on each ball that fell asleep. Any other change in who is awake, or the L
woken, goes the long way, with the exact tests below on every ball (count_tunneled,
remove_fallen: tests check the ways agree, tunneling by tunneling).

The tables kept between steps (ball_tables.py) are laid out so that a ball added or removed
keeps the usual path on at the cost of a few Python list and bytes moves, no NumPy call.
"""

from __future__ import annotations

import warnings
from itertools import filterfalse

import numpy as np

from app.pymunk_scene import extent
from scenes.ball_bounds import compared_flags
from scenes.ball_tables import Awake, _changed, fast_of, rows_finite, sizes_full
from scenes.l_frame import body_pose, cos_sin, local_x as _local_x, to_local as _to_local

# A ball gone non-finite (NaN or inf in any of its row's numbers) makes NaN flags in the
# product of _usual_check, on purpose: a NaN fails every comparison, so the ball goes to the
# exact tests and is removed that step. NumPy would also print "invalid value encountered in
# dot" for it; the lab reports the ball itself, so that warning is not shown (only this
# module's, only that message; np.errstate around the product would cost ~3 us on every step to
# hide a rare one).
warnings.filterwarnings("ignore", message="invalid value encountered in dot",
                        category=RuntimeWarning, module=r"scenes\.ball_(checks|look)")


class BallChecks:
    """The checks after a step of falling_balls. Expects self.balls, the slot tables (a ball's
    centre after the last step it was looked at, by slot: self._xy; ball_tables.py),
    self.L_body, self.counts and the tables of FallingBallsScene.restored."""

    arm_extent: tuple[float, float] = (0.0, 0.0)   # the long arm's ends along the L's own x

    def _checks_reset(self) -> None:
        """Forget what was kept between steps (the tables were rebuilt)."""
        self._awake: Awake | None = None    # who is awake after the last check
        # self._fast: (the L's pose, the awake rows' flags' bytes, their key: fast_of)
        self._fast = None
        # self._prev: (the Awake of the read, its rows) of the last step, not yet written into
        # self._xy (None: nothing kept; the slots stay a ball's while it lives, so a ball come
        # or gone since does not spoil them)
        self._prev = None
        self._flag_rows = None      # [n, product, limits (n, 5), their pose, their column 4,
                                    # M] (_flag_rows_at), and those for other n by n
        self._flag_sizes: dict = {}
        self._bound_sizes: dict = {}  # (ball_bounds.bounds_for: by rows and pose; Lines by rows)
        self._frames: dict = {}     # the L's frame at a few poses (_frame)
        self._views: dict = {}      # a read's views by its rows' id (_awake_views)
        self._keeps = ((0, self._own_prev), (1, self._own_prev))    # (the reader's keep, a buffer)

    def flush_xy(self) -> None:
        """Write the awake balls' centres from the last step into self._xy (the usual step keeps
        the reader's rows aside: writing them into place by slot costs more than keeping)."""
        prev = self._prev
        if prev is not None:
            self._prev = None
            self._write_centres(prev)

    def _write_centres(self, kept: tuple) -> None:
        """Write the ball rows' centres of a kept read (Awake, rows) into self._xy."""
        rows, slots = kept[0].arrays()
        data = kept[1]
        self._xy[slots] = data[:, :2] if rows is None else data[rows, :2]

    def _own_prev(self) -> None:
        """The reader is about to refill the rows self._prev holds: copy them (_usual_check)."""
        prev = self._prev
        if prev is not None and prev[1].base is not None:
            self._prev = (prev[0], prev[1].copy())

    def check_balls(self, L0: tuple[float, float, float]) -> tuple[float, float, float]:
        """After a step: count the balls that tunneled through the L, remove those that left the
        world, remember every ball's centre (self._xy); return the L's pose after the step (L0:
        before it). Only a body awake before or after the step can have moved: while the same
        bodies stay awake (and the L stays put, or no body sleeps), only they are looked at, and
        so they are when a few fall asleep or wake (_short_way); otherwise every ball is. The
        bodies are read once (state_rows: the runner's is_finite reuses the read), the L's pose
        with them while the same bodies stay awake."""
        ids, data = self.state_rows()
        awake, fast = self._awake, self._fast
        # the same awake ids in the same order, then the same first static body (the batch's
        # order is awake | static | asleep): one bytes compare (awake.key holds both)
        same = awake is not None and ids.tobytes()[:len(awake.key)] == awake.key
        if same:
            n, L_row = len(awake.ids), awake.L_row
            views = self._views.get(id(data))      # (this read's awake rows and the L's row)
            if views is None or views[0] is not awake:
                views = self._awake_views(data, awake)
            if L_row is None:
                L1 = self._L_static_pose or self.L_pose()
            else:
                L1 = tuple(views[2].tolist())
            # (a sleeping ball does not move, but a moving L may pass it: so with balls
            # asleep, a moving L means looking at every ball)
            same = L0 == L1 or len(ids) == n + len(self._static_ids)
            if same and fast is not None and fast[2] is not None and fast[0] == L0 \
                    and awake.balls:
                return self._usual_check(views[1], L0, L1, awake, fast)
        else:
            L1 = self.L_pose()
            if fast is not None and fast[2] is not None and fast[0] == L0 == L1 \
                    and self._L_static_pose is not None:
                done = self._short_way(ids, data, L1, fast)   # (a few fell asleep or woke)
                if done:
                    return L1
        self.flush_xy()
        if same:                  # the same bodies awake as after the last step
            rows, k = awake.arrays()
            xy = data[:n, :2] if rows is None else data[rows, :2]
        else:
            n = self.awake_count(ids)
            every = self.slot_index(ids)
            ball = every >= 0
            xy, k = data[ball, :2], every[ball]       # every ball, awake or asleep
            count = int(np.count_nonzero(ball[:n]))
            id_list, L = ids[:n].tolist(), self._L_id
            self._awake = Awake(id_list, every[:n].tolist(),
                                id_list.index(L) if L in id_list else None, count,
                                ids[:n + 1].tobytes(),
                                (None if count == n else np.flatnonzero(ball[:n]), k[:count]))
            self.resting = n == 0
        self._fast = None
        if not len(k):
            return L1
        self.count_tunneled(self._xy[k], xy, L0, L1)
        self._xy[k] = xy
        awake = self._awake
        if awake is not None and awake.balls:   # (made before remove_fallen, which takes the
            self._fast = self.flags_of(data[:len(awake.ids)], L1, awake.L_row)   # rows out)
            if self._fast[2] is not None:       # every awake ball in the box (their flags are
                k, xy = k[awake.balls:], xy[awake.balls:]     # its very comparisons): only
        self.remove_outside(k, xy)                            # those asleep are looked at
        return L1

    def _awake_views(self, data: np.ndarray, awake: Awake) -> tuple:
        """(awake, the awake rows data[:n], the L's (x, y, angle) or None, data, with the L
        awake the rows' centres x + iy as complex numbers (ball_look.Line) or None, and (awake,
        data[:n]): what a look keeps in self._prev, made once) for a read's rows, kept by the
        rows' id (the reader's two buffers give two; a slice costs ~1.7k instructions, a tenth
        of the usual check): made again when who is awake changed (data kept: a new array's id
        is never a kept one's)."""
        if len(self._views) >= 2:
            self._views.clear()
        L_row, n = awake.L_row, len(awake.ids)
        views = (awake, now := data[:n], None if L_row is None else data[L_row, :3], data,
                 None if L_row is None else data[:n, :2].view(complex)[:, 0], (awake, now))
        self._views[id(data)] = views
        return views

    def _short_way(self, ids: np.ndarray, data: np.ndarray, pose, fast: tuple) -> bool:
        """check_balls when a few balls fell asleep or woke (the L static, the usual path on
        until now); False if it cannot (then the long way). Chipmunk took each ball that fell
        asleep out of its array of awake bodies (the last into its place) and appended each
        one woken: the kept Awake after Awake.without and Awake.plus, if it is the read's, says
        which row is which, and the usual check goes on, with the flags each woken ball had
        where it slept. The balls that fell asleep get the usual tests on their own (their
        flags before, from the kept bytes; now, flags_row), and their centres are kept. Their
        centres before come from the last look's rows when it kept them (self._prev, for the
        Awake it was made with): not every ball's written into self._xy first (flush_xy); the
        rest of them stay in self._prev, which the usual check replaces. (The bench's long run
        of falling_balls, 62 short ways: 260.6k -> 259.5k instructions a step, callgrind.)"""
        old, prev = self._awake, self._prev
        id_list = ids.tolist()
        try:                    # the awake rows: those before the static block, which holds
            n = id_list.index(self._L_id)           # the L's row (static here)
        except ValueError:
            return False
        static = self._static_set
        while n and id_list[n - 1] in static:
            n -= 1
        awake_ids = id_list[:n]
        asleep = list(filterfalse(set(awake_ids).__contains__, old.ids))
        woken = n - len(old.ids) + len(asleep)    # (how many woke: the ids are unique)
        if not n or len(asleep) + woken > 8:
            return False
        woke = list(filterfalse(set(old.ids).__contains__, awake_ids)) if woken else []
        if prev is not None and prev[0] is not old:     # (kept before a ball came or went)
            self.flush_xy()
            prev = None
        slot_of, awake, flags, gone, xy = self._slot_of, old, fast[1], [], self._xy
        for body in asleep:
            i, slot = awake.ids.index(body), slot_of.get(body, -1)
            if slot < 0:
                return False                 # (not a ball)
            p0 = (xy[slot] if prev is None else prev[1][old.ids.index(body), :2]).tolist()
            gone.append((slot, id_list.index(body), flags[5 * i:5 * i + 5], p0))
            awake, flags = awake.without(body, flags)
        for body in woke:
            if body not in slot_of:
                return False                 # (not a ball)
            awake = awake.plus(body, slot_of[body])
        if awake.ids != awake_ids:
            return False
        for body in woke:                    # (asleep until now: its centre is in self._xy)
            flags += self.flags_row(tuple(xy[slot_of[body]].tolist()), pose)
        self._awake = awake
        self._usual_check(data[:n], pose, pose, awake, fast_of(pose, flags, None))
        ax, bx = self.arm_extent
        x0, y0, x1, y1 = self.box()
        out = []
        for slot, row, was, p0 in gone:     # (asleep now: their rows are after the static ones)
            p1 = data[row, :2].tolist()
            xy[slot, 0], xy[slot, 1] = p1
            if not was[4] and self.flags_row(p1, pose)[4]:     # crossed the arm's line
                if ax <= _local_x(p0, pose) <= bx and ax <= _local_x(p1, pose) <= bx:
                    self.counts["tunneled"] += 1
            x, y = p1
            if not (x >= x0 and y >= y0 and x <= x1 and y <= y1):     # (NaN fails)
                out.append(slot)
        if out:
            self.remove_slots(out)
        return True

    def flags_of(self, rows: np.ndarray, pose, L_row: int | None) -> tuple:
        """self._fast for these awake rows with the L at pose (fast_of)."""
        M, limits = self._flag_matrix(pose)
        with np.errstate(invalid="ignore"):   # (a row gone inf: NaN flags; the runner reports it)
            flags = rows.dot(M) <= limits
        return fast_of(pose, flags.tobytes(), L_row)

    def _usual_check(self, rows_now: np.ndarray, L0, L1, awake: Awake, fast: tuple):
        """check_balls while the same bodies stay awake (rows_now: their rows, balls and maybe
        the L): five flags a row (x and y inside the world's box, four, and the centre on or
        below the arm's line), out of look's comparisons where the L lies along x, else one
        product of the rows with a (6, 5) matrix and one comparison; a crossing is found by a
        change in the line's flag and a ball outside by the box's: each to the exact tests."""
        kept = self._flag_rows      # (for these rows and L1 already, unless a moving L moved)
        if kept is None or kept[0] != len(rows_now):
            kept = self._flag_rows_at(len(rows_now), L1)
        elif kept[3] != L1:
            self._flag_matrix(L1)   # (a moving L: its line's limit written again, kept's too)
        b = compared_flags(self, rows_now) or np.less_equal(      # (None: the product)
            rows_now.dot(kept[5], out=kept[1]), kept[2]).tobytes()
        return self._flags_seen(rows_now, L0, L1, awake, fast, b)

    def _flags_seen(self, rows_now: np.ndarray, L0, L1, awake: Awake, fast: tuple, b: bytes):
        """_usual_check's end, from the flags' bytes made (b: the key, and the L's box flags,
        from one call); ball_look.look comes here when they changed."""
        L_row = awake.L_row
        key = b if L_row is None else b[:5 * L_row] + b[5 * L_row + 5:]
        # (for flush_xy) the reader's rows themselves, no copy: they stay good through the next
        # read, and a read that would refill them first has _own_prev copy them (0.5 us a check)
        prev, self._prev = self._prev, (awake, rows_now)
        reader = self._state_reader
        reader.keep = self._keeps[reader.cur]  # ((reader.cur, self._own_prev), made once)
        if key == fast[2]:                     # the same flags as after the last step
            self._fast = (L1, b, key)
            if rows_finite(b, L_row):          # (every ball in the box: the key says so)
                self.finite_read = reader.reads
            return L1
        changed = _changed(fast[1], b)
        slots = awake.slots
        crossed, box = [], set()              # (a loop: a comprehension is a call of its own)
        for r, col in changed:
            if col == 4:
                if b[5 * r + 4] and slots[r] >= 0:
                    crossed.append(r)
            elif slots[r] >= 0:
                box.add(r)
        self._fast = fast_of(L1, b, L_row, key)
        if self._fast[2] is not None and rows_finite(b, L_row):    # (every ball in the box)
            self.finite_read = reader.reads
        if crossed:                   # above the line before, on or below it now: inside the
            if prev is not None and prev[0] is not awake:   # arm's extent? (a ball came or
                self._write_centres(prev)                   # went since the last step: its
                prev = None                                 # rows are in another order)
            ax, bx = self.arm_extent
            for r in crossed:     # (where it is now first: off the arm's end, where it was is
                if ax <= _local_x(rows_now[r, :2].tolist(), L1) <= bx:        # not looked up)
                    p0 = self._xy[slots[r]].tolist() if prev is None else prev[1][r, :2].tolist()
                    if ax <= _local_x(p0, L0) <= bx:
                        self.counts["tunneled"] += 1
        if self._fast[2] is None:   # a ball outside the box, or not finite: those whose box
            out = []                # flags changed (they were all true), by the exact test
            x0, y0, x1, y1 = self.box()
            for r in sorted(box):
                x, y = rows_now[r, :2].tolist()
                if not (x >= x0 and y >= y0 and x <= x1 and y <= y1):     # (NaN fails)
                    out.append(slots[r])
            if out:
                self.remove_slots(out)
        return L1

    def box(self) -> tuple[float, float, float, float]:
        """(x min, y min, x max, y max) of the centres kept: the world, 2 radii more to the
        sides and below, a world's height more above (remove_fallen)."""
        w, h = self.world_size
        r = self.p["radius"]
        return -2 * r, -h, w + 2 * r, h + 2 * r

    def remove_outside(self, k: np.ndarray, xy: np.ndarray) -> None:
        """remove_fallen(k, xy), after a quick look: if the points' extent is inside the box, no
        ball is out (the same comparisons as remove_fallen's; a NaN fails them)."""
        if not len(xy):
            return
        if len(xy) > 64:        # (a few: remove_fallen's look at each costs less, one call)
            x0, y0, x1, y1 = self.box()
            lo_x, lo_y, hi_x, hi_y = extent(xy)
            if lo_x >= x0 and lo_y >= y0 and hi_x <= x1 and hi_y <= y1:
                return
        self.remove_fallen(k, xy)

    def awake_after_add(self, body: int, slot: int, pos: tuple[float, float]) -> tuple:
        """(self._awake, self._fast) after a ball with this body id and slot was added at pos
        (Awake.plus: Chipmunk appends it to its awake bodies, so the order is known without a
        read; the next step's check_balls compares it with the read, and goes the long way if
        it differs); its flags are a last row (flags_row). (None, None) if nothing was kept."""
        awake, fast = self._awake, self._fast
        if awake is None:
            return None, None
        awake = awake.plus(body, slot)
        if fast is None:
            return awake, None
        row = self.flags_row(pos, fast[0])
        inside = fast[2] is not None and row[:4] == b"\1\1\1\1"        # (in the box)
        return awake, (fast[0], fast[1] + row, fast[2] + row if inside else None)

    def awake_after_removal(self, bodies: list[int]) -> tuple:
        """(self._awake, self._fast) after the balls with these body ids (in the order they were
        taken out) left the space (Awake.without, for each in turn: Chipmunk fills a removed
        body's place in its awake array with the last one, so the order of the rest is known
        without a read; the next step's check_balls compares it with the read), if the usual
        path was on; else (None, None)."""
        awake, fast = self._awake, self._fast
        if awake is None or fast is None:
            return None, None
        flags = fast[1]
        for body in bodies:
            after = awake.without(body, flags)
            if after is None:
                return None, None
            awake, flags = after
        if not awake.ids:
            return None, None
        return awake, fast_of(fast[0], flags, awake.L_row)

    def flags_row(self, pos: tuple[float, float], pose: tuple[float, float, float]) -> bytes:
        """The flags' bytes (5) of a body at rest at pos with the L at pose, as _usual_check
        makes them for a body's row."""
        now = self._flag_now
        if now is None or now[0] != pose or now[3] is None:     # (else made for this pose)
            M, limits = self._flag_matrix(pose)
            now = self._flag_now    # (limits and M[:2, 4] as floats, made once a pose)
            now[3] = tuple(limits.tolist() + M[:2, 4].tolist())
        x, y = float(pos[0]), float(pos[1])
        lx, ux, ly, uy, c, m0, m1 = now[3]
        ax, ay = -m0, -m1
        v = x * -ax + y * -ay                  # the product's last column, in plain Python:
        if abs(v - c) <= 1e-12 * (abs(x * ax) + abs(y * ay) + abs(c)):   # its sign is the
            return (np.array(((x, y, 0.0, 0.0, 0.0, 0.0),)).dot(now[1]) <= now[2]).tobytes()
        return bytes((-x <= lx, x <= ux, -y <= ly, y <= uy, v <= c))   # product's unless near

    def L_pose(self) -> tuple[float, float, float]:
        """The L's (x, y, angle): read from its body, or, for a static L (nothing moves it: a
        step does not, nor can the mouse), the pose it had when the tables were built."""
        pose = self._L_static_pose
        return body_pose(self.L_body) if pose is None else pose

    def _frame(self, pose: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray]:
        """(origin, axis) arrays of the L's frame at pose: a point's height over the arm is
        (p - origin) . axis (_to_local's y, axis the L's local y axis). The last few are kept
        (a static L has one pose; a moving L's pose before a step is the one after the last)."""
        kept = self._frames
        frame = kept.get(pose)
        if frame is None:
            if len(kept) >= 4:
                kept.clear()
            x, y, a = pose
            c, s = cos_sin(a)
            frame = kept[pose] = (np.array((x, y)), np.array((-s, c)))
        return frame

    def _flag_matrix(self, pose: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray]:
        """(M (6, 5), limits (5,)) with the L at pose: for a body's row (x, y, angle, vx, vy,
        w), row . M <= limits are its five flags: x >= -2r, x <= w + 2r, y >= -h, y <= h + 2r
        (inside the world's box, remove_fallen's test) and height over the arm >= 0 (on or
        below its line; a NaN fails all five). Only the last column depends on the pose: it is
        written in place when the pose changed (a moving L: every step), so the arrays are
        good until the next call with another pose."""
        now = self._flag_now
        if now is None:
            w, h = self.world_size
            r = self.p["radius"]
            M = np.zeros((6, 5))
            M[0, 0], M[0, 1], M[1, 2], M[1, 3] = -1.0, 1.0, -1.0, 1.0
            now = self._flag_now = [None, M, np.array((2 * r, w + 2 * r, h, h + 2 * r, 0.0)),
                                    None]
        if now[0] != pose:
            x, y, a = pose
            cos, sin = cos_sin(a)
            ax, ay = -sin, cos
            c = -(x * ax + y * ay)
            M, limits = now[1], now[2]
            M[0, 4], M[1, 4], limits[4] = -ax, -ay, c
            now[0] = pose
            now[3] = None           # (flags_row's floats of them: made when it needs them)
            kept = self._flag_rows      # (only the line's limit depends on the pose: the kept
            if kept is not None:        # rows' column alone, 0.2 us; the whole array 0.6)
                kept[4].fill(c)
                kept[3] = pose
        return now[1], now[2]

    def _flag_rows_at(self, n: int, pose: tuple[float, float, float]) -> list:
        """[n, product (n, 5), limits (n, 5), pose, the limits' column 4, M] for n rows with the
        L at pose: rows.dot(M, out=product) <= limits are _flag_matrix's flags for n
        C-contiguous rows (_usual_check), into a product kept for n rows and against the limits
        written out for every row (a comparison with a broadcast (5,) row costs three times one
        with an (n, 5) array; into a kept bool array too, out=, costs ~400 instructions more)."""
        M, limits = self._flag_matrix(pose)       # (writes a new pose into the kept rows too)
        kept = self._flag_rows
        if kept is None or kept[0] != n:      # (kept by n too: balls come and go, ~10k
            sizes = self._flag_sizes          # instructions a new one)
            kept = sizes.get(n)
            if kept is None:
                if sizes_full(sizes, n):
                    sizes.clear()
                full = np.empty((n, 5))
                full[:] = limits
                kept = sizes[n] = [n, np.empty((n, 5)), full, pose, full[:, 4], M]
            elif kept[3] != pose:             # (made at another pose of a moving L)
                kept[4].fill(limits[4])
                kept[3] = pose
            self._flag_rows = kept
        return kept

    def count_tunneled(self, xy0: np.ndarray, xy1: np.ndarray,
                       L0: tuple[float, float, float], L1: tuple[float, float, float]) -> None:
        """Count balls whose centre crossed the L's long arm from above to below in this step
        while inside its x-extent, seen in the L's own frame before (L0) and after (L1), all
        balls at once. xy0 and xy1 (n, 2) hold the same balls in the same order. (The x-extent
        is looked at only for balls that crossed.)"""
        o0, axis0 = self._frame(L0)
        y0 = (xy0 - o0) @ axis0
        o1, axis1 = self._frame(L1)
        y1 = (xy1 - o1) @ axis1
        crossed = (y0 < 0) & (y1 >= 0)               # above the arm, then on/below it
        if np.count_nonzero(crossed):     # (a ball at rest, asleep or not, never crossed)
            self._count_inside(xy0[crossed], xy1[crossed], L0, L1)

    def _count_inside(self, p0: np.ndarray, p1: np.ndarray, L0, L1) -> None:
        """Of the balls that crossed the arm's line (centres before p0, after p1), count those
        inside its x-extent before and after."""
        p0, p1 = _to_local(p0, L0), _to_local(p1, L1)
        ax, bx = self.arm_extent
        inside = (p0[:, 0] >= ax) & (p0[:, 0] <= bx) & (p1[:, 0] >= ax) & (p1[:, 0] <= bx)
        self.counts["tunneled"] += int(np.count_nonzero(inside))

    def remove_fallen(self, k: np.ndarray, xy: np.ndarray) -> None:
        """Remove the balls (slots k, centres xy) whose centre left the world: below it, far
        to a side, or more than a world's height above it (new balls fall in from just above,
        so "above" needs the margin). A non-finite centre counts as out."""
        if not len(xy):
            return
        x0, y0, x1, y1 = self.box()
        if len(xy) <= 64:     # a few: one look at each (the same comparisons; NaN fails them)
            out = [i for i, (x, y) in enumerate(xy.tolist())
                   if not (x >= x0 and y >= y0 and x <= x1 and y <= y1)]
            if out:
                self.remove_slots(k[out].tolist())
            return
        inside = ((xy >= (x0, y0)) & (xy <= (x1, y1))).all(axis=1)          # NaN: False
        if not inside.all():
            self.remove_slots(k[~inside].tolist())
