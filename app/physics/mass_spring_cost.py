"""What one step of the mass-spring cloth costs, estimated before it runs, and the budget the scene
(scenes/mass_spring_cloth.py) holds it to: the window gives physics at most FRAME_BUDGET_S of a
frame (app/window/scene_view.py) but always finishes the step it started, and a frame runs
hertz/60 steps (at most the loop's 8, app/loop.py), so a setting whose frame of steps is
estimated above FRAME_BUDGET_S is refused (`refusal`: one line that says what would fit).

A step is `substeps` substeps, and a substep costs (constants measured on the lab's 2-core
machine while other jobs ran, the busy end kept):

    explicit      evaluations x (the forces: FORCES_PER_PARTICLE x n)
    implicit, cg  the forces and the matrix (SETUP_PER_PARTICLE x n) + CG's iterations x (one
                  iteration: ITERATION_FIXED + ITERATION_PER_PARTICLE x n)
    direct        the forces and the matrix + SuperLU's factorization, LU_SECONDS x n^LU_POWER
                  (its factors fill in: the cost grows faster than n)

with n = rows x cols. CG's iterations are what the settings move most, from 1 to thousands. CG's
bound on the residual: with kappa the condition number of the preconditioned matrix, it needs
at most sqrt(kappa)/2 ln(2 sqrt(kappa)/tolerance) iterations, and here kappa ~ 1 + (h omega)^2:
the substep h against the cloth's highest frequency omega (at rest; `rest_omega`, from a small
probe of the same cells). The bound holds but overshoots: measured (first 40-100 steps from
rest, every preset at 16x16 and 32x32, hertz 30-1000, tolerance 1e-2 to 1e-10) the worst
iterations were 0.11-0.75 of it wherever it exceeds 30 (0.3-0.6 at 64x64), so the estimate
takes ITERATIONS_OF_BOUND = 0.8 of it. For a very stiff cloth (every stiffness 1e5, mass 0.001:
h omega up to 1e5) it is far too high: where the springs outweigh the masses the condition
number is the grid's own, and the measured worst was 1.97-2.33 x side^0.75 x ln(1/tolerance)
iterations (side = max(rows, cols); 16x16, 32x32 and 64x64; cotton at 16x16 and 30 Hz too), so
GRID_ITERATIONS = 2.4 of that, and up to 1.6x (32x32) and 2.6x (64x64) more at a tolerance of
1e-10, near the rounding floor, where CG stalls (GRID_STALL: x (1 + side/32)); the estimate is
the smaller of the two.

An estimate is not a guarantee: a fling can take more iterations than a hang. The scene caps CG
at what fits the budget (`iteration_cap`); a solve that hits the cap says so in the HUD, like any
solve that stops short (app/physics/linear_solve.py).
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Callable

from app.loop import FPS_CAP, FixedStepClock
from app.physics.blender_cloth import MATERIAL_KEYS, material_settings
from app.physics.integrators import INTEGRATORS

FRAME_BUDGET_S = 0.1                 # s of physics a frame may hold the window

FORCES_PER_PARTICLE = 0.45e-6        # s per particle: one evaluation of every force (64x64: 1.4 ms)
SETUP_PER_PARTICLE = 1.2e-6          # s per particle: forces, Jacobian blocks, matrix refresh
SETUP_FIXED = 0.3e-3                 # s per substep, whatever the size
ITERATION_FIXED = 20e-6              # s per CG iteration: its NumPy calls
ITERATION_PER_PARTICLE = 35e-9       # s per particle per iteration (64x64: 0.12-0.16 ms)
LU_SECONDS, LU_POWER = 7e-6, 1.2     # SuperLU: 16-24 ms at 32x32, 93-114 ms at 57x57 (stiff)
ITERATIONS_OF_BOUND = 0.8
GRID_ITERATIONS = 2.4
GRID_STALL = 1e-8                    # below this tolerance CG stalls in rounding near its floor
EXPLICIT_EVALUATIONS = {"euler": 1, "symplectic_euler": 1, "verlet": 1, "midpoint": 2, "rk4": 4}


def cloth_spacing(values, world: tuple[float, float]) -> float:
    """The cell size the scene builds (its spacing, shrunk so the cloth fits the world)."""
    w, h = world
    return min(values["spacing"], 0.6 * w / (values["cols"] - 1), 0.6 * h / (values["rows"] - 1))


PROBE_SPACING = 16.0


@lru_cache(maxsize=64)
def _probe_omega(material: tuple) -> float:
    from app.physics.mass_spring import MassSpringCloth
    from app.physics.mass_spring_stability import top_mode
    probe = MassSpringCloth(6, 6, PROBE_SPACING, (0.0, 0.0), "none")
    probe.material = dict(zip(MATERIAL_KEYS, material))
    probe.on = {"damping", "shear", "bending"}          # shear on: the stiffer case (1.2x)
    probe.configure()
    return top_mode(probe.ps, 60)[0]


def rest_omega(values, spacing: float) -> float:
    """omega_max (1/s) of a cloth of these material values and this cell size at rest, shear on:
    the top mode of a 6x6 probe of 16 px cells (a local quantity: the cloth's size hardly moves
    it), scaled to the cell size: every stiffness goes as 1/spacing and every mass as spacing^2,
    so omega^2 goes as spacing^-3. (As the cloth drapes it rises by up to 1.6x: the iterations
    behind cg_iterations were measured on the moving cloth.)"""
    omega = _probe_omega(tuple(float(values[k]) for k in MATERIAL_KEYS))
    return omega * (PROBE_SPACING / spacing) ** 1.5


def cg_iterations(h_omega: float, tolerance: float, rows: int, cols: int) -> int:
    """CG's iterations per solve, estimated (see the module docstring)."""
    root = math.sqrt(1.0 + h_omega * h_omega)
    bound = ITERATIONS_OF_BOUND * root / 2.0 * math.log(2.0 * root / tolerance)
    side = max(rows, cols)
    grid = GRID_ITERATIONS * side ** 0.75 * math.log(1.0 / tolerance)
    if tolerance < GRID_STALL:
        grid *= 1.0 + side / 32.0
    return max(1, math.ceil(min(bound, grid, 2 * rows * cols)))


