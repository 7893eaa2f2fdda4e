"""Exercise `collisions`: a Verlet cloth meets a ball (lecture "Cloth Simulation": Jakobsen's
particles "pushed back out of obstacles", and Coulomb friction on what touches them).

After the Verlet step, some particles are found INSIDE the circle of centre c and radius r.
Jakobsen's answer is projection: move each one to the surface by the shortest way out, no
force, no stiffness:

    d = |x - c|                  a particle is inside where d < r (on the surface, d = r: not)
    n = (x - c) / d              the outward normal, the shortest way out
    x = x + (r - d) n            on the surface now: it was moved depth = r - d px

A particle exactly AT the centre (d = 0) has no shortest way out (0 / 0 is NaN): it leaves
through the top, n = (0, -1) (y points down). A pinned particle (w = 0) never moves, inside or
not.

Then friction, for the particles that touched the circle (depth > 0). Verlet has no velocity:
the travel of this step, v = x - x_prev, is the velocity times h. Coulomb's law lets the
contact remove at most mu times the normal push from the part of v along the surface (a
position-based step's "normal force" is its normal correction, depth):

    v_t = v - (v . n) n          the travel along the surface (n as above, from the new x)
    |v_t| <= mu * depth:   x = x - v_t                        static: it sticks
    otherwise:             x = x - mu * depth * v_t / |v_t|   kinetic: it slides, slower

Only x changes (moving x back along the surface is what slows the next Verlet step, which reads
its velocity from x - x_prev); the travel along the normal stays; friction never reverses the
sliding. Particles that did not touch (depth 0) are not touched by friction either.

Write `push_out` and `friction`. x, x_prev: float arrays (n, 2), one row (x, y) per particle;
w: inverse masses (n,), 0 = pinned; center: (cx, cy) as an array (2,); radius > 0; depth:
what push_out returned (n,); mu >= 0 (any: the scene's slider stops at 2). Both CHANGE x IN
PLACE (x[...] = ..., x += ...: the cloth's own array, which the caller goes on using); push_out
returns depth, friction nothing.

Check it:   python -m app exercise check collisions
Watch it:   python -m app --scene exercise:collisions   (your rope left, the lab's right; drag
            a ball with the mouse)

What the grader measures: particles inside end on the surface and report how far they moved;
particles outside, exactly on the surface and pinned ones do not move; a particle at the
centre leaves through the top; friction stops a slow slide (static, however shallow the
contact), slows a fast one by exactly mu * depth (kinetic) without reversing it or touching the
normal travel, and leaves particles that did not touch alone; x_prev, w, center and depth are
not changed. Then random circles and particles (seeded: the seed is printed, --seed N repeats
it): any centre and radius, 1 to 60
particles inside, on, outside and at the centre, pinned ones, any travel and any mu,
compared with the lab's answer (app/physics/circle_contact.py) within float64 rounding. The
depth you return is checked against how far the grader sees each particle move.

Hints:
  * NumPy does all particles at once: a boolean mask `inside` picks the rows (x[inside] += ...).
  * np.linalg.norm(x - center, axis=1) is d for every particle; (x - center) / d[:, None] is n.
  * The centre: where d == 0, set n to (0, -1) before you use it (np.where, or n[d == 0] = ...).
  * `x = x + ...` inside your function makes a new array and leaves the caller's x as it was.
"""

import numpy as np


def push_out(x: np.ndarray, w: np.ndarray, center: np.ndarray, radius: float) -> np.ndarray:
    """Move every particle inside the circle (and not pinned) to its surface, in place; return
    depth (n,): how far each particle was moved (0 for the others)."""
    raise NotImplementedError("write me: inside = (d < radius) & (w > 0); "
                              "x[inside] += (radius - d) n; return the depth")


def friction(x: np.ndarray, x_prev: np.ndarray, center: np.ndarray, depth: np.ndarray,
             mu: float) -> None:
    """Coulomb friction on the particles with depth > 0, in place on x: their travel along the
    surface, v_t, loses min(|v_t|, mu * depth)."""
    raise NotImplementedError("write me: v = x - x_prev; v_t = v - (v . n) n; "
                              "x -= v_t or mu * depth * v_t / |v_t|")
