"""The usual mistakes of one implicit Euler step, for the hints of
app/exercises/implicit_spring/grader.py (the parent computes them on the check's inputs): the
springs' f0, K and D as dense matrices (the starter's formulas, and the mistakes' variants), the
step each named mistake takes, their hints, and the one a student's (x', v') matches."""

from __future__ import annotations

import numpy as np


def _springs(x, v, a, b, ks, kd, rest, transverse="clamped"):
    """f0 and the dense K, D of the springs (the starter's formulas: the transverse part clamped
    at 0 for a squashed spring; the other values of `transverse` make the mistakes' K)."""
    n = len(x)
    f = np.zeros((n, 2))
    K, D = np.zeros((2 * n, 2 * n)), np.zeros((2 * n, 2 * n))
    if not len(a):
        return f, K, D
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1)
    u = l / np.maximum(length, 1e-12)[:, None]
    fa = -(ks * (length - rest) + kd * np.sum((v[a] - v[b]) * u, axis=1))[:, None] * u
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    uu = u[:, :, None] * u[:, None, :]
    t = 1.0 - rest / np.maximum(length, 1e-12)
    t = {"clamped": np.maximum(t, 0.0), "K_ab = +K_aa": np.maximum(t, 0.0), "unclamped": t,
         "inverted": np.maximum(1.0 - length / rest, 0.0)}.get(transverse, np.zeros(len(a)))
    blocks = {"K": -ks * (uu + t[:, None, None] * (np.eye(2) - uu)), "D": -kd * uu}
    off = 1 if transverse == "K_ab = +K_aa" else -1
    for M, blk in ((K, blocks["K"]), (D, blocks["D"])):
        for p, q, s in ((a, a, 1), (b, b, 1), (a, b, off), (b, a, off)):
            rows = (2 * p[:, None] + np.arange(2))[:, :, None]
            cols = (2 * q[:, None] + np.arange(2))[:, None, :]
            np.add.at(M, (rows, cols), s * blk)
    return f, K, D


def mistaken_step(kind: str, x, v, w, a, b, ks, kd, rest, g, h):
    """(x', v') of one named mistake."""
    n = len(x)
    w = np.asarray(w, dtype=float)
    if kind == "pinned not held":
        w = np.where(w > 0, w, 1.0)
    f, K, D = _springs(x, v, a, b, ks, kd, rest, transverse={
        "no transverse part": "none", "transverse part not clamped": "unclamped",
        "transverse 1 - |l|/rest": "inverted", "K_ab = +K_aa": "K_ab = +K_aa"}.get(kind,
                                                                                "clamped"))
    if kind == "gravity's x dropped":
        g = np.array([0.0, g[1]])
    grav = np.where(w[:, None] > 0, g, 0.0) * (kind != "no gravity")
    acc = w[:, None] * f + grav
    if kind == "explicit Euler":
        return x + h * v, v + h * acc
    if kind == "symplectic Euler":
        return x + h * (v + h * acc), v + h * acc
    W = np.diag(np.tile(w, 2) if kind == "W tiled" else np.repeat(w, 2))
    k2 = h if kind == "h K for h^2 K" else h * h
    sign = -1.0 if kind == "K's sign flipped" else 1.0
    damp = 0.0 if kind == "no damping in A" else -h if kind == "D's sign flipped" else h
    if kind == "W on the right":
        A = np.eye(2 * n) - damp * D @ W - sign * k2 * K @ W
    else:
        A = np.eye(2 * n) - damp * W @ D - sign * k2 * W @ K
    kv = {"no h K v in rhs": 0.0, "h K v with a minus": -h}.get(kind, h)
    rhs = (np.eye(2 * n) if kind == "no W in rhs" else W) @ (f.ravel() + kv * K @ v.ravel())
    rhs = h * rhs + h * grav.ravel()
    dv = np.linalg.solve(A, rhs).reshape(n, 2)
    v_new = v + dv
    x_new = x + h * {"x' from the old v": v, "x' from dv": dv}.get(kind, v_new)
    return x_new, (dv if kind == "dv returned as v'" else v_new)


