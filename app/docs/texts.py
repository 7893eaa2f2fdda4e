"""What the generated reference says about each metric and each --json field: the one hand-written
part of the generated docs. The names come from the code (each scene's metrics(), a run's summary),
the words from here; the generator refuses a name that has no entry here, or an entry for a name
the code no longer reports, so the two cannot drift apart (tests/test_docs.py runs it).

Units are the JSON's (DESIGN.md): lengths in px at zoom 1, time in s, mass in kg, ratios as
fractions (not percent). How the HUD writes a metric comes from the scene's `metric_units`.
The same units head the --csv columns (`unit_of`, through Scene.json_unit): this module imports
nothing of the lab, so the layer rules (tests/test_classroom.py) let the lowest floor read it.
"""

from __future__ import annotations

# (JSON unit, meaning). "1" is a pure number (a ratio or a fraction).
Entry = tuple[str, str]
UNITLESS = ("count", "1", "text", "true/false")     # units a CSV header does not write

_CLOTH_COMMON: dict[str, Entry] = {
    "particles": ("count", "particles in the grid (rows x cols)"),
    "max_stretch": ("1", "largest |length/rest - 1| of the structural rods or springs now"),
    "mean_stretch": ("1", "mean |length/rest - 1| of the structural rods or springs now"),
    "pinned_drift": ("px", "largest distance a locked particle has moved from where it was "
                           "locked (0 for a pin that holds)"),
}

_BALLS: dict[str, Entry] = {
    "balls_spawned": ("count", "balls dropped since the start (the spawner and mouse clicks)"),
    "balls_removed": ("count", "balls removed after leaving the world (the tutorial's "
                               "balls_to_remove)"),
    "balls_alive": ("count", "balls in the space now"),
    "tunneled": ("count", "balls whose centre passed from above the L's long segment to below it "
                          "between two steps: through it, not around it (step too coarse)"),
    "balls_asleep": ("count", "balls pymunk has put to sleep (0 with the `sleeping` effect off)"),
}

