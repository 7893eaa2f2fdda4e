"""falling_balls' look at its balls after a step (FallingBallsScene.step), its usual case written
out: the L static, the same bodies awake as after the last look, every ball's five flags
(ball_checks.py) as they were; look_moving does the same for pivoting_l's moving L. What they
compute is what BallChecks.check_balls and _usual_check compute then, on the same arrays: the
read, the ids' bytes against the kept key, one product and one comparison (or, with the L along
x, comparisons alone: below), the flags' bytes against the last ones. They leave out the
checks those make on every step to find which case this is (who is awake and where the L is, the
kept arrays' size and pose: ~10k instructions a step, against the usual look's ~19k besides the
read; callgrind, 37 balls): those are made once, when the usual case starts (`arm`), and kept in
scene._quick, which is good while scene._awake and scene._fast are the very objects it holds
(anything that changes who is awake, a ball added or removed, a restore, a look the general
way, makes new ones; a look whose flags changed, no ball gone, puts its new scene._fast in
it). With the L static at angle 0 (falling_balls), look makes no product: one
comparison of the rows with bounds (ball_bounds.py) says whether the flags stayed, exactly (the
flags are comparisons of x and y then), and when they did not, the flags are made out of its
bytes (flags_of_compared; the product only for a row not finite). Not for its cost alone (about one
product's): right after OpenBLAS's product (its FMA kernels) pymunk's next step took ~1.5 us
longer (falling_balls' space.step, 37 balls, medians of 20 rounds: 18.6-18.7 us alone, 20.3-20.6
with a product of (37, 6) by (6, 5) between steps, 18.5-19.1 with the comparison; load 1.1),
which instructions do not show. Flags that changed go on to _usual_check's end (_flags_seen,
with the flags made here); anything else to check_balls, which finds the read in scene._rows.
look_moving does not make the product either while the flags stay and the L is in the box: Line
compares the rows with the box's bounds and each centre's height over the arm's line, as one
complex product (the L's line moves, so it is no bound). tests/test_falling_balls.py compares
them with check_balls step by step, and Line with the flags over random poses and rows;
tests/test_pymunk_checks.py the counts and the state with the exact tests, ball by ball.
"""

from __future__ import annotations

import math

import numpy as np

from scenes.ball_bounds import _box_rows, bounds_for, compared_of, flags_of_compared
from scenes.ball_checks import BallChecks
from scenes.ball_tables import _NAN_FAILS, rows_finite, sizes_full


class Armed:
    """What a look's usual case was armed with (arm, arm_moving): good while `awake` and `fast`
    are the scene's very objects (a new look the general way makes new ones; look puts a new
    `fast` in, and the comparisons' bytes with it, when the flags changed and nothing else:
    not a new Armed, as arm would make: falling_balls' long run in the bench, 2,400 steps,
    261.8k -> 260.7k instructions a step, callgrind)."""

    __slots__ = ("awake", "fast", "kept", "key_len", "key", "pose", "kept_pose", "bodies",
                 "flag_at", "bounds", "inside", "sig", "line")

    def __init__(self, awake, fast, kept, key: bytes, pose=None, kept_pose=None,
                 bodies: int = 0, flag_at: int = 0, bounds: tuple | None = None):
        self.awake = awake          # scene._awake: who is awake (ball_checks)
        self.fast = fast            # scene._fast: (the L's pose, the flags' bytes, their key)
        self.kept = kept            # scene._flag_rows: the flags' kept arrays (_flag_rows_at)
        self.key_len = len(key)     # the key: the awake ids' bytes (and the first static body's)
        self.key = key
        self.pose = pose            # look: the L's static pose, and the pose the kept arrays
        self.kept_pose = kept_pose  # were made for (_flag_matrix puts another in for another)
        self.bodies = bodies        # look_moving: the bodies awake or static,
        self.flag_at = flag_at      # and 5 x the L's row: where its flags are in the bytes
        # look: the bounds (3, n, 6) the rows are compared with instead of the product
        # (bounds_for), the comparisons' array, and their bytes for the flags kept (None: not
        # yet made: the look makes them out of the flags, compared_of)
        self.bounds, self.inside = bounds or (None, None)
        self.sig = None
        self.line = None            # look_moving: its Line (line_for), or None: the product


