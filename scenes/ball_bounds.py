"""The comparisons falling_balls' look makes in place of the flags' product (ball_checks.py:
five flags a ball, x and y in the world's box and its centre on or below the arm's line): with
the L static along x each flag is a comparison of x or y with a bound, so one comparison of the
rows with bounds (bounds_for) says exactly whether the flags are the kept ones (compared_of:
the comparisons' bytes a look expects, made out of the flags), and when they are not, the
flags are made out of the comparisons' bytes (flags_of_compared). Used by ball_look.look and by
BallChecks._usual_check (compared_flags); tests/test_falling_balls.py checks both ways against
the product over edge cases and random rows."""

from __future__ import annotations

import math

import numpy as np

from scenes.ball_tables import sizes_full

_NOT = bytes.maketrans(b"\0\1", b"\1\0")
_HEADS: dict[int, bytes] = {}       # (compared_of's first two thirds for inside rows, by size)


def compared_of(b: bytes, inside: bool = False) -> bytes:
    """The bytes of look's comparisons (bounds_for) of finite rows whose flags' bytes are b (5
    a row): for each row (x <= w + 2r, y <= h + 2r, and four 1s: finite), then (x < -2r, y <
    -h, four 0s), then (0, y < -c, four 0s); flag 1 is the first, flag 0 not the second, and so
    on. Bytes moves, no NumPy call (~1.5 us): with it a look armed after a ball came or went,
    or after flags changed, needs no product. (Rows not finite: their comparisons differ from
    these, so look goes on to the product, which finds them.) inside: the caller knows every
    box flag of b is true (a look armed: its key says so); then the first two thirds are all 1s
    and all 0s (kept by size), and only the line's bytes are moved (alone, 37 rows: 1.8 -> 0.7
    us, 0.46 with the thirds kept; in look's 344 calls of the bench's long run, 2,400 steps of
    falling_balls: 263.8k -> 261.9k instructions a step, and 258.9k -> 258.5k with the thirds
    kept, callgrind)."""
    n = len(b) // 5
    if inside:
        k = 6 * n
        line = bytearray(k)
        line[1::6] = b[4::5].translate(_NOT)
        return _head(k) + line
    upper, lower, line = bytearray(b"\1" * (6 * n)), bytearray(6 * n), bytearray(6 * n)
    upper[0::6], upper[1::6] = b[1::5], b[3::5]
    lower[0::6], lower[1::6] = b[0::5].translate(_NOT), b[2::5].translate(_NOT)
    line[1::6] = b[4::5].translate(_NOT)
    return bytes(upper + lower + line)


def flags_of_compared(sig: bytes, rows: np.ndarray) -> bytes | None:
    """The flags' bytes (5 a row) the product would give the n rows (n, 6) whose comparisons
    with bounds_for's bounds have the bytes sig, made out of sig (compared_of the other way
    round: bytes moves, no NumPy call), or None if a row may hold a number that is not finite
    (then the product: NaN * 0 makes such a row's flags). Why not the product: it is a BLAS
    call, and after OpenBLAS's AVX-512 kernel the engine's next steps run slower (look made
    one whenever the flags changed, ~290 times in the bench's 2,400 steps of falling_balls:
    with OPENBLAS_CORETYPE=Prescott, whose kernels use no AVX, the lab's own cost was ~1.2 us
    a step less; with the flags made here, and in _usual_check the same way, Prescott's kernels
    gain nothing any more (10.3-10.7 us a step either way). The bench's long run's lab/bare,
    medians of runs taking turns with the product in one process: 1.594 -> 1.562, 1.585 ->
    1.543 and 1.607 -> 1.592, load 0.1-0.4, 2026-11-27). A row's angle, vx, vy and w are
    finite when each is at most the largest float (the first comparisons) and none is -inf
    (the second); its x and y are compared with the box's ends, so they are read (as Python
    floats) only for a row outside the box, where a NaN or an inf would be too (a ball that
    left: one every ~15 steps)."""
    n = len(sig) // 18
    k = 6 * n
    if sig.startswith(_head(k)):    # every row finite and in the box: every box flag true,
        flags = bytearray(b"\1" * (5 * n))         # only the line's to read (a ball crossed
        flags[4::5] = sig[2 * k + 1::6].translate(_NOT)     # it: 2.3 -> 0.7 us alone, 37
        return bytes(flags)                         # rows; long run 258.4k -> 256.8k a step)
    x_in, y_in, x_left, y_above = sig[0:k:6], sig[1:k:6], sig[k:2 * k:6], sig[k + 1:2 * k:6]
    outside = (x_in.count(0) + y_in.count(0), x_left.count(1) + y_above.count(1))
    # (the other columns: every first comparison true, every second false; counted, not
    # sliced: 2.5 -> 2.3 us alone, 37 rows; long run 259.6k -> 259.3k instructions a step)
    if sig.count(0, 0, k) != outside[0] or sig.count(1, k, 2 * k) != outside[1]:
        return None
    if outside != (0, 0):   # (each row outside the box, by each flag it fails: finite? 259.2k
        # -> 258.9k instructions a step in the long run against a set of the rows first)
        for b, v in ((x_in, 0), (y_in, 0), (x_left, 1), (y_above, 1)):
            r = b.find(v)
            while r >= 0:
                x, y = rows[r, :2].tolist()
                if not (math.isfinite(x) and math.isfinite(y)):
                    return None
                r = b.find(v, r + 1)
    flags = bytearray(5 * n)
    flags[0::5], flags[1::5] = x_left.translate(_NOT), x_in
    flags[2::5], flags[3::5] = y_above.translate(_NOT), y_in
    flags[4::5] = sig[2 * k + 1::6].translate(_NOT)       # (not y < -c: on or below the line)
    return bytes(flags)