METRICS: dict[str, dict[str, Entry]] = {
    "cloth": {
        "particles": _CLOTH_COMMON["particles"],
        "constraints": ("count", "rods in the active rod sets (structural, shear, bending)"),
        "iterations": ("count", "constraint sweeps per substep (the parameter)"),
        "substeps": ("count", "substeps per fixed step (the parameter)"),
        "max_stretch": _CLOTH_COMMON["max_stretch"],
        "mean_stretch": _CLOTH_COMMON["mean_stretch"],
        "pinned_drift": _CLOTH_COMMON["pinned_drift"],
        "torn": ("count", "rods torn so far (the `tearing` effect)"),
        "locked": ("count", "particles locked now: the pins and those dropped with the mouse"),
        "contacts": ("count", "particles that touched an obstacle in the last substep (pushed "
                              "out by the projection; 0 with `collisions` off)"),
        "penetration_max": ("px", "how deep the deepest free particle lies inside an obstacle "
                                  "after the step (0 when the projection left none inside)"),
        "tunneled": ("count", "particle paths that passed through an obstacle within a substep, "
                              "since the start: each was caught and put back where it entered"),
        "self_overlaps": ("count", "pairs of particles closer than 95% of self_distance after "
                                   "the step (neighbours of one grid cell and rod ends left out)"),
    },
    "trampoline": {
        "coupling_impulse": ("kg px/s", "|J|, the momentum the cloth gave the body in the last "
                                        "step (summed over its substeps); the cloth got -J. A "
                                        "body resting on the cloth: its weight times dt"),
        "contacts": ("count", "cloth particles found inside the body at the last substep"),
        "penetration_max": ("px", "deepest movable particle inside the body after the step; 0 "
                                  "with `collisions` off"),
        "momentum_x": ("kg px/s", "total momentum, cloth + body, x (changes only by gravity, "
                                  "pins and the floor)"),
        "momentum_y": ("kg px/s", "total momentum, cloth + body, y (down)"),
        "body_vy": ("px/s", "the body's vertical velocity (y down: negative is up)"),
        "body_y": ("px", "the body's centre, y (down); the pins are at 440"),
        "max_stretch": _CLOTH_COMMON["max_stretch"],
    },
    "mass_spring_cloth": {
        "particles": _CLOTH_COMMON["particles"],
        "springs": ("count", "springs in the active sets (structural, shear, bending)"),
        "integrator": ("text", "the integrator in use"),
        "omega_max": ("1/s", "the cloth's highest angular frequency (power iteration), "
                             "re-estimated as it moves"),
        "explicit_limit_h": ("s", "symplectic Euler's predicted largest stable step on the cloth "
                                  "now, with its spring damping (2/omega_max undamped)"),
        "step_limit_h": ("s", "the limit of the integrator in use, the lowest seen (the HUD's "
                              "band is judged against it); null for implicit Euler"),
        "limit_band": ("text", "where the step is: `stable` (below half the limit), `marginal`, "
                               "`past the limit`; null for implicit Euler"),
        "max_stretch": _CLOTH_COMMON["max_stretch"],
        "mean_stretch": _CLOTH_COMMON["mean_stretch"],
        "energy": ("kg px^2/s^2", "kinetic + spring + gravitational energy, 0 in the start pose "
                                  "(the HUD divides by 256^2 to show joules)"),
        "solver": ("text", "the implicit step's linear solve: `cg` (conjugate gradients) or "
                           "`direct` (SciPy's sparse LU); the parameter"),
        "cg_iterations": ("count", "conjugate-gradient iterations of the last implicit solve; 0 "
                                   "with an explicit integrator, null before the first solve"),
        "cg_converged": ("true/false", "whether the last solve reached its tolerance; null "
                                       "without one"),
        "cg_residual": ("1", "the last solve's relative residual; null without one"),
        "cg_failures": ("count", "implicit steps whose CG stopped short (each then solved by the "
                                 "sparse LU)"),
        "pinned_drift": _CLOTH_COMMON["pinned_drift"],
        "contacts": ("count", "free particles touching an obstacle: moved out of one in the "
                              "last step (projection) or inside one now (penalty); 0 with "
                              "`collisions` off"),
        "penetration_max": ("px", "deepest free particle inside an obstacle after the step "
                                  "(projection: 0 but where obstacles overlap; penalty: how far "
                                  "its spring lets the cloth in)"),
        "contact_limit_h": ("s", "contact=penalty: its own step limit 2 sqrt(m/k_c) for the "
                                 "lightest free particle; null with projection"),
    },
    "falling_balls": dict(_BALLS),
    "pivoting_l": {
        "angle_deg": ("deg", "the L's angle now"),
        "slide_distance": ("px", "distance between the slide joint's anchors now"),
        "slide_seen_min": ("px", "smallest slide_distance seen over the run"),
        "slide_seen_max": ("px", "largest slide_distance seen (the joint's limit is the "
                                 "parameter `slide_max`)"),
        "pin_error": ("px", "largest distance between the pin's two anchors seen (0 for a perfect "
                            "pin)"),
        "pin_let_go": ("true/false", "the pin opened by more than 5 px: the step is too coarse "
                                     "for the joints"),
        **_BALLS,
    },
    "newtons_cradle": {
        "lifted": ("count", "k, the balls lifted (the parameter)"),
        "balls_out": ("count", "balls that swing out past half the release amplitude in the first "
                               "half-swing after the first impact"),
        "middle_max_drift": ("px", "largest distance from rest of a ball that should stay still "
                                   "(neither lifted nor expected out)"),
        "energy_ratio": ("1", "kinetic + potential energy now / at release; null with no energy "
                              "at release"),
        "release_speed": ("px/s", "speed of the lifted balls just before the first impact"),
        "out_speed_ratio": ("1", "the slowest far ball's top speed after the impact / "
                                 "release_speed"),
    },
    "double_pendulum": {
        "energy_drift": ("1", "(E - E0) / E0 of the pymunk pendulum now"),
        "reference_divergence": ("px", "distance between the pymunk tip and the RK4 ghost's tip "
                                       "now; null with the reference off"),
        "divergence_time": ("s", "time from release until the tips first parted by more than "
                                 "10 px; null while they have not"),
        "energy_drift_max": ("1", "largest |energy_drift| seen"),
        "engine_blowup_t": ("s", "time from release until |energy_drift| first passed 5 %; null "
                                 "while it has not"),
        "pin_error": ("px", "largest rod length error now"),
        "reference_energy_drift": ("1", "the ghost's own relative energy error since the release"),
        "reference_blowup_t": ("s", "time at which the reference could not follow; null while it "
                                    "has not"),
    },
    "integrators": {
        "omega_dt": ("1", "omega * h, the step h = dt/substeps against the problem's frequency"),
        "<integrator>_error": ("1", "relative phase-space distance from the exact solution now"),
        "<integrator>_step_us": ("us", "median microseconds per step, measured while it runs"),
        "<integrator>_energy_ratio": ("1", "energy now / at the start, E/E0"),
        "<integrator>_blew_up_t": ("s", "when it blew up (non-finite or 1000x the problem's size "
                                        "away); null while it has not"),
        "<integrator>_cg_converged": ("true/false", "implicit Euler only: whether its last "
                                                    "linear solve converged"),
        "<integrator>_cg_residual": ("1", "implicit Euler only: its last solve's residual"),
        "<integrator>_cg_failures": ("count", "implicit Euler only: steps whose CG stopped short"),
    },
    "particle_dance": {
        "particles": ("count", "particles in the box"),
        "pair_tests": ("count", "pairs whose distance was tested in the last step (all pairs: "
                                "n(n-1)/2); null before the first step"),
        "neighbour_method": ("text", "`all_pairs` or `grid`"),
        "kinetic_energy": ("px^2/s^2", "sum of v^2/2 (every mass is 1)"),
        "pairs_interacting": ("count", "pairs closer than the cut-off in the last step (the same "
                                       "for both methods); null before the first step"),
    },
}
METRICS["cloth_collisions"] = METRICS["cloth"]      # the same cloth, with its contact cards
METRICS["mass_spring_collisions"] = METRICS["mass_spring_cloth"]   # the same cloth, on obstacles

