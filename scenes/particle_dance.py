"""Particle dance: species that like or dislike each other, and what finding the pairs costs.

What it shows: a few hundred particles (up to 5000) of 1-6 species in a box. Any two closer than
the cut-off R attract or repel each other by a soft rule (the lecture's third family of forces,
spatial interaction; drag is a unary force; the cloth has the n-ary springs): a repulsive core
inside 0.3 R keeps them apart, and beyond it a species pair's entry of the rule matrix (the
table in the colour key: + attract, - repel) pulls them together or pushes them apart. Watch
like-minded species gather into clusters and shun the others. The pair forces are equal and
opposite, so they never change the total momentum; with drag on, the dance settles, the mouse
stirs it up again. Physics: app/physics/particle_dance.py and app/physics/neighbours.py.

The cost: the forces need every pair closer than R. `neighbour_method=all_pairs` tests all
n (n - 1) / 2 pairs, O(n^2); `grid` sorts the particles into cells at least R wide and tests only
pairs from the same or neighbouring cells: 4.5 cells' worth per particle, O(n) at a fixed density.
This box is fixed, so more particles means denser and the grid's tests grow like n^2 too, but
from about 1/50 of all pairs at R = 40 (n x 4.5 cells' worth of the 24 x 18 = 432 against
n^2/2: 9/432; still 1/50 after 10 s at 2000 particles; 1/33 to 1/21 over 10 s of the LMB
gathering a crowd at the centre), after a fixed cost per step (about 0.1 ms of NumPy calls,
whatever n is) that makes all pairs the cheaper one below about 100-200 particles. The HUD shows
the pair tests (and, for the grid, their share of all pairs) and the ms per step of the method in
use: raise `particles` and switch the method live. Hold the LMB and a crowd forms in which
each particle has many more neighbours within R: the grid's share of all pairs climbs, and each
pair within R needs its force whichever method found it. The HUD says when the physics no longer
keeps up with real time, and names a crowd when there is one.

Controls:
  LMB (held)  pull the particles near the cursor towards it (follow it around)
  RMB (held)  push them away
Settings: particles, species, rules (random / like_own / opposites), neighbour_method, cutoff,
attraction, repulsion, drag_coef; effects: interaction, drag, walls.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.bounds import clamp_point
from app.physics.neighbours import (NEIGHBOUR_METHODS, all_pair_tests, crowded_share,
                                    expected_grid_tests)
from app.physics.particle_dance import (CORE, EFFECTS, RULES, MouseForce, PairRule,
                                        ParticleDance, rule_matrix)
from app.scene import Effect, InputEvent, Param, ParamError, Scene, Try, Unit
from app.vectors import Arrows, sample_every, sample_text

DOT_RADIUS = 3.5            # world px
MAX_SPECIES = 6             # as many as app/draw/dance_draw.py has colours

# Step budget: the window gives physics at most 0.1 s of a frame (app/window/scene_view.py) but
# always runs one whole step, so a step estimated above STEP_BUDGET_S is refused (the window would
# answer only every step). The estimate: a cost per particle (sorting, integrating, drag, walls)
# plus one per pair test (with the force on the pairs that pass); measured on the 2-core lab
# machine, busy (`bench particles` prints the estimate beside the measured step): the grid
# 17-43 ns per candidate pair, all pairs 3.4-7.6 ns per test, and 230-375 ns per particle at
# cut-off 10 px (where the pair tests cost next to nothing); the constants lean to the busy end.
STEP_BUDGET_S = 0.1
SECONDS_PER_TEST = {"all_pairs": 7e-9, "grid": 2.5e-8}
SECONDS_PER_PARTICLE = 3e-7
# Spread over the box at 5000 particles, a particle has some 35 neighbours within R = 40 (60 once
# the clusters form); past CROWD the HUD calls it crowded (the mouse gathers hundreds).
CROWD = 100


class ParticleDanceScene(Scene):
    __doc__ = __doc__
    name = "particle_dance"
    title = "Particle dance: spatial forces, all pairs vs grid"
    category = "Particle systems"
    params = (
        Param("particles", 600, int, 2, 5000, help="number of particles"),
        Param("species", 3, int, 1, MAX_SPECIES, help="number of species (colours)"),
        Param("rules", "random", str, choices=RULES, rebuild=False,
              help="who likes whom: random (from the seed), like_own (clusters), opposites"),
        Param("neighbour_method", "grid", str, choices=NEIGHBOUR_METHODS, rebuild=False,
              help="how the pairs within the cut-off are found: test all pairs, or a cell grid"),
        Param("cutoff", 40.0, float, 10.0, 80.0, rebuild=False,
              help="interaction range R in px (repulsive core: the inner 30 %)"),
        Param("attraction", 300.0, float, 0.0, 2000.0, rebuild=False,
              help="k_att: the rule matrix's +-1 is this many px/s^2 at the tent's peak"),
        Param("repulsion", 1000.0, float, 0.0, 5000.0, rebuild=False,
              help="k_rep: the core's push at distance 0, px/s^2"),
        Param("drag_coef", 1.0, float, 0.0, 20.0, rebuild=False,
              help="k_d in f = -k_d v, 1/s (every mass 1): how fast the velocity decays"),
        Param("mouse_strength", 3000.0, float, 0.0, 20000.0, rebuild=False,
              help="the mouse's strongest pull or push, px/s^2 (half-way to its radius)"),
        Param("mouse_radius", 150.0, float, 20.0, 400.0, rebuild=False,
              help="the mouse reaches particles this close, px"),
    )
    effects = (
        Effect("interaction", True, "the pair forces (spatial interaction): off = no pair search",
               amount="attraction"),
        Effect("drag", True, "viscous drag f = -k_d v (unary)", amount="drag_coef"),
        Effect("walls", True, "the box reflects particles (off: they drift out of view)"),
    )
    tries = (
        Try("3000 particles, all pairs", {"particles": 3000, "neighbour_method": "all_pairs"},
            "the HUD's pair tests: 4.5 million per step, and the ms per step that costs"),
        Try("3000 particles, grid", {"particles": 3000, "neighbour_method": "grid"},
            "the same forces from about 1/50 of the pair tests: compare the ms per step"),
        Try("Like your own kind", {"rules": "like_own", "species": 4},
            "each colour gathers into its own clusters; the RMB breaks them up, they re-form"),
        Try("No drag", {"drag_coef": 0.0},
            "nothing takes energy out: the dance never settles (and the step's energy error "
            "at the rule's kinks slowly heats it)"),
    )
    comparisons = (     # "try this" cards that run variants side by side (--compare)
        Try("All pairs vs grid", {"particles": 2000},
            "the same pairs and the same forces, found by testing all pairs (A) or a cell grid "
            "(B): B tests a fraction of the pairs, in a fraction of A's ms per step; the dances "
            "agree to a millionth of a pixel at first, then part within seconds: round-off "
            "from another order of summing, grown by the chaos of thousands of particles",
            compare=({"neighbour_method": "all_pairs"}, {"neighbour_method": "grid"})),
    )

    # ----- settings ---------------------------------------------------------------------------
    @classmethod
    def step_seconds(cls, values) -> float:
        """Estimated seconds of one fixed step, with the particles spread out (not crowded)."""
        n, method = values["particles"], values["neighbour_method"]
        world = (float(cls.world_size[0]), float(cls.world_size[1]))
        tests = (all_pair_tests(n) if method == "all_pairs"
                 else expected_grid_tests(n, values["cutoff"], world))
        return values["substeps"] * (tests * SECONDS_PER_TEST[method] + n * SECONDS_PER_PARTICLE)

    @classmethod
    def omega(cls, values) -> float:
        """The fastest oscillation the pair forces can drive, 1/s: two particles joined by the
        stiffest spring the rule acts like (the core's slope k_rep / b or the tent's
        2 k_att / (R - b)) swing at sqrt(2 k) (reduced mass 1/2); a crowd pushes harder, so k is
        scaled by 1 + CORE^2 c, c the neighbours within R if spread evenly (those in the core)."""
        R = values["cutoff"]
        b = CORE * R
        k = max(values["repulsion"] / b, 2.0 * values["attraction"] / (R - b))
        w, h = cls.world_size
        crowd = (values["particles"] - 1) * math.pi * R * R / (w * h)
        return math.sqrt(2.0 * k * (1.0 + CORE * CORE * crowd))

    @classmethod
    def check_combination(cls, values) -> None:
        h = 1.0 / (values["hertz"] * values["substeps"])
        # explicit drag multiplies v by (1 - k_d h): past 1 it reverses the velocity, past 2 it grows
        if values["drag_coef"] * h > 1.0:
            raise ParamError(
                f"drag_coef x h too large: {values['drag_coef']:g}/s x h = "
                f"{values['drag_coef'] * h:.3g} (h = 1/(hertz x substeps)); accepted: at most 1 "
                f"(an explicit step would reverse the velocity), here hertz x substeps >= "
                f"{math.ceil(values['drag_coef'])}")
        # symplectic Euler keeps an oscillation bounded for omega h < 2; past about 1 the kinks
        # of the rule (at b, mid-way, at R) already heat the dance up step by step
        omega = cls.omega(values)
        if omega * h > 1.0:
            raise ParamError(
                f"step too large for the forces: omega h = {omega * h:.3g} (omega = "
                f"{omega:.3g}/s from repulsion, attraction, cutoff and particles; h = 1/(hertz x "
                f"substeps)); accepted: at most 1, here hertz x substeps >= {math.ceil(omega)}")
        cost = cls.step_seconds(values)
        if cost > STEP_BUDGET_S:
            raise ParamError(
                f"particles x substeps too large for {values['neighbour_method']}: "
                f"{values['particles']} particles x {values['substeps']} substeps would take "
                f"~{cost * 1000:.0f} ms per step; accepted: at most {STEP_BUDGET_S * 1000:.0f} ms "
                f"(the window waits for a whole step; use fewer particles or substeps"
                + (", or neighbour_method=grid)" if values["neighbour_method"] == "all_pairs"
                   else ")"))

    # ----- world ------------------------------------------------------------------------------
    def _rule(self) -> PairRule:
        p = self.p
        matrix = rule_matrix(p["rules"], p["species"], np.random.default_rng([p["seed"], 1]))
        return PairRule(matrix, p["cutoff"], p["attraction"], p["repulsion"])

    def build(self) -> None:
        p = self.p
        self.dance = ParticleDance(p["particles"], p["species"], self.world_size, self._rule(),
                                   self.rng, self.on, p["drag_coef"], p["neighbour_method"])
        self.mouse_pos: tuple[float, float] | None = None
        self.mouse_button = 0
        self._costs: dict[str, float] = {}
        self._cost_mark = (0, dict(self.dance.spent), 0.0)
        self._energy0 = None            # the energy bars' start: taken when first shown

    def settings_changed(self, names: set[str]) -> None:
        d, p = self.dance, self.p
        self._energy0 = None            # a new rule: a new potential, a new start
        d.pair_force.rule = self._rule()
        d.pair_force.method = p["neighbour_method"]
        d.drag.kd = p["drag_coef"]
        if self.mouse_button:
            self._press(self.mouse_button)
        d.set_effects(self.on)
        if "neighbour_method" in names:
            self._costs.clear()                     # the old method's cost is not this one's

    def step(self, h: float) -> None:
        self.dance.step(h)

    # ----- the mouse --------------------------------------------------------------------------
    def _press(self, button: int) -> None:
        sign = 1.0 if button == 1 else -1.0
        self.mouse_button = button
        self.dance.set_mouse(MouseForce(self.mouse_pos, sign * self.p["mouse_strength"],
                                        self.p["mouse_radius"]))

    def handle_event(self, event: InputEvent) -> None:
        if not event.kind.startswith("mouse"):
            return
        self.mouse_pos = clamp_point(event.pos, self.world_size)     # every scene's one rule
        if event.kind == "mouse_down" and event.button in (1, 3):
            self._press(event.button)
        elif event.kind == "mouse_up" and event.button == self.mouse_button:
            self.mouse_button = 0
            self.dance.set_mouse(None)
        elif event.kind == "mouse_move" and self.dance.mouse is not None:
            self.dance.mouse.point = np.asarray(self.mouse_pos, dtype=float)

    def arrows(self) -> Arrows:
        """Every particle, or one in k when there are more than MAX_ARROWS (a thicket of 5000
        arrows reads as nothing)."""
        ps = self.dance.ps
        ids = np.arange(0, ps.n, sample_every(ps.n))
        return Arrows(ids, ps.x[ids].copy(), ps.v[ids].copy(), ps.mass[ids].copy(),
                      sample_text(len(ids), ps.n, "particle"))

    # ----- reports ----------------------------------------------------------------------------
    def energies(self):
        """Energy bars: kinetic and the pair potentials (0 beyond the cut-off), against the total
        when the bars were first shown since the dance was built or its settings changed (the
        dance starts in motion; taking it at every build would cost a pair search the bars may
        never need)."""
        from app.energy import Energies
        d = self.dance
        kinetic, pairs = d.kinetic_energy(), d.potential_energy()
        if self._energy0 is None:
            self._energy0 = kinetic + pairs
        return Energies((("kinetic", kinetic), ("pairs", pairs)), self._energy0,
                        zero="at rest, no two particles within the cut-off (every mass 1)",
                        losses="drag, symplectic Euler at the rule's kinks (it gains too); the "
                               "mouse puts energy in", unit="px^2/s^2")

    def metrics(self) -> dict[str, float | str | None]:
        d = self.dance
        # before the first step no search has run: None; with interaction off, 0 tests is a count
        searched = self.steps > 0 or "interaction" not in self.on
        return {
            "particles": d.ps.n,
            "pair_tests": d.pair_force.tests if searched else None,
            "neighbour_method": self.p["neighbour_method"],
            "kinetic_energy": d.kinetic_energy(),
            "pairs_interacting": d.pair_force.pairs if searched else None,
        }

    def _update_costs(self) -> None:
        """ms per fixed step of each effect (and of the pair search), averaged since the last
        call, lightly smoothed."""
        steps0, spent0, search0 = self._cost_mark
        if self.steps <= steps0:
            return
        d = self.dance
        n = self.steps - steps0
        now = {k: (d.spent[k] - spent0.get(k, 0.0)) * 1000.0 / n for k in d.spent}
        now["search"] = (d.pair_force.search_seconds - search0) * 1000.0 / n
        for k, v in now.items():
            self._costs[k] = v if k not in self._costs else 0.7 * self._costs[k] + 0.3 * v
        self._cost_mark = (self.steps, dict(d.spent), d.pair_force.search_seconds)

    def effect_costs(self) -> dict[str, float]:
        self._update_costs()
        shown = [k for k in EFFECTS if k in self.on]
        if self.dance.mouse is not None:
            shown.append("mouse")
        return {k: self._costs.get(k, 0.0) for k in shown}

    def hud_details(self) -> list[str]:
        """The mouse; the rule matrix follows (color_key, on this page: a line per species)."""
        return ["LMB: pull   RMB: push   (hold and move)",
                f"rules: {self.p['rules']}; who likes whom:" if "interaction" in self.on
                else "interaction off: no rules act"]

    def step_ms(self) -> float:
        """Measured ms of physics per fixed step: the effects' costs added up (0 before any)."""
        return sum(v for k, v in self._costs.items() if k != "search")

    def hud_lines(self) -> list:
        from app.draw.hud import WARN_COLOR, Line
        self._update_costs()
        d, p = self.dance, self.p
        pf, n = d.pair_force, d.ps.n
        lines: list = []
        slow = self.real_time_words()
        if "interaction" not in self.on:
            lines.append(f"{n} particles, interaction off: no pairs to find")
            return lines + ([Line(slow, WARN_COLOR)] if slow else [])
        method, every = p["neighbour_method"], all_pair_tests(n)
        of_all = (f"{crowded_share(pf.tests, n):.0%} of all {every:,}" if method == "grid" and every
                  else "every pair")
        # (phrases parted by '  |  ': a row breaks between them at F2, never inside one)
        lines.append(f"{n} particles  |  {method}: {pf.tests:,} pair tests/step  |  ({of_all})")
        search = self._costs.get("search", 0.0)
        total = self._costs.get("interaction", 0.0)
        lines.append(f"find pairs {search:.2f} + forces {max(total - search, 0.0):.2f} = "
                     f"{total:.2f} ms/step  |  {pf.pairs:,} pairs < R")
        if slow:
            lines.append(Line(slow, WARN_COLOR))
        return lines

    def real_time_words(self) -> str:
        step, need = self.step_ms(), 1000.0 / self.p["hertz"]
        if step <= need:                 # physics alone keeps up with the time it simulates
            return ""
        pairs = self.dance.pair_force.pairs if "interaction" in self.on else 0
        partners = 2.0 * pairs / max(self.dance.ps.n, 1)     # each pair has two particles
        crowd = f"; crowded: {partners:.0f} neighbours within R each" if partners > CROWD else ""
        return (f"too slow for real time: {step:.0f} ms per {need:.1f} ms step "
                f"(x{need / step:.2f}){crowd}")

    # ----- state ------------------------------------------------------------------------------
    def state_arrays(self):
        return (self.dance.ps.x, self.dance.ps.v)

    # ----- drawing ------------------------------------------------------------------------------
    def draw(self, surface, view) -> None:
        from app.draw.dance_draw import draw_mouse, draw_particles
        d = self.dance
        draw_particles(surface, view, d.ps.x, d.species, self.p["species"], DOT_RADIUS)
        if d.mouse is not None:
            draw_mouse(surface, view, d.mouse.point, d.mouse.radius, d.mouse.strength >= 0)

    color_key_details = True     # a line per species: on the HUD's second page (F4)
    metric_units = {"kinetic_energy": Unit("px^2/s^2")}    # (every mass is 1)

    @property
    def color_key(self) -> tuple:
        """Who likes whom (the rule matrix), a HUD line per species; none without interaction."""
        from app.draw.dance_draw import rule_key
        return rule_key(self.dance.pair_force.rule.matrix) if "interaction" in self.on else ()