def iteration_seconds(particles: int) -> float:
    return ITERATION_FIXED + ITERATION_PER_PARTICLE * particles


def substep_seconds(values, h_omega: float) -> tuple[float, int]:
    """(seconds, CG iterations) of one substep with these settings."""
    n = values["rows"] * values["cols"]
    name = values["integrator"]
    if name in EXPLICIT_EVALUATIONS:
        return EXPLICIT_EVALUATIONS[name] * FORCES_PER_PARTICLE * n, 0
    setup = SETUP_FIXED + SETUP_PER_PARTICLE * n
    if values["solver"] == "direct":
        return setup + LU_SECONDS * n ** LU_POWER, 0
    its = cg_iterations(h_omega, values["cg_tolerance"], values["rows"], values["cols"])
    return setup + its * iteration_seconds(n), its


def step_estimate(values, world: tuple[float, float]) -> tuple[float, int]:
    """(seconds of one step: substeps x a substep, CG iterations per substep)."""
    h = 1.0 / (values["hertz"] * values["substeps"])
    omega = rest_omega(values, cloth_spacing(values, world))
    seconds, its = substep_seconds(values, h * omega)
    return values["substeps"] * seconds, its


def iteration_cap(values, step_budget: float) -> int:
    """The most CG iterations a substep may take for the step to stay within `step_budget`
    seconds (at least 1): the solver's cap (MassSpringSystem.budget_iterations). With
    solver=direct CG is the fallback, run after the LU: it gets what the LU leaves."""
    n = values["rows"] * values["cols"]
    room = step_budget / values["substeps"] - SETUP_FIXED - SETUP_PER_PARTICLE * n
    if values["solver"] == "direct":
        room -= LU_SECONDS * n ** LU_POWER
    return max(1, int(room / iteration_seconds(n)))


