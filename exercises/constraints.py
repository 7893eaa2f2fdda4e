"""Exercise `constraints`: Jakobsen's rods relaxed by local iteration (lecture "Cloth
Simulation": "constrain particles by rods, not springs ... solve by local iteration").

A rod k joins particle a[k] to particle b[k] and wants their distance to be rest[k]. The slide's
satisfyConstraints() fixes one rod at a time, moving both ends along the rod:

    delta = x[b] - x[a]
    diff  = (|delta| - rest) / |delta|
    x[a] += delta * diff * w[a] / (w[a] + w[b])
    x[b] -= delta * diff * w[b] / (w[a] + w[b])

w is the inverse mass (1 / m): a particle with w = 0 is pinned and never moves; a rod whose two
ends are both pinned is skipped. Fixing one rod breaks its neighbours, so the whole sweep over all
rods is repeated `iterations` times, each sweep starting from the positions the last one left
("each constraint tries to satisfy itself, let the other constraints worry about themselves").

Write `satisfy_rods`. x has shape (n, 2); a, b are integer arrays (m,); rest, w are float arrays.

Check it:   python -m app exercise check constraints
Watch it:   python -m app --scene exercise:constraints   (your cloth left, the lab's right)

What the grader measures: pinned particles move by exactly 0 (a rod between two of them is
skipped); one rod alone is exactly satisfied after one sweep, squashed or stretched, and three rods
of different rest lengths each reach their own; the ends share the correction by inverse mass
(the centre of mass stays put); a hanging cloth stretches less with more iterations; two
particles at one point give no NaN.
Then random sets of rods (seeded: the seed is printed, --seed N repeats it): inverse masses,
pinned particles, zero-length rods, two ends at one point, 1 to 4 sweeps; your result must be
the slide's sweeps in some order of the rods (the same order each sweep), within rounding.

Hints:
  * A plain Python loop over the rods is fine here (it is what the slide does); the lab's
    version (app/physics/jakobsen.py) solves batches of rods that share no particle at once.
  * Guard the division: two particles at one point have |delta| = 0 (use max(|delta|, 1e-9)).
  * Work on a copy (x = x.copy()) or in place, but return the positions.
"""

import numpy as np


def satisfy_rods(x: np.ndarray, a: np.ndarray, b: np.ndarray, rest: np.ndarray, w: np.ndarray,
                 iterations: int) -> np.ndarray:
    """Relax every rod `iterations` times; return the new positions (n, 2)."""
    raise NotImplementedError("write me: for each sweep, for each rod: move x[a] and x[b] "
                              "along delta by their shares w / (w[a] + w[b])")