MISTAKES = {
    "x' from the old v": "x' uses the old velocity: backward Euler moves with the NEW one, "
                         "x' = x + h v'",
    "explicit Euler": "that is explicit (forward) Euler: forces at the START of the step, "
                      "which blows up past h = 2/omega",
    "symplectic Euler": "that is symplectic Euler (v' = v + h f(x)/m, x' = x + h v'): explicit, "
                        "stable only below h = 2/omega",
    "no h K v in rhs": "rhs is missing h K v: b = h W (f0 + h K v) (the position change h v "
                       "already pulls on the springs during the step)",
    "h K for h^2 K": "A has h K where it needs h^2 K: A = I - h W D - h^2 W K (dx = h (v + dv) "
                     "brings a second h)",
    "no transverse part": "K is missing its transverse part: K_aa = -ks [u u^T + max(1 - "
                          "rest/|l|, 0) (I - u u^T)]; without it a stretched spring does not "
                          "resist turning",
    "transverse part not clamped": "the squashed spring's transverse part is not clamped: "
                                   "max(1 - rest/|l|, 0), as the lab does (for |l| < rest the "
                                   "exact term pushes sideways and A can lose its positive "
                                   "definiteness, which conjugate gradients need)",
    "K's sign flipped": "K has the wrong sign: K = df/dx is negative along a spring (-ks u u^T): "
                        "A = I - h W D - h^2 W K has + h^2 ks/m on its diagonal",
    "no damping in A": "A is missing the damping: A = I - h W D - h^2 W K with D = df/dv "
                       "(D_aa = -kd u u^T)",
    "no gravity": "gravity is missing: it adds h g to dv of every free particle",
    "gravity's x dropped": "only gravity's y component is used: g is a vector (gx, gy) that may "
                           "point any way; add h g, both components, for each free particle",
    "pinned not held": "the pinned particle moved: w = 0 (mass infinite) makes its rows of W, "
                       "and so its dv, zero",
    "K_ab = +K_aa": "the off-diagonal blocks have the wrong sign: K_ab = K_ba = -K_aa (the "
                    "force on a pulls against b's displacement)",
    "W tiled": "W's diagonal is in the wrong order: np.repeat(w, 2) = (w1, w1, w2, w2, ...), "
               "one pair per particle; np.tile(w, 2) gives (w1, w2, ..., w1, w2, ...)",
    "x' from dv": "x' moves by h dv: it moves by h v' = h (v + dv), the new velocity",
    "dv returned as v'": "the second value is dv, the change: return v' = v + dv",
    "D's sign flipped": "D has the wrong sign: D = df/dv = -kd u u^T (damping opposes the "
                        "motion): A = I - h W D - h^2 W K has + h kd/m on its diagonal",
    "h K v with a minus": "rhs has - h K v: b = h W (f0 + h K v), a plus",
    "no W in rhs": "rhs is missing W: b = h W (f0 + h K v) (+ h g for each free particle), the "
                   "inverse masses on the right too (and a pinned particle's rows are 0)",
    "W on the right": "W is on the wrong side: A = I - h W D - h^2 W K (W times D and K: the "
                      "rows of a particle are divided by its mass, not the columns)",
    "transverse 1 - |l|/rest": "the transverse factor is upside down: max(1 - rest/|l|, 0), "
                               "not 1 - |l|/rest",
}


def name_mistake(xv: tuple[np.ndarray, np.ndarray], inputs: tuple) -> str:
    """The hint of the usual mistake these (x', v') match, or ''."""
    def same(p: tuple, q: tuple) -> bool:
        scale = max(float(np.abs(q[1] - inputs[1]).max()), 1e-300)
        return bool(float(np.abs(p[1] - q[1]).max()) <= 1e-7 * scale and
                    float(np.abs(p[0] - q[0]).max()) <= 1e-7 * max(float(np.abs(q[0]).max()),
                                                                   1.0))
    right = mistaken_step("", *inputs)
    if same(xv, right):
        return ""
    found = []
    for kind, hint in MISTAKES.items():
        try:
            with np.errstate(all="ignore"):
                wrong = mistaken_step(kind, *inputs)
        except np.linalg.LinAlgError:
            continue
        if not same(wrong, right) and same(xv, wrong):     # told apart on these inputs
            found.append(hint)
    if len(found) > 1:       # several mistakes give the same numbers on a small system
        return ("this matches more than one usual mistake here (the five-particle checks 'A and "
                "rhs' and 'the step' tell them apart): " + "; or ".join(found[:3]))
    return found[0] if found else ""
