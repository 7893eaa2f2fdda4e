"""Exercise `verlet`: the velocity-less Verlet step (lecture: "Verlet integration").

The slide stores each particle's current position x and its previous position x_prev, and no
velocity at all:

    x_new = 2 x - x_prev + a h^2          then  x_prev = x   ("swap the array pointers")

because 2x - x_prev = x + (x - x_prev), and (x - x_prev) is the distance travelled in the last
step. "By lowering the value 2 to something like 1.99 a small amount of drag can also be
introduced": write the drag as the fraction of that distance lost per step,

    x_new = x + (1 - drag) (x - x_prev) + a h^2            (drag = 0.01: 2 -> 1.99)

that is (2 - drag) x - (1 - drag) x_prev + a h^2: the x_prev term changes too. Read literally,
the slide's "lower 2 to 1.99" (1.99 x - x_prev) is no drag at all: it adds -0.01 x / h^2 to the
acceleration, a spring pulling every particle towards the point x = 0.

Write `verlet_step`. Arrays have shape (n, 2): one row (x, y) per particle, y pointing down.

Check it:   python -m app exercise check verlet
Watch it:   python -m app --scene exercise:verlet        (yours filled, the lab's as orange rings)

What the grader measures: a free fall must follow the parabola exactly (Verlet's central
difference is exact for a constant acceleration); on a spring the error must fall 4x when h
halves (second order. The slide's "4th order accurate" is true of ONE step, whose error is
O(h^4); over a fixed time the 1/h steps add up to O(h^2)); with drag 0 a spring keeps its energy;
with drag 0.01 it loses 1% of its energy per step; x and a must not be changed.
Then the same on random systems (seeded: the seed is printed, --seed N repeats it): 1 to 40
particles, each with its own acceleration, any h and drag, compared with the lab's step within
its rounding.

Hints:
  * NumPy does the whole array at once: no loop over particles.
  * `x + ...` makes a new array; `x += ...` would change the caller's x, which is also the
    x_prev you return.
  * h squared, not h; and no 1/2 (it is already inside x - x_prev).
"""

import numpy as np


def verlet_step(x: np.ndarray, x_prev: np.ndarray, a: np.ndarray, h: float,
                drag: float) -> tuple[np.ndarray, np.ndarray]:
    """One Verlet step of h seconds: return (x_new, x), the new positions and the new previous
    positions. a: accelerations (n, 2) at x; drag: fraction of the last step's travel lost."""
    raise NotImplementedError("write me: x_new = x + (1 - drag) * (x - x_prev) + a * h * h")
