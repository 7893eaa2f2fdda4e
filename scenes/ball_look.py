"""falling_balls' look at its balls after a step (FallingBallsScene.step), its usual case written
out: the L static, the same bodies awake as after the last look, every ball's five flags
(ball_checks.py) as they were. What it computes is what BallChecks.check_balls and _usual_check
compute then, with the same NumPy calls on the same arrays: the read, the ids' bytes against
the kept key, one product, one comparison, the flags' bytes against the last ones. It leaves
out the checks those make on every step to find which case this is (who is awake and where the
L is, the kept arrays' size and pose), about half of the lab's own work on a step of the
default scene (callgrind): they are made once, when the usual case starts (`arm`), and kept
in scene._quick, which is good while scene._awake and scene._fast are the very objects it was
made with (anything that changes who is awake, a ball added or removed, a restore, a look
the general way, makes new ones). Flags that changed go on to _usual_check's end
(_flags_seen, with the flags made here); anything else to check_balls, which finds the read in
scene._rows. tests/test_pymunk_checks.py compares the counts and the state with the exact
tests, ball by ball, and the seeded runs' metrics and state hashes are main's.
"""

from __future__ import annotations

import numpy as np

from scenes.ball_checks import _NAN_FAILS, BallChecks


def look(scene, L0: tuple[float, float, float]) -> tuple[float, float, float]:
    """scene.check_balls(L0) after a step: the L's pose after it (L0: before it)."""
    q = scene._quick
    if q is not None and q[0] is scene._awake and q[1] is scene._fast and L0 is q[6] \
            and q[2][3] is q[7]:
        reader = scene._state_reader
        rows = scene._rows = reader.read(scene.space)
        ids, data = rows
        if ids.tobytes()[:q[3]] == q[4]:           # the same bodies awake, in the same order
            now = q[5].get(id(data))
            if now is None:
                now = _rows_view(q, data)
            kept = q[2]
            flags = np.less_equal(now.dot(kept[5], out=kept[1]), kept[2])
            b = flags.tobytes()
            fast = q[1]
            if b == fast[2]:                       # the same flags as after the last look
                scene._prev = (q[0], now)          # (_usual_check's, when the flags match)
                reader.keep = (reader.cur, scene._own_prev)
                scene._fast = q[1] = (L0, b, b)
                if _NAN_FAILS:
                    scene.finite_read = reader.reads
                return L0
            L1 = scene._flags_seen(now, L0, L0, q[0], fast, flags, b)
            scene._quick = arm(scene, L1)
            return L1
    L1 = scene.check_balls(L0)
    scene._quick = arm(scene, L1)
    return L1


def arm(scene, L1: tuple[float, float, float]) -> list | None:
    """scene._quick after a look that left the L at L1: [awake, fast, the flags' kept arrays
    (_flag_rows_at), the key's length, the key (the awake ids' bytes and the first static
    body's), each read's awake rows by the rows' id, the L's pose, the pose the kept arrays
    were made for (the same object: _flag_matrix puts another in if another pose rewrote
    them)], or None if look's usual case does not hold (a moving L, a ball outside the box,
    no ball awake, the flags made for another pose, a subclass's own check_balls)."""
    awake, fast, kept = scene._awake, scene._fast, scene._flag_rows
    if type(scene).check_balls is not BallChecks.check_balls or type(scene)._usual_check \
            is not BallChecks._usual_check:       # (a subclass checks otherwise: its way)
        return None
    if awake is None or fast is None or fast[2] is None or awake.L_row is not None \
            or not awake.balls or L1 != scene._L_static_pose or fast[0] != L1 \
            or kept is None or kept[0] != len(awake.ids) or kept[3] != L1:
        return None
    q = scene._quick             # (the views of the reads: kept while the same are awake)
    views = q[5] if q is not None and q[0] is awake else {}
    return [awake, fast, kept, len(awake.key), awake.key, views, L1, kept[3]]


def _rows_view(q: list, data: np.ndarray) -> np.ndarray:
    """The awake rows of a read (data[:n]), kept by the rows' id (the reader's two buffers:
    two ids while the bodies stay; the views keep their rows, so an id is no new array's)."""
    views = q[5]
    if len(views) >= 2:
        views.clear()
    now = views[id(data)] = data[:q[2][0]]
    return now