def _kept(scene, reader, awake, now: np.ndarray, finite: bool) -> None:
    """What a look whose flags are the last ones leaves (_flags_seen's, when they match): the
    rows kept for flush_xy without a copy, and the read found finite if `finite`."""
    scene._prev = (awake, now)
    reader.keep = (reader.cur, scene._own_prev)
    if finite:
        scene.finite_read = reader.reads


def look(scene, L0: tuple[float, float, float]) -> tuple[float, float, float]:
    """scene.check_balls(L0) after a step: the L's pose after it (L0: before it)."""
    q = scene._quick
    if q is not None and q.awake is scene._awake and q.fast is scene._fast and L0 is q.pose \
            and q.kept[3] is q.kept_pose:
        reader = scene._state_reader
        rows = scene._rows = reader.read(scene.space)
        ids, data = rows
        if ids.tobytes()[:q.key_len] == q.key:     # the same bodies awake, in the same order
            views = scene._views.get(id(data))     # (the read's awake rows: ball_checks)
            if views is None or views[0] is not q.awake:
                views = scene._awake_views(data, q.awake)
            now = views[1]
            bounds = q.bounds
            if bounds is not None:                 # (the flags' comparisons, no product)
                sig = np.less_equal(now, bounds, out=q.inside).tobytes()
                kept_sig = q.sig
                if kept_sig is None:               # (armed since the last look: every box
                    kept_sig = q.sig = compared_of(q.fast[1], inside=True)    # flag true)
                if sig == kept_sig:                # the same flags as after the last look
                    scene._prev = views[5]                      # (_kept's, written out)
                    reader.keep = scene._keeps[reader.cur]
                    if _NAN_FAILS:
                        scene.finite_read = reader.reads
                    return L0
                # the flags out of the comparisons: no product (flags_of_compared)
                b = flags_of_compared(sig, now)
            else:
                b = None
            if b is None:
                kept = q.kept
                b = np.less_equal(now.dot(kept[5], out=kept[1]), kept[2]).tobytes()
            fast = q.fast
            if b == fast[2]:                       # the same flags as after the last look
                _kept(scene, reader, q.awake, now, _NAN_FAILS)
                scene._fast = q.fast = (L0, b, b)
                if bounds is not None:             # (the comparisons of rows with these flags)
                    q.sig = sig
                return L0
            L1 = scene._flags_seen(now, L0, L0, q.awake, fast, b)
            if scene._quick is not q:              # (a ball went: remove_balls armed again)
                return L1
            fast = scene._fast
            if fast[2] is None:                    # (a ball outside the box, not removed)
                scene._quick = None
                return L1
            q.fast = fast                          # (the same bodies awake, the same kept
            if bounds is not None:                 # arrays and pose: arm's Armed but for these
                q.sig = sig if fast[1] is b else None          # flags)
            return L1
    L1 = scene.check_balls(L0)
    scene._quick = arm(scene, L1)
    return L1


def arm(scene, L1: tuple[float, float, float]) -> Armed | None:
    """scene._quick after a look that left the L at L1 (Armed), or None if look's usual case
    does not hold (a moving L, a ball outside the box, no ball awake, the flags made for
    another pose, a subclass's own check_balls)."""
    awake, fast, kept, cls = scene._awake, scene._fast, scene._flag_rows, type(scene)
    if cls.check_balls is not BallChecks.check_balls \
            or cls._usual_check is not BallChecks._usual_check:    # (a subclass: its way)
        return None
    if awake is None or fast is None or fast[2] is None or awake.L_row is not None \
            or not awake.balls or L1 != scene._L_static_pose or fast[0] != L1 \
            or kept is None or kept[0] != len(awake.ids) or kept[3] != L1:
        return None
    return Armed(awake, fast, kept, awake.key, pose=L1, kept_pose=kept[3],
                 bounds=bounds_for(scene, kept[0]))


