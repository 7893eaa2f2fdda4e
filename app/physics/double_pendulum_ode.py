"""The double pendulum from its equations of motion: the reference ("ghost") beside pymunk's.

Two point masses m1, m2 hang on massless rods of lengths l1, l2 from a fixed pivot. The state is
the two angles from the downward vertical and their rates, y = (theta1, theta2, omega1, omega2);
with y pointing down (the project's convention) the bobs are at

    p1 = pivot + l1 (sin theta1, cos theta1)        p2 = p1 + l2 (sin theta2, cos theta2)

Lagrange's equations give the angular accelerations (the textbook form, e.g. myPhysicsLab), with
d = theta1 - theta2 and D = 2 m1 + m2 - m2 cos(2 d):

    alpha1 = (-g (2 m1 + m2) sin theta1 - m2 g sin(theta1 - 2 theta2)
              - 2 sin d m2 (omega2^2 l2 + omega1^2 l1 cos d)) / (l1 D)
    alpha2 = 2 sin d (omega1^2 l1 (m1 + m2) + g (m1 + m2) cos theta1
                      + omega2^2 l2 m2 cos d) / (l2 D)

These are integrated with classical Runge-Kutta (RK4) at a step much smaller than anything the
eye can see, so for the lecture the result is "the exact solution". The motion is chaotic for high
releases: two runs that differ by a hair part ways after a few seconds, which is what the scene
shows by running the same pendulum in pymunk beside this one.

Why point masses match pymunk's bobs: pymunk's bobs are discs with a moment of inertia, but both
pin joints hold them at their centres of mass, so no joint force has a lever arm on a bob, the bobs
never start spinning and their rotation drops out of the energy. Point masses are the exact model.

The step is bounded: `advance(dt, n)` takes at least ceil(dt / MAX_STEP) RK4 steps (MAX_STEP =
1 ms), whatever n asks for, so a coarse physics step (hertz 1) does not make the reference coarse
too. RK4 is only conditionally stable: at h ~ 1/omega it blows up, and a reference that blows up
is no reference. If it still goes non-finite (extreme masses and g), `advance` keeps the last
finite state, returns False and never raises; the scene freezes the ghost and says so.

The step uses plain float arithmetic (the math module): one state of four numbers is far too small
for arrays to pay off: the same RK4 step on a 4-element NumPy array took ~65 us against ~20 us
here. `positions` returns a NumPy array for drawing and comparing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

State = tuple[float, float, float, float]    # theta1, theta2, omega1, omega2 (rad, rad/s)

MAX_STEP = 1e-3    # seconds: the longest RK4 step advance() takes (see the module docstring)


@dataclass
class DoublePendulumODE:
    """A double pendulum of point masses integrated with RK4 (lengths in px, g in px/s^2)."""

    l1: float
    l2: float
    m1: float
    m2: float
    g: float
    state: State = (0.0, 0.0, 0.0, 0.0)

    # ----- the equations of motion --------------------------------------------------------
    def derivative(self, y: State) -> State:
        """dy/dt = (omega1, omega2, alpha1, alpha2) from the equations in the module docstring."""
        t1, t2, w1, w2 = y
        l1, l2, m1, m2, g = self.l1, self.l2, self.m1, self.m2, self.g
        d = t1 - t2
        sin_d, cos_d = math.sin(d), math.cos(d)
        den = 2 * m1 + m2 - m2 * math.cos(2 * d)
        a1 = (-g * (2 * m1 + m2) * math.sin(t1) - m2 * g * math.sin(t1 - 2 * t2)
              - 2 * sin_d * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * cos_d)) / (l1 * den)
        a2 = (2 * sin_d * (w1 * w1 * l1 * (m1 + m2) + g * (m1 + m2) * math.cos(t1)
                           + w2 * w2 * l2 * m2 * cos_d)) / (l2 * den)
        return (w1, w2, a1, a2)

    def rk4_step(self, h: float) -> None:
        """One classical Runge-Kutta step of h seconds:
        y += h/6 (k1 + 2 k2 + 2 k3 + k4), k1 = f(y), k2 = f(y + h/2 k1), k3 = f(y + h/2 k2),
        k4 = f(y + h k3)."""
        y = self.state
        f = self.derivative
        k1 = f(y)
        k2 = f(tuple(a + 0.5 * h * b for a, b in zip(y, k1)))
        k3 = f(tuple(a + 0.5 * h * b for a, b in zip(y, k2)))
        k4 = f(tuple(a + h * b for a, b in zip(y, k3)))
        self.state = tuple(a + h / 6.0 * (b1 + 2 * b2 + 2 * b3 + b4)
                           for a, b1, b2, b3, b4 in zip(y, k1, k2, k3, k4))

    @staticmethod
    def steps_for(dt: float, n: int) -> int:
        """RK4 steps used for dt when n are asked for: n, or more if dt/n exceeds MAX_STEP."""
        return max(n, math.ceil(dt / MAX_STEP))

    def advance(self, dt: float, n: int) -> bool:
        """Advance dt seconds in steps_for(dt, n) RK4 steps of equal length. Returns True, or
        False if the integration went non-finite: then the state is left as it was before the
        call, the last finite state."""
        y0 = self.state
        if not all(map(math.isfinite, y0)):
            return False
        m = self.steps_for(dt, n)
        h = dt / m
        try:
            for _ in range(m):
                self.rk4_step(h)
        except (ValueError, OverflowError):   # math.sin(inf), float ** overflow
            self.state = (math.nan,) * 4
        if all(map(math.isfinite, self.state)):
            return True
        self.state = y0
        return False

    # ----- reading and setting the state ----------------------------------------------------
    def positions(self, pivot: tuple[float, float]) -> np.ndarray:
        """The bobs' world positions, shape (2, 2): rows p1, p2 (y down)."""
        t1, t2 = self.state[0], self.state[1]
        p1 = (pivot[0] + self.l1 * math.sin(t1), pivot[1] + self.l1 * math.cos(t1))
        p2 = (p1[0] + self.l2 * math.sin(t2), p1[1] + self.l2 * math.cos(t2))
        return np.array([p1, p2])

    def energy(self) -> float:
        """Kinetic plus potential energy, zero when both bobs hang straight down at rest."""
        t1, t2, w1, w2 = self.state
        l1, l2, m1, m2, g = self.l1, self.l2, self.m1, self.m2, self.g
        kinetic = (0.5 * (m1 + m2) * (l1 * w1) ** 2 + 0.5 * m2 * (l2 * w2) ** 2
                   + m2 * l1 * l2 * w1 * w2 * math.cos(t1 - t2))
        # Heights above the lowest configuration (y down, so "up" is -y).
        potential = (m1 * g * l1 * (1 - math.cos(t1))
                     + m2 * g * (l1 * (1 - math.cos(t1)) + l2 * (1 - math.cos(t2))))
        return kinetic + potential

    def set_from_cartesian(self, pivot: tuple[float, float], p1, v1, p2, v2) -> None:
        """Set the state from bob positions and velocities (e.g. pymunk's after a mouse drag):
        each angle from its rod's direction, each rate from the velocity across the rod,
        omega = (r x v) / |r|^2 with r the rod vector."""
        r1 = (p1[0] - pivot[0], p1[1] - pivot[1])
        r2 = (p2[0] - p1[0], p2[1] - p1[1])
        u2 = (v2[0] - v1[0], v2[1] - v1[1])
        # theta is measured from +y (down) towards +x: theta = atan2(x, y).
        t1 = math.atan2(r1[0], r1[1])
        t2 = math.atan2(r2[0], r2[1])
        # d(theta)/dt for theta = atan2(x, y) is (y vx - x vy) / (x^2 + y^2); x * x, not x ** 2:
        # a float ** overflows with an exception (a huge state after a blow-up), * gives inf.
        w1 = (r1[1] * v1[0] - r1[0] * v1[1]) / (r1[0] * r1[0] + r1[1] * r1[1])
        w2 = (r2[1] * u2[0] - r2[0] * u2[1]) / (r2[0] * r2[0] + r2[1] * r2[1])
        self.state = (t1, t2, w1, w2)
