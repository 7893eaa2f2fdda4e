"""Exercise `solver_interface`: the particle system's derivative evaluation (lecture: "Solver
Interface" and "Derivation Evaluation Loop").

The solver sees the particles only as one flat state vector y = [x, v] (all positions, then all
velocities: x1, y1, x2, y2, ..., vx1, vy1, ...) and asks the particle system for dy/dt. The
slide's loop has three steps:

    1. clear forces        zero the force accumulator f (one row per particle)
    2. calculate forces    every force object adds its force into f
    3. gather              return [v, f / m]           (dx/dt = v, dv/dt = f / m)

Write `derivative(state, masses, forces)`: state is the flat vector (4 n numbers for n particles
in 2-D), masses has shape (n,), forces is a list of functions force(x, v, f) that ADD their force
into f (shape (n, 2)) in place. Return dy/dt, a flat vector like state.

Check it:   python -m app exercise check solver_interface
Watch it:   python -m app --scene exercise:solver_interface

What the grader measures: your derivative against the lab's particle system
(app/physics/particles.py) with gravity, drag and springs; dx/dt is exactly v; two calls on the
same state agree (the accumulator is cleared); doubling the masses halves the accelerations; the
state you were given is not changed.
Then random systems (seeded: the seed is printed, --seed N repeats it): 1 to 8 particles,
any masses, 0 to 4 forces of any kind, compared with the lab's derivative within its rounding.

Hints:
  * x = state[:2 * n].reshape(n, 2) is a view, not a copy: read from it, do not write into it.
  * np.concatenate([v.ravel(), (f / masses[:, None]).ravel()]).
"""

import numpy as np


def derivative(state: np.ndarray, masses: np.ndarray, forces: list) -> np.ndarray:
    """dy/dt = [v, f/m] at the phase-space point `state`, flat like it."""
    raise NotImplementedError("write me: clear f, call every force(x, v, f), return [v, f/m]")