def _head(k: int) -> bytes:
    """The comparisons' first two thirds (k bytes each) of rows finite and in the box: k 1s,
    then k 0s (compared_of, flags_of_compared); kept by size, up to 64."""
    head = _HEADS.get(k)
    if head is None:
        if len(_HEADS) >= 64:
            _HEADS.clear()
        head = _HEADS[k] = b"\1" * k + bytes(k)
    return head


def compared_flags(scene, rows: np.ndarray) -> bytes | None:
    """flags_of_compared for these rows, compared as look compares them, with the L at the
    pose its flags' matrix was last made for (BallChecks._flag_matrix), if look's bounds are
    made for it (the L along x: bounds_for); else None (then the product)."""
    made = bounds_for(scene, len(rows))
    if made is None:
        return None
    bounds, inside = made
    return flags_of_compared(np.less_equal(rows, bounds, out=inside).tobytes(), rows)


_BIG = float(np.finfo(np.float64).max)


def bounds_for(scene, n: int) -> tuple | None:
    """(bounds (3, n, 6), a bool array for the comparisons) with which look finds, without the
    product, whether n awake rows' flags are the kept ones: `rows <= bounds` (rows broadcast)
    gives, for each row, (x, y) at most the box's right and bottom ends and (angle, vx, vy, w)
    at most the largest float; x and y below the box's left and top ends; y above the arm's
    line. For rows that are finite and inside the box (the kept flags say so: look is armed
    only then) these say exactly what the flags say: x <= w + 2r is flag 1; -x <= 2r (flag 0)
    is not x < -2r, which is x <= the float before -2r; the same for y; the arm's line with the
    L at angle 0 (its column in the flags' matrix (0, -1)) is -y <= c, not y < -c. A NaN fails
    all of them, +inf one of the first, and -inf passes one of the second (a kept row fails
    each of those): either way the row's bytes are not a kept row's, nor are its flags (NaN
    times 0 is NaN). So when the comparisons' bytes are those of a look whose flags were the
    kept ones, so are the flags.
    None if the arm's line is not along x (a static L at another angle: the product then)."""
    now = scene._flag_now
    key = (n, now[0])               # (the matrix and limits are made for a pose: _flag_matrix)
    sizes = scene._bound_sizes
    made = sizes.get(key, False)
    if made is False:
        if sizes_full(sizes, n):
            sizes.clear()
        M, limits = now[1], now[2]
        if not (M[0, 4] == 0.0 and M[1, 4] == -1.0):      # (M's rows 2-5 are 0)
            sizes[key] = None
            return None
        c = limits[4].item()
        below = -math.inf
        bounds = np.empty((3, n, 6))
        bounds[0], bounds[1] = _box_rows(limits)
        bounds[2] = (below, math.nextafter(-c, below), below, below, below, below)
        made = sizes[key] = (bounds, np.empty((3, n, 6), dtype=bool))
    return made


def _box_rows(limits: np.ndarray) -> tuple[tuple, tuple]:
    """bounds_for's first two rows: (x, y) at most the box's right and bottom ends and the
    rest at most the largest float; (x, y) below the box's left and top ends (the float before
    -2r: x <= it is x < -2r, not flag 0) and the rest at -inf."""
    lx, ux, ly, uy = limits[:4].tolist()
    below = -math.inf
    return ((ux, uy, _BIG, _BIG, _BIG, _BIG),
            (math.nextafter(-lx, below), math.nextafter(-ly, below), below, below, below, below))
