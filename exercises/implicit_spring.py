"""Exercise `implicit_spring`: one backward (implicit) Euler step of a damped spring system,
Baraff & Witkin's linear system (lecture "Cloth Simulation": "Backwards Euler", "Large Steps in
Cloth Simulation", "Force derivatives", "Mass Modification").

Explicit Euler takes the forces at the START of a step: past h = 2/omega (omega = sqrt(ks/m) of
the stiffest spring, higher for a mesh) it blows up. Backward Euler takes them at the END:

    v' = v + h W f(x', v'),     x' = x + h v'          W = M^-1: the inverse masses

f(x', v') is unknown. Linearise it once around the start (one Newton step, as Baraff & Witkin
do), f(x + dx, v + dv) ~ f0 + K dx + D dv with K = df/dx, D = df/dv and dx = h (v + dv), and
group the dv terms: one linear system for dv,

    A dv = rhs,    A = I - h W D - h^2 W K,    rhs = h W (f0 + h K v)
    v' = v + dv,   x' = x + h v'

For n particles in 2-D, A is a 2n x 2n matrix and dv, rhs are vectors of 2n numbers in the order
of x.ravel(): (x1, y1, x2, y2, ...). W is the diagonal matrix of the inverse masses, each one
twice (w1, w1, w2, w2, ...). A pinned particle has w = 0 ("make its mass infinite: it won't
move"): its rows of W are zero, so its dv is 0.

The forces: gravity, an acceleration g for every free particle (W m g = g: it adds h g to rhs for
each particle with w > 0), and a damped spring for each pair (a[k], b[k]) (exercise `spring`,
written for you below). With l = x_a - x_b, u = l / |l|:

    f_a = -[ks (|l| - rest) + kd (v_a - v_b) . u] u,        f_b = -f_a

Their derivatives, one 2 x 2 block per pair of particles (I is the 2 x 2 identity, u u^T the
outer product np.outer(u, u)):

    K_aa = df_a/dx_a = -ks [ u u^T + max(1 - rest/|l|, 0) (I - u u^T) ]
    D_aa = df_a/dv_a = -kd u u^T
    K_bb = K_aa, K_ab = K_ba = -K_aa;   the same for D

Two simplifications, as the lab makes them (app/physics/forces.py, Springs.jacobian): the
damping force's x-derivative is dropped ("for symmetry's sake", as the slide and Baraff & Witkin
do), and the transverse part (1 - rest/|l|), negative for a squashed spring, is clamped at 0
(Choi & Ko): exactly it would push sideways, and A would no longer be positive definite. Each
spring adds its four blocks into K and D: block (i, j) is rows 2i, 2i+1 and columns 2j, 2j+1.

Write `linear_system` (return A and rhs) and `implicit_euler_step` (solve A dv = rhs with
np.linalg.solve, return x' and v'). x, v have shape (n, 2); w (n,); a, b integer arrays (m,);
ks, kd numbers; rest (m,); g the gravity vector (2,), y down; h the step, seconds. Do not change
x or v.

Check it:   python -m app exercise check implicit_spring
Watch it:   python -m app --scene exercise:implicit_spring   (yours filled, the lab's as orange
            rings; try --set hertz=10: h = 100 ms, 9x past the explicit limit, and the swing
            dies faster: backward Euler's artificial damping)

What the grader measures: a free fall is exact (v' = v + h g, x' = x + h v', the pinned particle
stays); one undamped spring at omega h = 10 keeps exactly 1/(1 + (omega h)^2) of its energy per
step (backward Euler's artificial damping); your A and rhs solve to the lab's step, and your step
agrees with it (1e-9) on a system of five particles (one spring squashed); a stiff chain at 14x
the explicit limit only loses energy; x and v are not changed.
Then random systems (seeded: the seed is printed, --seed N repeats it): 2 to 6 particles, any
springs, masses and pinned particles (at rest: a pinned particle won't move), gravity of any size
pointing any way, h from 1 ms to 0.5 s: your A and rhs and your step against the lab's linear
system, within its rounding.

Hints:
  * Build K and D with np.zeros((2 n, 2 n)) and a loop over the springs (a few particles: a loop
    is fine here; the lab's app/physics/forces.py never forms the matrix, see Springs.jacobian).
  * W = np.diag(np.repeat(w, 2)); I = np.eye(2 * n).
  * dx = h (v + dv) brings the second h: h^2 on K, and the h K v in rhs.
"""

import numpy as np


def spring_forces(x, v, a, b, ks, kd, rest):
    """Given (the `spring` exercise): the damped springs' total force on each particle, (n, 2)."""
    l = x[a] - x[b]
    length = np.linalg.norm(l, axis=1, keepdims=True)
    u = l / np.maximum(length, 1e-12)
    fa = -(ks * (length - rest[:, None]) + kd * np.sum((v[a] - v[b]) * u, axis=1,
                                                       keepdims=True)) * u
    f = np.zeros_like(x, dtype=float)
    np.add.at(f, a, fa)
    np.add.at(f, b, -fa)
    return f


def linear_system(x: np.ndarray, v: np.ndarray, w: np.ndarray, a: np.ndarray, b: np.ndarray,
                  ks: float, kd: float, rest: np.ndarray, g: np.ndarray,
                  h: float) -> tuple[np.ndarray, np.ndarray]:
    """Baraff & Witkin's A (2n x 2n) and rhs (2n,) for one backward Euler step of h."""
    raise NotImplementedError("write me: K, D from the springs' blocks, then "
                              "A = I - h W D - h^2 W K, rhs = h W (f0 + h K v) + h g (free ones)")


def implicit_euler_step(x: np.ndarray, v: np.ndarray, w: np.ndarray, a: np.ndarray,
                        b: np.ndarray, ks: float, kd: float, rest: np.ndarray, g: np.ndarray,
                        h: float) -> tuple[np.ndarray, np.ndarray]:
    """One backward Euler step: return (x_new, v_new), each (n, 2)."""
    raise NotImplementedError("write me: dv = np.linalg.solve(A, rhs); v' = v + dv, "
                              "x' = x + h v'")