def what_fits(values, fits: Callable[[dict], bool]) -> list[str]:
    """Settings one change away for which fits(settings) is true, in words ('substeps <= 3',
    'hertz <= 120', 'solver=cg', 'cg_tolerance >= 1e-4', 'at most 40x40 particles')."""
    ok = lambda **change: fits({**values, **change})      # noqa: E731
    ways = []
    fewer = [s for s in range(values["substeps"] - 1, 0, -1) if ok(substeps=s)]
    if fewer:
        ways.append(f"substeps <= {fewer[0]}")
    slower = [hz for hz in (960, 720, 480, 360, 240, 180, 120, 60, 30)
              if hz < values["hertz"] and ok(hertz=hz)]
    if slower:
        ways.append(f"hertz <= {slower[0]}")
    implicit = values["integrator"] not in EXPLICIT_EVALUATIONS
    if implicit and values["solver"] == "direct" and ok(solver="cg"):
        ways.append("solver=cg")
    if implicit and values["solver"] == "cg":
        looser = [t for t in (1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 1e-1)
                  if t > values["cg_tolerance"] and ok(cg_tolerance=t)]
        if looser:
            ways.append(f"cg_tolerance >= {looser[0]:g}")
    side = max(values["rows"], values["cols"])
    smaller = [k for k in range(side - 1, 1, -1)
               if ok(rows=min(values["rows"], k), cols=min(values["cols"], k))]
    if smaller:
        ways.append(f"at most {smaller[0]}x{smaller[0]} particles")
    step = {"hertz": 60, "substeps": 1, "solver": "cg", "cg_tolerance": 1e-2}  # the defaults
    if any(values[k] != v for k, v in step.items()) and ok(**step):
        ways.append("this cloth at hertz 60, 1 substep, solver cg to cg_tolerance 0.01")
    return ways


def steps_per_frame(hertz: int) -> int:
    """The steps a frame runs at full speed: hertz / FPS_CAP, at most the loop's cap."""
    return min(FixedStepClock.max_steps_per_frame, max(1, math.ceil(hertz / FPS_CAP)))


def frame_cost(values, world: tuple[float, float]) -> tuple[float, float, int]:
    """(seconds of the steps a frame runs, of one step, CG iterations a substep), estimated;
    while a named material's preset is being applied (a scene's set('material', ...)), the more
    expensive of the values given and the preset's."""
    step, its = step_estimate(values, world)
    if values["material"] != "custom":
        step, its = max((step, its), step_estimate(
            {**values, **material_settings(values["material"])}, world))
    return steps_per_frame(values["hertz"]) * step, step, its


def refusal(values, world: tuple[float, float]) -> str:
    """'' if a frame of these settings fits FRAME_BUDGET_S; else one line: what it would cost
    and what would fit."""
    frame, step, its = frame_cost(values, world)
    if frame <= FRAME_BUDGET_S:
        return ""
    p, k = values, steps_per_frame(values["hertz"])
    what = (f"{p['rows']}x{p['cols']} x {p['substeps']} substep"
            + ("s" if p["substeps"] > 1 else "") + f", {p['integrator']}")
    if not INTEGRATORS[p["integrator"]].explicit:
        what += f", solver {p['solver']}" + (
            f" (~{its:,} CG iterations a substep at cg_tolerance {p['cg_tolerance']:g})"
            if p["solver"] == "cg" else "")
    per_frame = (f"; at hertz {p['hertz']} a frame runs {k} steps: ~{_seconds(frame)}"
                 if k > 1 else "")
    ways = what_fits(p, lambda v: frame_cost(v, world)[0] <= FRAME_BUDGET_S)
    return (f"too slow for the window: {what} would take ~{_seconds(step)} a step{per_frame}; "
            f"accepted: at most {FRAME_BUDGET_S * 1e3:.0f} ms a frame (the window waits for "
            "whole steps)" + (": " + ", or ".join(ways) + " would fit" if ways else ""))


def _seconds(seconds: float) -> str:
    """'85 ms', '3.2 s'."""
    return f"{seconds * 1e3:.0f} ms" if seconds < 1.0 else f"{seconds:.2g} s"


__all__ = ["FRAME_BUDGET_S", "step_estimate", "frame_cost", "refusal", "steps_per_frame",
           "iteration_cap", "what_fits", "rest_omega", "cg_iterations", "cloth_spacing"]