# the --json summary of one run (and what --compare and --video add)
SUMMARY_FIELDS: dict[str, str] = {
    "scene": "the scene's name",
    "steps": "fixed steps run",
    "sim_seconds": "simulated time, s",
    "wall_seconds": "wall time of the run, s (with --compare: the whole comparison's)",
    "step_ms": "median wall time of one physics step, drawing excluded, ms",
    "params": "every parameter's resolved value",
    "effects": "the effects that are on",
    "metrics": "the scene's own numbers (below, per scene)",
    "state_hash": "a hash of the physical state (the same command gives the same hash)",
    "finite": "false if the simulation went non-finite (exit code 1)",
    "events": "--input events delivered",
    "error": "the message of an exception raised by a student's code (exercise scenes); null",
    "variant": "--compare: this pane's settings as given",
    "pane": "--compare: the pane's tag, A to D",
    "label": "--compare: what differs, as the pane's box says it",
    "reference_error": "--compare: the scene's error against its reference: `what`, `metric`, "
                       "`value` (null where the scene has none)",
    "video": "--video: the clip's path",
    "video_frames": "--video: frames in the file (read back: a GIF merges equal frames)",
    "video_seconds": "--video: the clip's duration, s, as read back from the file",
    "video_bytes": "--video: the file's size",
    "replaced": "the outputs of this run (--csv, --screenshot, --video) that replaced a file that "
                "was there (their paths; [] if none did)",
}


def unit_of(scene: str, metric: str) -> str:
    """The JSON unit of `metric` of the scene named `scene` ("" if this table does not know it).
    A pattern entry `<integrator>_error` stands for every name ending in `_error` that has no
    entry of its own (the longest such ending wins)."""
    table = METRICS.get(scene, {})
    if metric in table:
        return table[metric][0]
    ends = {k.partition(">")[2]: v[0] for k, v in table.items() if k.startswith("<")}
    for end in sorted(ends, key=len, reverse=True):
        if metric.endswith(end) and len(metric) > len(end):
            return ends[end]
    return ""
