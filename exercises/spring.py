"""Exercise `spring`: damped Hooke springs, an n-ary force (lecture: "A Newtonian Particle",
damped springs between pairs of particles).

For a spring between particles a and b, with l = x_a - x_b:

    f_a = -[ ks (|l| - rest) + kd (v_a - v_b) . l / |l| ] l / |l|          f_b = -f_a

The first term is Hooke's law (proportional to how far the length is from the rest length);
the second damps the relative speed ALONG the spring only. Both act along the unit vector
l / |l|. A particle in several springs feels the sum of them all.

Write `spring_forces`: x, v have shape (n, 2); a, b are integer arrays (m,) of the springs' ends;
ks, kd are numbers; rest is a float array (m,). Return the total spring force on every particle,
shape (n, 2), in a new array: do not change x or v.

Check it:   python -m app exercise check spring
Watch it:   python -m app --scene exercise:spring        (a rope of springs, the lab's as a ghost)

What the grader measures: your forces against the lab's (app/physics/forces.py, Springs) on
random systems, the Hooke part and the damping part separately; Newton's third law (all the
forces add up to zero); a damped spring loses energy; x and v are not changed.
Then random springs (seeded: the seed is printed, --seed N repeats it): any ks, kd, rests,
particles in several springs or in none, compared with the lab's forces within its rounding.

Hints:
  * Row-wise dot products: np.sum(p * q, axis=1, keepdims=True).
  * f[a] += fa does NOT add twice when a particle appears twice in a: use np.add.at(f, a, fa)
    (or loop over the springs).
"""

import numpy as np


def spring_forces(x: np.ndarray, v: np.ndarray, a: np.ndarray, b: np.ndarray, ks: float,
                  kd: float, rest: np.ndarray) -> np.ndarray:
    """The sum of all springs' forces on each particle, shape (n, 2)."""
    raise NotImplementedError("write me: f_a = -[ks (|l| - rest) + kd (v_a - v_b) . u] u, "
                              "u = l / |l|, f_b = -f_a, summed per particle")
