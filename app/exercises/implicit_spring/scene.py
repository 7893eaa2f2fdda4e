"""The `implicit_spring` exercise's scene: `python -m app --scene exercise:implicit_spring`.

A small net of stiff damped springs pinned at the middle of its top row, swinging, stepped by
the student's implicit_euler_step at a step far past the explicit limit, beside the lab's
backward Euler (app/physics/integrators.py: implicit_euler, orange rings).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from app.exercises.implicit_spring.grader import G, _springs, energy, step
from app.exercises.live import StudentCode
from app.exercises.particle_scene import ParticleExercise
from app.scene import Param, common

ROWS, COLS, SPACING = 4, 5, 45.0
PIN = COLS // 2                  # the top row's middle particle: the net swings about it
ORIGIN = (480.0 - PIN * SPACING, 150.0)
RELEASE = math.radians(70.0)     # the net is let go turned this far from hanging straight


def net() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The net at rest (hanging straight down from PIN): positions, spring ends a, b and rest
    lengths (structural and shear springs)."""
    r, c = np.mgrid[0:ROWS, 0:COLS]
    idx = r * COLS + c
    pairs = [(idx[:, :-1], idx[:, 1:]), (idx[:-1, :], idx[1:, :]),
             (idx[:-1, :-1], idx[1:, 1:]), (idx[:-1, 1:], idx[1:, :-1])]
    a = np.concatenate([p.ravel() for p, _ in pairs])
    b = np.concatenate([q.ravel() for _, q in pairs])
    x = np.stack([ORIGIN[0] + c.ravel() * SPACING, ORIGIN[1] + r.ravel() * SPACING], axis=1)
    return x.astype(float), a, b, np.linalg.norm(x[a] - x[b], axis=1)


class _Net:
    """The net, stepped by impl.implicit_euler_step (the student's or the lab's)."""

    radius = 7.0
    ring = True

    def __init__(self, impl, ks: float, kd: float, turn: float = RELEASE):
        # the function, not the module: the window's snapshots copy the nets, a module cannot be
        self.impl = SimpleNamespace(implicit_euler_step=impl.implicit_euler_step)
        self.ks, self.kd = ks, kd
        x, self.a, self.b, self.rest = net()
        pin = x[PIN]
        c, s = math.cos(turn), math.sin(turn)         # turned about the pin, to the left
        self.x = pin + (x - pin) @ np.array([[c, -s], [s, c]])
        self.w = np.ones(len(self.x))
        self.w[PIN] = 0.0                           # pinned: it never moves
        self.v = np.zeros_like(self.x)
        self.links = list(zip(self.a.tolist(), self.b.tolist()))
        self.fixed = np.empty((0, 2))

    def step(self, h: float) -> None:
        self.x, self.v = step(self.impl, (self.x, self.v, self.w, self.a, self.b, self.ks,
                                          self.kd, self.rest, G, h))

    def energy(self) -> float:
        return energy(self.x, self.v, self.w, self.a, self.b, self.ks, self.rest, G)

    def points(self) -> np.ndarray:
        return self.x


class ImplicitSpringExercise(StudentCode, ParticleExercise):
    """Exercise `implicit_spring`: a net of stiff damped springs (structural and shear) pinned at
    the middle of its top row, let go turned 70 degrees, swinging like a pendulum, stepped by
    YOUR implicit_euler_step (filled) beside the lab's backward Euler (orange rings). At the
    default 30 Hz the step is 3x past the explicit limit 2/omega_max (the HUD says how far):
    explicit Euler would blow up here in a few steps. Backward Euler never does, at any step,
    and pays in artificial damping: the larger h, the faster the swing dies. At 30 Hz about half
    the swing's energy is gone after 1 s; at hertz 10 (9x past the limit) 85%.

    HUD: the step against the explicit limit, how far yours is from the lab's, and the energy
    left above rest in each.
    """

    exercise = "implicit_spring"
    title = "Exercise: implicit Euler (Baraff & Witkin)"
    params = (common("hertz", default=30, lo=1), common("substeps", default=1),
              Param("ks", 5000.0, float, 10.0, 50000.0, help="spring stiffness, 1/s^2 per unit "
                    "mass"),
              Param("kd", 2.0, float, 0.0, 50.0, help="spring damping kd, 1/s per unit mass"))

    def make(self, impl):
        return _Net(impl, self.p["ks"], self.p["kd"])

    def build(self) -> None:
        super().build()
        if self.error:                 # their code failed: StudentCode holds the message
            return
        x, a, b, rest = net()
        self.e_rest = energy(*self.at_rest(), self.lab.w, a, b, self.p["ks"], rest, G)
        self.e_start = self.lab.energy() - self.e_rest
        _, K, _ = _springs(x, np.zeros_like(x), a, b, self.p["ks"], 0.0, rest)  # at rest, straight
        W = np.diag(np.repeat(self.lab.w, 2))
        top = float(np.linalg.eigvals(-W @ K).real.max())
        self.omega_max = math.sqrt(max(top, 0.0))

    _rest: dict[tuple[float, float], np.ndarray] = {}

    def at_rest(self) -> tuple[np.ndarray, np.ndarray]:
        """Where the net comes to rest under gravity: the lab's backward Euler with heavy
        damping and long steps from the rest shape (10 s steps: its energy is settled to 1e-13
        after five; kept per stiffness)."""
        key = (self.p["ks"], self.p["kd"])
        if key not in self._rest:
            sim = _Net(self.reference, self.p["ks"], max(self.p["kd"], 50.0), turn=0.0)
            for _ in range(8):
                sim.step(10.0)
            self._rest[key] = sim.x
        return self._rest[key], np.zeros_like(self._rest[key])

    def rest_bounds(self, seconds: float = 3.0) -> tuple[float, float, float, float]:
        """The circle the net can swing through about its pin (its farthest particle, plus room
        for the stretch and a margin): fixed, cheap, and the same at every setting."""
        x, *_ = net()
        reach = float(np.linalg.norm(x - x[PIN], axis=1).max()) * 1.15 + 20.0
        return (x[PIN, 0] - reach, x[PIN, 1] - reach, 2 * reach, 2 * reach)

    def explicit_limit(self) -> float:
        """2 / omega_max, seconds (omega_max of the net at rest, undamped)."""
        return 2.0 / self.omega_max if self.omega_max > 0 else math.inf

    def measure(self) -> dict[str, float]:
        h = self.dt / self.p["substeps"]
        left = [(sim.energy() - self.e_rest) / self.e_start if self.e_start > 0 else math.nan
                for sim in (self.mine, self.lab)]
        return {"apart_px": self.apart(), "h_ms": 1000.0 * h,
                "explicit_limit_ms": 1000.0 * self.explicit_limit(),
                "h_over_limit": h / self.explicit_limit(),
                "energy_left": left[0], "energy_left_lab": left[1]}

    def live_line(self, m: dict[str, float]) -> str:
        return (f"h = {m['h_ms']:.1f} ms: {m['h_over_limit']:.1f}x the explicit limit "
                f"2/omega_max = {m['explicit_limit_ms']:.1f} ms\n"
                f"yours vs the lab's: {m['apart_px']:.3g} px apart; swing energy left: yours "
                f"{share(m['energy_left'])}, the lab's {share(m['energy_left_lab'])}")


def share(value: float) -> str:
    """A fraction of the start as the HUD shows it: 36.6%, or 2.4e+44x once it has blown up."""
    if value is None or not math.isfinite(value):
        return "NaN"
    return f"{100 * value:.1f}%" if abs(value) < 100 else f"{value:.3g}x"


SCENE = ImplicitSpringExercise