def rearm(scene) -> None:
    """Arm the usual look again after a ball came or went. scene._awake and scene._fast were
    made then without a read (awake_after_add, awake_after_removal: who is awake, in
    Chipmunk's order, and their flags); the next look takes its usual case if its read is what
    they say (the same test as check_balls': the ids' bytes against the key), else it goes the
    general way, as before. Without this, the step after every ball added or removed went the
    general way (check_balls, then arm: ~20 us). The kept arrays are made for the new number
    of rows here (_flag_rows_at), as _usual_check would make them in the next look."""
    awake, fast = scene._awake, scene._fast
    scene._quick = scene._quick_moving = None
    reader, kept = scene._state_reader, scene.finite_kept
    scene.finite_kept = -1
    if awake is None or fast is None or fast[2] is None or not awake.balls:
        return                                  # (nothing to arm: the general way next step)
    # Every body finite still? The flags are those of the last read (no step since it: its rows
    # still kept, or a change before this one found the same), every awake ball's box flags
    # hold (a NaN anywhere in a row fails them: _NAN_FAILS), and so do the L's if it is awake;
    # a new ball is at rest in the box. Then the runner's is_finite need not read the bodies
    # again after the change (PymunkScene.is_finite: a read and a check, ~5 us)
    if (scene._rows is not None or kept == reader.reads) and rows_finite(fast[1], awake.L_row):
        scene.finite_kept = reader.reads
    pose = fast[0]
    scene._flag_rows_at(len(awake.ids), pose)
    if awake.L_row is None:
        scene._quick = arm(scene, pose)
    else:
        scene._quick_moving = arm_moving(scene, pose)


def look_moving(scene, L0: tuple[float, float, float]) -> tuple[float, float, float]:
    """look for an L that moves (pivoting_l's written-out step): the same with the L's row
    among the awake rows (its pose from the read, the flags' line written again for it, the
    key without its row) and every body awake or static (none asleep: a moving L may pass a
    sleeping ball, and check_balls then looks at every ball)."""
    q = scene._quick_moving
    if q is not None and q.awake is scene._awake and q.fast is scene._fast \
            and q.fast[0] is L0 and q.kept is scene._flag_rows:
        reader = scene._state_reader
        rows = scene._rows = reader.read(scene.space)
        ids, data = rows
        if len(ids) == q.bodies and ids.tobytes()[:q.key_len] == q.key:
            views = scene._views.get(id(data))     # (the read's awake rows and the L's)
            if views is None or views[0] is not q.awake:
                views = scene._awake_views(data, q.awake)
            now = views[1]
            L1 = tuple(views[2].tolist())
            line = q.line
            if line is not None and line.same(now, L1, views[4]):
                scene._prev = (q.awake, now)                    # (_kept's, written out; the
                reader.keep = (reader.cur, scene._own_prev)     # bounds: every row finite)
                scene.finite_read = reader.reads
                fast = q.fast
                scene._fast = q.fast = (L1, fast[1], fast[2])
                return L1
            kept = q.kept
            if kept[3] != L1:
                scene._flag_matrix(L1)             # (the line's column and limit for L1)
            flags = np.less_equal(now.dot(kept[5], out=kept[1]), kept[2])
            b = flags.tobytes()
            fast, r = q.fast, q.flag_at
            key = b[:r] + b[r + 5:]
            if key == fast[2]:                     # (_flags_seen's, when the flags match)
                _kept(scene, reader, q.awake, now, rows_finite(b, q.awake.L_row))
                scene._fast = q.fast = (L1, b, key)
                if (b[r:r + 4] == b"\1\1\1\1") is (line is None):    # (the L left the box
                    q.line = line_for(scene, kept[0], q.awake.L_row, b)   # or came back: Line
                return L1                          # keeps the bytes, so only with them true)
            L1 = scene._flags_seen(now, L0, L1, q.awake, fast, b)
            scene._quick_moving = arm_moving(scene, L1)
            return L1
    L1 = scene.check_balls(L0)
    scene._quick_moving = arm_moving(scene, L1)
    return L1


def arm_moving(scene, L1: tuple[float, float, float]) -> Armed | None:
    """scene._quick_moving after a look that left the L at L1 (Armed, with the number of
    bodies awake or static and where the L's flags are), or None (as arm, and an L that is
    not awake)."""
    awake, fast, kept = scene._awake, scene._fast, scene._flag_rows
    if type(scene).check_balls is not BallChecks.check_balls or type(scene)._usual_check \
            is not BallChecks._usual_check:
        return None
    if awake is None or fast is None or fast[2] is None or awake.L_row is None \
            or not awake.balls or fast[0] is not L1 or kept is None \
            or kept[0] != len(awake.ids):
        return None
    armed = Armed(awake, fast, kept, awake.key,
                  bodies=len(awake.ids) + len(scene._static_ids), flag_at=5 * awake.L_row)
    armed.line = line_for(scene, kept[0], awake.L_row, fast[1])
    return armed


