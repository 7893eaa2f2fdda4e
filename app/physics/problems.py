"""Test problems for the integrators, each with its exact (or reference) solution and its energy,
and the two experiments the lab runs on them: order of convergence and stability limit.

* MassOnSpring: a bob hanging from the ceiling by an undamped spring, under gravity (one unary
  force, one n-ary force). The spring is Hooke's law f = -k (x - x_rest) about its rest point
  (a zero-rest-length spring to a pinned particle there), so the system is linear everywhere,
  even when a blowing-up bob swings past the ceiling: omega = sqrt(k/m), and the exact solution
  is y(t) = y_eq + A cos(omega t). With hang=0 and gravity=0 it is the textbook oscillator
  x'' = -omega^2 x: the stability experiment uses that one.
* Pendulum: a bob on a circle of radius L, written as a 1-D particle at arc length s = L theta
  (force: gravity's tangential part). No closed form at a large angle, so the reference is RK4 at
  a tiny step (h = 1e-4 s): far more accurate than anything compared against it.
* TwoBodyOrbit: two bodies under their mutual attraction (a spatial force) on a Kepler ellipse;
  exact solution from Kepler's equation E - e sin E = n t (solved by Newton's method).

Units are the lab's: pixels, seconds, y down. Each problem's origin is its anchor / pivot / centre
of mass; the scene places it on screen. `error(ps, t)` is the relative phase-space error
sqrt(sum |x - x_ref|^2 + |v - v_ref|^2 / omega^2) / scale over the free particles (velocities
count too, so a run that happens to pass the right point with the wrong speed is not 'exact').
The benchmark's end time T (`horizon`) is deliberately not a whole period: after exactly one
period of a periodic motion the O(h) error of symplectic Euler cancels and it would look second
order.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from app.physics.forces import Attraction, FloorPush, Gravity, PendulumGravity, Springs
from app.physics.integrators import INTEGRATORS, check_step, get_integrator, rk4_tuple
from app.physics.particles import ParticleSystem


class Problem:
    """A system with a known answer. Subclasses set the class attributes and implement
    make_system, exact, energy, points and phase."""

    name = ""
    title = ""
    omega = 1.0        # characteristic angular frequency (1/s): the HUD's omega*dt uses it
    scale = 1.0        # characteristic length (px): errors are relative to it
    horizon = 1.0      # the benchmark's end time T (s)
    phase_labels = ("x", "v")
    start_offsets = 1  # error_at averages over this many start times spread over one step
    sweep: tuple[float, int] | None = None   # the order sweep (largest omega*h, halvings), if
    #                                          not the benchmark's per-order default

    def make_system(self) -> ParticleSystem:
        """A fresh particle system in the initial state."""
        raise NotImplementedError

    def exact(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Exact (or reference) positions and velocities at time t, shaped like ps.x and ps.v."""
        raise NotImplementedError

    def energy(self, x: np.ndarray, v: np.ndarray) -> float:
        """Total energy of the state (x, v)."""
        raise NotImplementedError

    def points(self, x: np.ndarray) -> np.ndarray:
        """World points (k, 2), relative to the problem's origin, of the bodies to draw."""
        return x

    def phase(self, x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
        """One (position, velocity) pair for the phase portrait."""
        raise NotImplementedError

    def phase_curve(self, samples: int = 200) -> np.ndarray:
        """The exact trajectory in the phase portrait: a closed curve, shape (samples, 2)."""
        raise NotImplementedError

    def make_system_at(self, t: float) -> ParticleSystem:
        """A fresh system in the exact state at time t (t = 0: make_system())."""
        ps = self.make_system()
        if t:
            x, v = self.exact(t)
            ps.x, ps.v = x.copy(), v.copy()
        return ps

    def error(self, ps: ParticleSystem, t: float) -> float:
        """Relative phase-space error of ps against the exact solution at time t."""
        x_ref, v_ref = self.exact(t)
        dx = (ps.x - x_ref) * ps.free
        dv = (ps.v - v_ref) * ps.free / self.omega
        return math.sqrt(float(np.sum(dx * dx) + np.sum(dv * dv))) / self.scale


class MassOnSpring(Problem):
    name = "spring"
    title = "mass on a spring"
    phase_labels = ("displacement (px)", "velocity (px/s)")

    def __init__(self, omega: float = 9.0, hang: float = 180.0, gravity: float = 980.0,
                 amplitude: float = 120.0, mass: float = 1.0):
        self.omega, self.hang, self.g, self.mass = omega, hang, gravity, mass
        self.k = mass * omega * omega
        self.sag = mass * gravity / self.k                   # how far gravity pulls the bob down
        self.length_eq = hang + self.sag                     # the bob's rest position below the ceiling
        self.amplitude = self.scale = amplitude
        self.horizon = 2.0

    def make_system(self) -> ParticleSystem:
        """Particle 0 is the pinned rest point of the spring (`hang` below the ceiling at the
        origin), particle 1 the bob, `amplitude` below its equilibrium."""
        x = np.array([[0.0, self.hang], [0.0, self.length_eq + self.amplitude]])
        forces = [Springs([0], [1], self.k, 0.0, rest=0.0)]
        if self.g:
            forces.append(Gravity((0.0, self.g)))
        return ParticleSystem(x, np.zeros_like(x), self.mass, forces, pinned=[0])

    def exact(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        wt = self.omega * t
        x = np.array([[0.0, self.hang], [0.0, self.length_eq + self.amplitude * math.cos(wt)]])
        v = np.array([[0.0, 0.0], [0.0, -self.amplitude * self.omega * math.sin(wt)]])
        return x, v

    def energy(self, x: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + spring + gravity energy, zero at rest in equilibrium (= k d^2/2 + m v^2/2
        for a displacement d from equilibrium)."""
        bob, vb = x[1], v[1]
        stretch2 = float((bob - x[0]) @ (bob - x[0]))
        height = bob[1] - self.length_eq                     # below the equilibrium, y down
        e = (0.5 * self.mass * float(vb @ vb) + 0.5 * self.k * (stretch2 - self.sag ** 2)
             - self.mass * self.g * height)
        # the minimum is 0 at rest in equilibrium; near it the large spring and gravity terms
        # cancel to rounding noise (-1e-17), which the table would show as a negative E/E0
        return max(e, 0.0)

    def phase(self, x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
        return float(x[1, 1] - self.length_eq), float(v[1, 1])

    def phase_curve(self, samples: int = 200) -> np.ndarray:
        wt = np.linspace(0, 2 * math.pi, samples)
        return np.stack((self.amplitude * np.cos(wt), -self.amplitude * self.omega * np.sin(wt)), 1)


class Pendulum(Problem):
    name = "pendulum"
    title = "pendulum"
    phase_labels = ("angle (rad)", "angular velocity (rad/s)")

    def __init__(self, length: float = 200.0, gravity: float = 980.0, angle: float = 1.2,
                 mass: float = 1.0, reference_step: float = 1e-4):
        self.length, self.g, self.angle, self.mass = length, gravity, angle, mass
        self.omega = math.sqrt(gravity / length)
        self.scale = length * angle                          # the arc amplitude
        self.horizon = 2.0                                   # not a whole period (see error())
        self.reference_step = reference_step
        self._ref = (0.0, angle, 0.0)                        # (t, theta, theta') of the reference

    def make_system(self) -> ParticleSystem:
        return ParticleSystem([[self.length * self.angle]], [[0.0]], self.mass,
                              [PendulumGravity(self.g, self.length)])

    def exact(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """The reference: RK4 on theta'' = -(g/L) sin theta at a step <= reference_step, carried
        forward from the last time asked (the scene asks for increasing times)."""
        t0, th, om = self._ref
        if t < t0:
            t0, th, om = 0.0, self.angle, 0.0
        n = math.ceil((t - t0) / self.reference_step - 1e-9)
        if n > 0:
            h, c = (t - t0) / n, self.g / self.length
            def f(y: tuple[float, ...]) -> tuple[float, float]:   # (theta, theta')'
                return (y[1], -c * math.sin(y[0]))
            y = (th, om)
            for _ in range(n):
                y = rk4_tuple(f, y, h)
            th, om = y
            self._ref = (t, th, om)
        return np.array([[self.length * th]]), np.array([[self.length * om]])

    def energy(self, x: np.ndarray, v: np.ndarray) -> float:
        theta = float(x[0, 0]) / self.length
        return 0.5 * self.mass * float(v[0, 0]) ** 2 + self.mass * self.g * self.length * (1 - math.cos(theta))

    def points(self, x: np.ndarray) -> np.ndarray:
        theta = x[:, 0] / self.length
        return np.stack((self.length * np.sin(theta), self.length * np.cos(theta)), axis=1)

    def phase(self, x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
        return float(x[0, 0]) / self.length, float(v[0, 0]) / self.length

    def phase_curve(self, samples: int = 200) -> np.ndarray:
        """Energy conservation: theta'^2 = 2 (g/L) (cos theta - cos theta0)."""
        theta = self.angle * np.cos(np.linspace(0, 2 * math.pi, samples))
        speed = np.sqrt(np.maximum(2 * self.omega ** 2 * (np.cos(theta) - math.cos(self.angle)), 0))
        sign = np.where(np.linspace(0, 2 * math.pi, samples) <= math.pi, -1.0, 1.0)
        return np.stack((theta, sign * speed), 1)


class TwoBodyOrbit(Problem):
    name = "orbit"
    title = "two-body orbit"
    phase_labels = ("separation r (px)", "dr/dt (px/s)")

    def __init__(self, semi_major: float = 150.0, eccentricity: float = 0.5, period: float = 2.0,
                 masses: tuple[float, float] = (3.0, 1.0)):
        self.a, self.e = semi_major, eccentricity
        self.m = np.array(masses, dtype=float)
        self.omega = 2 * math.pi / period                    # mean motion n
        self.gm = self.omega ** 2 * semi_major ** 3          # Kepler's third law: n^2 a^3 = G M
        self.G = self.gm / self.m.sum()
        self.b = semi_major * math.sqrt(1 - eccentricity ** 2)
        self.scale = semi_major
        self.horizon = 1.3 * period                          # not a whole period

    def make_system(self) -> ParticleSystem:
        x, v = self.exact(0.0)
        return ParticleSystem(x, v, self.m, [Attraction(self.G, 2)])

    def exact(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        mean = self.omega * t
        E = mean if self.e < 0.8 else math.pi
        for _ in range(50):                                  # Newton on E - e sin E = n t
            dE = (E - self.e * math.sin(E) - mean) / (1 - self.e * math.cos(E))
            E -= dE
            if abs(dE) < 1e-15:
                break
        rate = self.omega / (1 - self.e * math.cos(E))       # dE/dt
        r = np.array([self.a * (math.cos(E) - self.e), self.b * math.sin(E)])
        dr = np.array([-self.a * math.sin(E) * rate, self.b * math.cos(E) * rate])
        share = self.m[::-1, None] / self.m.sum() * np.array([[-1.0], [1.0]])
        return share * r, share * dr                         # centre of mass at rest at 0

    def energy(self, x: np.ndarray, v: np.ndarray) -> float:
        r = math.hypot(*(x[1] - x[0]))
        kinetic = 0.5 * float(np.sum(self.m[:, None] * v * v))
        return kinetic - self.G * self.m[0] * self.m[1] / r

    def phase(self, x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
        d, dv = x[1] - x[0], v[1] - v[0]
        r = math.hypot(*d)
        return r, float(d @ dv) / r

    def exact_orbit_points(self, samples: int = 200) -> np.ndarray:
        """The exact path of the lighter body (the last one) around the centre of mass."""
        E = np.linspace(0, 2 * math.pi, samples)
        r = np.stack((self.a * (np.cos(E) - self.e), self.b * np.sin(E)), 1)
        return r * self.m[0] / self.m.sum()

    def phase_curve(self, samples: int = 200) -> np.ndarray:
        """r = a (1 - e cos E), dr/dt = a e sin E dE/dt over one orbit."""
        E = np.linspace(0, 2 * math.pi, samples)
        rate = self.omega / (1 - self.e * np.cos(E))
        return np.stack((self.a * (1 - self.e * np.cos(E)), self.a * self.e * np.sin(E) * rate), 1)


class Bounce(Problem):
    """A ball dropped onto a stiff floor: what a contact does to an integrator's order.

    The floor (forces.FloorPush) pushes the ball up with a constant force `stiffness` times its
    weight while the ball's lowest point is below the surface (y > 0, y down), and not at all
    above it: the force jumps from 0 to 30 m g the instant the ball touches. The motion is exact
    and periodic, piecewise parabolas: fall for t1 = sqrt(2 H / g) to the speed V = g t1, sink
    in and come back out in t2 = 2 V / (push/m - g) (38 ms at the defaults, 4.9 px deep), rise
    for t1. Energy is conserved, so E/E0 keeps its meaning.

    Why a jump and not a Hooke penalty spring k d: a step is a quadrature of the force over h,
    and a quadrature rule misses a kink or a jump inside its interval by a fixed fraction of it.
    A spring's force starts from zero at the surface (only its slope jumps): the step that
    straddles the touch-down errs by O(h^2), and since that happens once per contact, not every
    step, the global order falls only to 2. With a jump in the force itself, that step evaluates
    the wrong force for a fraction of h: an O(h) error per contact, whatever the method's order,
    so every integrator's global order falls to about 1 (measured: measured_orders and
    `python -m app bench integrators`).
    """

    name = "bounce"
    title = "ball bouncing on a floor"
    phase_labels = ("height above the floor (px)", "velocity (px/s)")

    def __init__(self, height: float = 150.0, gravity: float = 980.0, stiffness: float = 30.0,
                 mass: float = 1.0):
        if not stiffness > 1.0:
            raise ValueError(f"the floor must push harder than gravity pulls: stiffness > 1, "
                             f"got {stiffness!r}")
        self.height, self.g, self.mass = height, gravity, mass
        self.push = stiffness * mass * gravity
        self.t_fall = math.sqrt(2 * height / gravity)
        self.speed = gravity * self.t_fall                 # V at the surface
        self.inside = self.push / mass - gravity           # deceleration in the floor
        self.t_contact = 2 * self.speed / self.inside
        self.depth = self.speed ** 2 / (2 * self.inside)
        self.period = 2 * self.t_fall + self.t_contact
        self.omega = 2 * math.pi / self.period
        self.scale = height
        self.horizon = 2.0                                 # two bounces, not a whole period
        # Where the touch-down falls within a step decides the size (and sign) of its error: the
        # error of one run swings by 100x between neighbouring step sizes. The order is measured
        # on the root mean square over 8 start times spread over one step, and over a sweep of
        # steps from 18 ms to 1.1 ms (omega*h 0.1 down to 0.00625), not only its smallest steps.
        self.start_offsets = 8
        self.sweep = (0.1, 4)

    def make_system(self) -> ParticleSystem:
        return ParticleSystem([[0.0, -self.height]], [[0.0, 0.0]], self.mass,
                              [Gravity((0.0, self.g)), FloorPush(0.0, self.push)])

    def exact(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Fall, sink into the floor, rise: three parabolas, repeated every period."""
        tau = math.fmod(t, self.period)
        g, V = self.g, self.speed
        if tau < self.t_fall:                               # falling
            y, v = -self.height + g * tau * tau / 2, g * tau
        elif tau < self.t_fall + self.t_contact:            # in the floor, pushed back
            s = tau - self.t_fall
            y, v = V * s - self.inside * s * s / 2, V - self.inside * s
        else:                                               # rising
            s = tau - self.t_fall - self.t_contact
            y, v = -V * s + g * s * s / 2, -V + g * s
        return np.array([[0.0, y]]), np.array([[0.0, v]])

    def energy(self, x: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravity (zero at the floor's surface; y down) + the floor's potential."""
        y = float(x[0, 1])
        return (0.5 * self.mass * float(v[0] @ v[0]) - self.mass * self.g * y
                + self.push * max(y, 0.0))

    def phase(self, x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
        return -float(x[0, 1]), -float(v[0, 1])             # height and upward velocity

    def phase_curve(self, samples: int = 200) -> np.ndarray:
        ts = np.linspace(0.0, self.period, samples, endpoint=False)
        return np.array([self.phase(*self.exact(float(t))) for t in ts])


PROBLEMS: dict[str, Callable[[], Problem]] = {
    "spring": MassOnSpring, "pendulum": Pendulum, "orbit": TwoBodyOrbit, "bounce": Bounce}


def make_problem(name: str) -> Problem:
    """A fresh problem called `name`; ValueError listing the accepted names otherwise."""
    if name not in PROBLEMS:
        raise ValueError(f"unknown problem {name!r}; accepted: " + ", ".join(PROBLEMS))
    return PROBLEMS[name]()


def oscillator(omega: float = 1.0) -> MassOnSpring:
    """The undamped linear oscillator x'' = -omega^2 x (zero-rest-length spring, no gravity)."""
    return MassOnSpring(omega=omega, hang=0.0, gravity=0.0, amplitude=1.0)


# ----- experiments ----------------------------------------------------------------------------------
def run(problem: Problem, integrator: str, h: float, steps: int) -> ParticleSystem:
    """A fresh system of `problem` advanced by `steps` steps of h."""
    step, h = get_integrator(integrator).step, check_step(h)
    ps = problem.make_system()
    for _ in range(steps):
        step(ps, h)
    return ps


def error_at(problem: Problem, integrator: str, T: float, steps: int) -> tuple[float, int]:
    """(relative error at time T, derivative evaluations + Jacobian products) for `steps` steps;
    the error is inf if the run went non-finite. A problem with start_offsets = k > 1 (bounce)
    is run k times from the exact state at t0 = j h / k (j = 0 .. k-1) to t0 + T: the error is
    the root mean square of the k errors, the evaluations those of one run."""
    step, h = get_integrator(integrator).step, check_step(T / steps)
    k = problem.start_offsets
    squares, evals = 0.0, 0
    for j in range(k):
        t0 = j * h / k
        ps = problem.make_system_at(t0)
        for _ in range(steps):
            step(ps, h)
        if not ps.is_finite():
            return math.inf, ps.evals + ps.jac_products
        squares += problem.error(ps, t0 + T) ** 2
        evals = ps.evals + ps.jac_products
    return math.sqrt(squares / k), evals


def fitted_order(hs: list[float], errors: list[float], asymptotic: bool = False) -> float | None:
    """Slope of log(error) against log(h) by least squares (error ~ C h^order). asymptotic: fit
    only the (up to) 4 smallest steps whose error lies between round-off (1e-11) and 0.1, where
    the leading term dominates; None if fewer than 2 such points (hs from largest to smallest)."""
    if asymptotic:
        good = [(h, e) for h, e in zip(hs, errors) if 1e-11 < e < 0.1][-4:]
        if len(good) < 2:
            return None
        hs, errors = [h for h, _ in good], [e for _, e in good]
    return float(np.polyfit(np.log(hs), np.log(errors), 1)[0])


def convergence_order(problem: Problem, integrator: str, steps: list[int],
                      T: float | None = None) -> tuple[float, list[float]]:
    """The measured order: slope of log(error) against log(h) by least squares over runs of
    `steps` steps each to time T; returns (order, errors)."""
    T = problem.horizon if T is None else T
    errors = [error_at(problem, integrator, T, n)[0] for n in steps]
    return fitted_order([T / n for n in steps], errors), errors


def sweep_steps(problem: Problem, top: float, halvings: int, T: float | None = None) -> list[int]:
    """Step counts to time T for omega*h = top, top/2, ... (halvings + 1 runs)."""
    T = problem.horizon if T is None else T
    return [math.ceil(problem.omega * T / (top / 2 ** k)) for k in range(halvings + 1)]


def measured_orders(problem: Problem, integrators: list[str] | None = None) -> dict[str, float]:
    """Each integrator's order on a problem with its own sweep (bounce): the least-squares slope
    of log(error) against log(h) over the whole sweep (convergence_order)."""
    if problem.sweep is None:
        raise ValueError(f"problem {problem.name!r} has no sweep of its own")
    steps = sweep_steps(problem, *problem.sweep)
    return {name: convergence_order(problem, name, steps)[0]
            for name in (integrators or list(INTEGRATORS))}


def energy_growth(integrator: str, omega_h: float, steps: int = 2000) -> float:
    """On the undamped oscillator at this omega*h: the largest energy over the last quarter of the
    run divided by the largest over the first quarter (inf if it blew up). Bounded methods give
    about 1; a growth factor per step > 1 shows up as a large ratio."""
    problem = oscillator()
    ps = problem.make_system()
    step, h = get_integrator(integrator).step, check_step(omega_h / problem.omega)
    quarter = steps // 4
    energies = np.empty(steps)
    for k in range(steps):
        step(ps, h)
        energies[k] = problem.energy(ps.x, ps.v)
        if not math.isfinite(energies[k]) or energies[k] > 1e12:
            return math.inf
    return float(energies[-quarter:].max() / energies[:quarter].max())


def is_stable(integrator: str, omega_h: float, steps: int = 2000, tolerance: float = 1.001) -> bool:
    """The growth criterion: stable if the energy's maximum grew by less than `tolerance`."""
    return energy_growth(integrator, omega_h, steps) < tolerance


def stability_limit(integrator: str, lo: float = 0.1, hi: float = 20.0, steps: int = 2000,
                    rel_tol: float = 2e-3) -> float:
    """The measured stability limit in omega*h on the undamped oscillator, by bisection between
    lo and hi (geometric midpoints). 0.0 if it already grows at lo (no limit: unstable at every
    step size we can test), inf if it is still stable at hi (unconditionally stable)."""
    if not is_stable(integrator, lo, steps):
        return 0.0
    if is_stable(integrator, hi, steps):
        return math.inf
    while hi / lo > 1 + rel_tol:
        mid = math.sqrt(lo * hi)
        if is_stable(integrator, mid, steps):
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


__all__ = ["Problem", "MassOnSpring", "Pendulum", "TwoBodyOrbit", "Bounce", "PROBLEMS", "make_problem",
           "oscillator", "run", "error_at", "convergence_order", "sweep_steps", "measured_orders", "energy_growth", "is_stable",
           "stability_limit"]
