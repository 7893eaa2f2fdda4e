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

These are integrated with classical Runge-Kutta (RK4, app/physics/integrators.py's rk4_tuple) at
a step chosen so that the result is "the exact solution" for the lecture at every setting the
scene allows. The motion is chaotic for high releases: two runs that differ by a hair part ways
after a few seconds, which is what the scene shows by running the same pendulum in pymunk beside
this one.

Why point masses match pymunk's bobs: pymunk's bobs are discs with a moment of inertia, but both
pin joints hold them at their centres of mass, so no joint force has a lever arm on a bob, the bobs
never start spinning and their rotation drops out of the energy. Point masses are the exact model.

The step adapts to the motion (`advance`). A fixed step cannot serve every setting: with a light
upper bob under a heavy lower one (mass1 0.05, mass2 20) the denominator D = 2 m1 + m2 - m2 cos 2d
drops to 2 m1 whenever the rods line up, the accelerations jump a hundredfold, and at a fixed 0.1 ms
step RK4 lost 82% of the energy in 5 s. So every step is checked against the one thing the exact
solution keeps: its energy. A step whose energy change exceeds its share of the budget
(ENERGY_RATE: a relative 1e-8 per simulated second, so 60 s cost at most 6e-7) is redone at a
smaller step; while the error is well under the budget the step grows again, never past MAX_STEP
(1/120 s. At the default release the energy budget holds the step between 1 and 8.3 ms, 6.3 ms
median over 10 s, measured. The cap was 1 ms: after 10 s at the defaults the two runs' angles differ
by 3e-7 rad (under 1e-4 px at the 160 px rods' tip), as much as either differs from a run capped
at 1/7680 s: far below the 10 px at which the scene says pymunk parted from it; the cap of 1/120
s does about a third of the work).
RK4's energy error per step scales as h^5, so the new step is
h (budget / error)^(1/5) with a safety factor. `energy_drift()` reports the relative drift since
the last set_state (`reference_energy_drift` in the scene's metrics). RK4 is only conditionally
stable (on a linear oscillator it blows up past omega*h = 2.8); the energy check shrinks the step
long before that. If the step would have to fall below MIN_STEP, or one call needs more than
MAX_WORK steps, the reference cannot follow: `advance` keeps the last good state and returns False,
and the scene says so (it never raises).

The step uses plain float arithmetic (the math module; see rk4_tuple for why); `positions` returns
a NumPy array for drawing and comparing. What it costs: advance() takes each step through
`stepper()`, rk4_tuple on derivative() and the energy check written out as one function (the
same bits: a test compares them); one RK4 step is four evaluations of the equations (six
trigonometric calls and ~40 float operations each) and an energy check, ~5 us in CPython, and
the energy budget asks for 2.4-3.2 steps a 60 Hz frame at the defaults (at least 2: MAX_STEP),
~13-17 us a frame, more than pymunk's whole step of the same pendulum (~12 us, 10 substeps):
`bench pymunk` measures both (2026-11-26).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


State = tuple[float, float, float, float]    # theta1, theta2, omega1, omega2 (rad, rad/s)

MAX_STEP = 1 / 120    # seconds: the longest RK4 step advance() takes (the module docstring)
MIN_STEP = 1e-8       # seconds: a step this short that still misses the budget means "cannot follow"
ENERGY_RATE = 1e-8    # allowed relative energy error per simulated second (60 s: 6e-7 at most)
ROUNDOFF = 1e-14      # energy changes below this x the terms' size are rounding, not the step's
MAX_WORK = 200_000    # RK4 steps one advance() may take (about a second of work)


@dataclass
class DoublePendulumODE:
    """A double pendulum of point masses integrated with RK4 (lengths in px, g in px/s^2)."""

    l1: float
    l2: float
    m1: float
    m2: float
    g: float
    state: State = (0.0, 0.0, 0.0, 0.0)
    h: float = MAX_STEP           # the step advance() tries next (it adapts)
    energy0: float = 0.0          # the energy at set_state (for energy_drift)
    steps_taken: int = 0          # RK4 steps accepted or tried since construction (work done)

    def __post_init__(self) -> None:
        self.set_state(self.state)

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

    def constants(self) -> tuple[float, ...]:
        """The products of the parameters that derivative() forms at every call, formed once
        (for stepper(); they hold while l1, l2, m1, m2 and g stay the same)."""
        l1, l2, m1, m2, g = self.l1, self.l2, self.m1, self.m2, self.g
        return (l1, l2, m2, 2 * m1 + m2, m1 + m2, -g * (2 * m1 + m2), m2 * g, g * (m1 + m2))

    def energy_scale(self) -> float:
        """What the relative energy error is measured against: the energy at set_state, or, if
        that is about zero (released at rest at the bottom), the energy of lifting both bobs
        by their rod lengths."""
        lift = (self.m1 + self.m2) * abs(self.g) * (self.l1 + self.l2)
        return max(abs(self.energy0), 1e-6 * lift, 1e-12)

    def energy_drift(self) -> float:
        """(E - E0) / scale since the last set_state: the reference's own error."""
        return (self.energy() - self.energy0) / self.energy_scale()

    def advance(self, dt: float) -> bool:
        """Advance dt seconds in RK4 steps whose size adapts (see the module docstring). Returns
        True, or False if the reference cannot follow (non-finite, a step below MIN_STEP, more
        than MAX_WORK steps): then the state is left as it was before the call."""
        y0 = self.state
        if not all(map(math.isfinite, y0)):
            return False
        scale = self.energy_scale()
        step = self.stepper()
        t, work, e = 0.0, 0, self.energy()
        blur = ROUNDOFF / scale                         # rounding of the energy, per unit size
        y = y0
        try:
            while t < dt:
                h = min(self.h, dt - t)                 # the last step ends exactly at dt
                y_new, e_new, size = step(y, h)
                err, allowed = abs(e_new - e) / scale, max(ENERGY_RATE * h, blur * size)
                work += 1
                if not math.isfinite(err) or work > MAX_WORK:
                    raise OverflowError
                # the step that would just meet the budget (error ~ h^5), with a safety factor
                fit = 0.9 * (allowed / err) ** 0.2 if err > 0 else 2.0
                if err <= allowed or h < MIN_STEP:      # accepted (a sliver at the end of dt
                                                        # has no error worth the name)
                    t, e, y = t + h, e_new, y_new
                    if h == self.h:                     # (a step clipped to dt says little)
                        self.h = min(MAX_STEP, h * min(2.0, fit))
                else:                                   # rejected: redo it shorter
                    self.h = h * max(0.1, fit)
                    if self.h < MIN_STEP:
                        raise OverflowError
        except (ValueError, OverflowError, ZeroDivisionError):   # math.sin(inf), overflow
            self.state = y0
            return False
        self.steps_taken += work
        # angles back into [-pi, pi]: a spinning rod's angle would grow without bound and lose
        # the digits the energy check needs (the positions do not change)
        t1, t2, w1, w2 = y
        self.state = (math.remainder(t1, math.tau), math.remainder(t2, math.tau), w1, w2)
        return True

    def stepper(self):
        """step(y, h) -> (y after one RK4 step of h, and energy_terms() there):
        integrators.rk4_tuple on derivative() and energy_terms written out as one function over
        plain floats, with the parameters' products formed here, once per advance() (the same
        operations in the same order, so the same numbers to the last bit: a test checks it;
        about a third less time than the three calls, which is what advance() spends its time
        on: ~2.5 RK4 steps a frame at the defaults)."""
        l1, l2, m2, m_2m1_m2, m12, minus_g_2m1_m2, m2_g, g_m12 = self.constants()
        sin, cos = math.sin, math.cos
        m1, g = self.m1, self.g
        k1, k2 = 0.5 * (m1 + m2), 0.5 * m2                  # energy_terms' products
        k3, k4, k5 = m2 * l1 * l2, (m1 + m2) * g * l1, m2 * g * l2

        def f(t1: float, t2: float, w1: float, w2: float) -> tuple[float, float]:
            """derivative()'s (alpha1, alpha2), with the products formed above."""
            d = t1 - t2
            sin_d, cos_d = sin(d), cos(d)
            den = m_2m1_m2 - m2 * cos(2 * d)
            return ((minus_g_2m1_m2 * sin(t1) - m2_g * sin(t1 - 2 * t2)
                     - 2 * sin_d * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * cos_d)) / (l1 * den),
                    (2 * sin_d * (w1 * w1 * l1 * m12 + g_m12 * cos(t1)
                                  + w2 * w2 * l2 * m2 * cos_d)) / (l2 * den))

        def step(y: State, h: float) -> tuple[State, float, float]:
            t1, t2, w1, w2 = y
            hh = 0.5 * h
            c1, d1 = f(t1, t2, w1, w2)                         # k1 = (w1, w2, c1, d1)
            a2, b2 = w1 + hh * c1, w2 + hh * d1
            c2, d2 = f(t1 + hh * w1, t2 + hh * w2, a2, b2)
            a3, b3 = w1 + hh * c2, w2 + hh * d2
            c3, d3 = f(t1 + hh * a2, t2 + hh * b2, a3, b3)
            a4, b4 = w1 + h * c3, w2 + h * d3
            c4, d4 = f(t1 + h * a3, t2 + h * b3, a4, b4)
            h6 = h / 6.0
            t1, t2 = t1 + h6 * (w1 + 2 * a2 + 2 * a3 + a4), t2 + h6 * (w2 + 2 * b2 + 2 * b3 + b4)
            w1, w2 = w1 + h6 * (c1 + 2 * c2 + 2 * c3 + c4), w2 + h6 * (d1 + 2 * d2 + 2 * d3 + d4)
            e1, e2 = k1 * (l1 * w1) * (l1 * w1), k2 * (l2 * w2) * (l2 * w2)
            e3 = k3 * w1 * w2 * cos(t1 - t2)
            e4, e5 = k4 * (1 - cos(t1)), k5 * (1 - cos(t2))
            return ((t1, t2, w1, w2), e1 + e2 + e3 + e4 + e5,
                    abs(e1) + abs(e2) + abs(e3) + abs(e4) + abs(e5))

        return step

    # ----- reading and setting the state ----------------------------------------------------
    def positions(self, pivot: tuple[float, float]) -> np.ndarray:
        """The bobs' world positions, shape (2, 2): rows p1, p2 (y down)."""
        t1, t2 = self.state[0], self.state[1]
        p1 = (pivot[0] + self.l1 * math.sin(t1), pivot[1] + self.l1 * math.cos(t1))
        p2 = (p1[0] + self.l2 * math.sin(t2), p1[1] + self.l2 * math.cos(t2))
        return np.array([p1, p2])

    def tip(self, pivot: tuple[float, float]) -> tuple[float, float]:
        """positions(pivot)[1], the lower bob, as two floats (no array: once a step)."""
        t1, t2 = self.state[0], self.state[1]
        return (pivot[0] + self.l1 * math.sin(t1) + self.l2 * math.sin(t2),
                pivot[1] + self.l1 * math.cos(t1) + self.l2 * math.cos(t2))

    def energy(self) -> float:
        """Kinetic plus potential energy, zero when both bobs hang straight down at rest."""
        return self.energy_terms()[0]

    def energy_terms(self) -> tuple[float, float]:
        """(energy, size): size is the sum of the terms' magnitudes. When the bobs swing fast
        in opposite senses the kinetic terms nearly cancel, and rounding blurs the energy by
        about 1e-16 x size, not 1e-16 x energy: advance() allows for that."""
        t1, t2, w1, w2 = self.state
        l1, l2, m1, m2, g = self.l1, self.l2, self.m1, self.m2, self.g
        # x * x, not x ** 2: a float ** overflows with an exception, * gives inf
        terms = (0.5 * (m1 + m2) * (l1 * w1) * (l1 * w1), 0.5 * m2 * (l2 * w2) * (l2 * w2),
                 m2 * l1 * l2 * w1 * w2 * math.cos(t1 - t2),
                 # heights above the lowest configuration (y down, so "up" is -y)
                 (m1 + m2) * g * l1 * (1 - math.cos(t1)), m2 * g * l2 * (1 - math.cos(t2)))
        return sum(terms), sum(map(abs, terms))

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
        self.set_state((t1, t2, w1, w2))

    def set_state(self, state: State) -> None:
        """Start from this state: it is the baseline of energy_drift()."""
        self.state = tuple(state)
        try:
            self.energy0 = self.energy()
        except (ValueError, OverflowError):
            self.energy0 = math.nan
        self.h = MAX_STEP