class Line:
    """look_moving's test, without the product, of whether n awake rows' flags are the kept
    ones with the L at a new pose: the rows against the box's bounds (_box_rows: every row
    inside the box and finite, as the kept flags of a look armed say), and each centre's
    height over the arm's line, the product's last column, X sin a - Y cos a (the L at (x, y,
    a); the flag: at most x sin a - y cos a), as the real part of one complex product: the
    centre X + iY times sin a + i cos a. More instructions than the product (`bench pymunk
    --full`, pivoting_l: 1.294 -> 1.328 x the bare loop's), less time: after OpenBLAS's product
    (its FMA kernels; np.exp's AVX-512 loop too, not a multiply, a comparison or this complex
    product) the code that follows runs slower on the lab's Xeon, ~2 us in pymunk's next 17 us
    step (medians of 30 rounds, load 0.4). pivoting_l's lab step, this test against the
    product every step, in one process taking turns (40 rounds of 120 steps, load 1.1): 0.959
    and 0.972 x; with OPENBLAS_CORETYPE=Prescott (SSE kernels, no such slowdown) the product is
    the faster one (1.03-1.04 x). The L's own row has no line flag here (its centre is on its
    own arm's line: the flag flips with rounding): its byte is left out. A row whose
    comparisons differ (a flag changed, or the rounding of the two ways differs for a centre
    within ~4e-13 px of the line) goes on to the product, which says; the other way round (this
    rounding gives the kept flag, the product's would not) the flags stay: that near the line
    the flag is a coin flip of rounding either way, as the product's own is from pose to pose
    (and with OpenBLAS's kernels for another CPU: OPENBLAS_CORETYPE=Prescott's flags differ
    from the FMA kernels' there)."""

    __slots__ = ("bounds", "inside", "box", "L_row", "z", "height", "below", "head", "tail")

    def __init__(self, limits: np.ndarray, n: int, L_row: int):
        self.bounds = np.empty((2, n, 6))
        self.bounds[0], self.bounds[1] = _box_rows(limits)
        self.inside = np.empty((2, n, 6), dtype=bool)
        self.box = b"\1" * (6 * n) + b"\0" * (6 * n)     # every row inside the box, finite
        self.L_row = L_row
        self.z, self.below = np.empty(n, complex), np.empty(n, bool)
        self.height = self.z.real           # (a view, made once)
        self.head = self.tail = b""         # the kept line flags' bytes before the L's row, after

    def same(self, now: np.ndarray, pose: tuple[float, float, float],
             centres: np.ndarray) -> bool:
        """Whether the rows `now` (n, 6) have the kept flags with the L at pose (its row of
        now); centres: now's centres x + iy as complex numbers, a view of now
        (ball_checks._awake_views keeps one a read)."""
        if np.less_equal(now, self.bounds, out=self.inside).tobytes() != self.box:
            return False
        x, y, a = pose        # (the L's row of now passed the box test: a finite angle)
        c, s = math.cos(a), math.sin(a)
        np.multiply(centres, complex(s, c), out=self.z)
        b = np.less_equal(self.height, x * s - y * c, out=self.below).tobytes()
        r = self.L_row
        return b[:r] == self.head and b[r + 1:] == self.tail


def line_for(scene, n: int, L_row: int, b: bytes) -> Line | None:
    """The Line for n awake rows with the L's at L_row, armed with the flags' bytes b (5 a
    row); kept by n (its arrays are the same whichever row is the L's: that row, and the bytes
    before and after it, are set here). None if the L's box flags do not hold (then the
    product)."""
    if b[5 * L_row:5 * L_row + 4] != b"\1\1\1\1":
        return None
    sizes = scene._bound_sizes
    key = ("line", n)
    line = sizes.get(key)
    if line is None:
        if sizes_full(sizes, n):
            sizes.clear()
        line = sizes[key] = Line(scene._flag_now[2], n, L_row)
    sig = b[4::5]
    line.L_row, line.head, line.tail = L_row, sig[:L_row], sig[L_row + 1:]
    return line
