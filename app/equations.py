"""Each scene's governing formulas, as the F4 page shows them (rendered by app/draw/formula.py).

Plain data, no pygame: a scene's formulas are a list of `Equation(caption, tex)`, the TeX in
matplotlib's mathtext dialect (no TeX install needed). Every formula here is the one the code
runs, in the code's names and the project's convention (y down, gravity (0, +g)); the module
that runs it is named in its caption or in the comment beside it, and tests/test_equations.py
steps the code and checks the formula's numbers where one step can show them.

`equations_for(scene)` gives the list for a scene as it is set now: the mass-spring cloth shows
the update of the integrator in use, the integrator lab all six.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Equation:
    caption: str        # what it is, in words (the HUD's text font)
    tex: str            # the formula, mathtext: "$...$"


# the six integrators of app/physics/integrators.py, as its docstring writes them
# (a = f/m; y = [x, v]; f(y) = [v, a])
INTEGRATOR_UPDATES: dict[str, Equation] = {
    "euler": Equation("forward Euler", r"$y_{n+1} = y_n + h\,f(y_n)$"),
    "symplectic_euler": Equation(
        "symplectic Euler", r"$v_{n+1} = v_n + h\,a(x_n, v_n),\quad x_{n+1} = x_n + h\,v_{n+1}$"),
    "verlet": Equation("Verlet (velocity-less)", r"$x_{n+1} = 2x_n - x_{n-1} + h^2\,a(x_n)$"),
    "midpoint": Equation("midpoint (RK2)",
                         r"$y_{n+1} = y_n + h\,f\left(y_n + \frac{h}{2}f(y_n)\right)$"),
    "rk4": Equation("RK4", r"$y_{n+1} = y_n + \frac{h}{6}\,(k_1 + 2k_2 + 2k_3 + k_4)$"),
    "implicit_euler": Equation(
        "implicit Euler (Baraff & Witkin): one Newton step, one linear solve (CG, or an LU)",
        r"$\left(M - h\,\frac{\partial f}{\partial v} - h^2\,\frac{\partial f}{\partial x}\right)"
        r"\Delta v = h\left(f_0 + h\,\frac{\partial f}{\partial x}\,v_0\right),\quad "
        r"x_{n+1} = x_n + h\,(v_n + \Delta v)$"),
}

HOOKE = Equation(
    "a spring from a to b, l = x_a - x_b (spring_forces.py): Hooke's law with its damping",
    r"$f_a = -\left[k\,(|l| - r) + k_d\,(v_a - v_b)\cdot\frac{l}{|l|}\right]"
    r"\frac{l}{|l|},\quad f_b = -f_a$")

EXPLICIT_LIMIT = Equation(
    "an explicit step is stable only below (undamped; RK4: 2.83/omega_max)",
    r"$h < \frac{2}{\omega_{max}}$")

VERLET_CLOTH = Equation(
    "the Verlet step (physics/cloth.py): drag is the velocity lost per 1/60 s, at any h",
    r"$x_{n+1} = x_n + (1 - \mathrm{drag})^{60h}\,(x_n - x_{n-1}) + a\,h^2$")

ROD_PROJECTION = Equation(
    "Jakobsen's rod (physics/rods.py): both ends move along the rod, w = 1/m (0: pinned)",
    r"$\delta = x_2 - x_1,\quad x_1 \leftarrow x_1 + \delta\,\frac{|\delta| - r}{|\delta|}"
    r"\frac{w_1}{w_1 + w_2},\quad x_2 \leftarrow x_2 - \delta\,\frac{|\delta| - r}{|\delta|}"
    r"\frac{w_2}{w_1 + w_2}$")

STRAIN = Equation("the stretch the colours show", r"$\varepsilon = \left|\frac{|\delta|}{r} - 1\right|$")

# pymunk (Chipmunk2D) 7: cpSpaceStep moves every body (cpBodyUpdatePosition) before it updates
# the velocities (cpBodyUpdateVelocity) and solves contacts and joints, once a step of h
PYMUNK_STEP = Equation(
    "pymunk's step: positions first, with the velocity the last step left (plus a small bias "
    "that pushes overlaps apart), then the velocities (damping: what is left of v after 1 s), "
    "then contacts and joints correct them",
    r"$x_{n+1} = x_n + h\,v_n,\quad v_{n+1} = v_n\,\mathrm{damping}^{\,h} + "
    r"h\left(g + \frac{F}{m}\right)$")

CONTACT = Equation(
    "a contact: impulses j along the normal n, iterated (e = e_a e_b, mu = mu_a mu_b)",
    r"$j_n \geq 0,\quad v'_{rel}\cdot n \geq -e\,v_{rel}\cdot n,\quad |j_t| \leq \mu\,j_n$")

NEWTON_EULER = Equation("a rigid body: force and torque",
                        r"$m\,\dot v = F,\quad I\,\dot\omega = \tau = r \times F$")

PIN_SLIDE = Equation(
    "the joints: a pin keeps a distance, a slide keeps it in a range",
    r"$|p_b - p_a| = d,\qquad d_{min} \leq |p_b - p_a| \leq d_{max}$")

COLLISION_1D = Equation(
    "two balls meet: momentum is kept; equal masses with e = 1 swap their velocities",
    r"$m_1 v_1 + m_2 v_2 = m_1 v'_1 + m_2 v'_2,\quad v'_2 - v'_1 = -e\,(v_2 - v_1)$")

DOUBLE_PENDULUM = Equation(
    "the ghost's equations (double_pendulum_ode.py), d = theta1 - theta2, "
    "D = 2 m1 + m2 - m2 cos 2d",
    r"$\ddot\theta_1 = \frac{-g(2m_1 + m_2)\sin\theta_1 - m_2 g \sin(\theta_1 - 2\theta_2)"
    r" - 2\sin d\;m_2(\dot\theta_2^2 l_2 + \dot\theta_1^2 l_1 \cos d)}{l_1 D}$")

DOUBLE_PENDULUM_2 = Equation(
    "", r"$\ddot\theta_2 = \frac{2\sin d\,\left(\dot\theta_1^2 l_1 (m_1 + m_2) + g(m_1 + m_2)"
        r"\cos\theta_1 + \dot\theta_2^2 l_2 m_2 \cos d\right)}{l_2 D}$")

PAIR_FORCE = Equation(
    "the pair rule (particle_dance.py), d = x_j - x_i, b = 0.3 R: a core, then a tent",
    r"$f_i = F(r)\,\frac{d}{r},\ f_j = -f_i;\quad F = k_{rep}\left(\frac{r}{b} - 1\right)"
    r"\ (r < b),\quad F = A_{s_i s_j} k_{att}\left(1 - \frac{|2r - R - b|}{R - b}\right)"
    r"\ (b \leq r < R)$")

DRAG = Equation("drag (every particle on its own)", r"$f = -k_d\,v$")

PROJECTION = Equation(
    "contact by projection (obstacles.py): a particle inside (d < 0) moves to the surface; "
    "for a ball d = |p - c| - r",
    r"$\mathrm{if}\ d(p) < 0:\quad p \leftarrow p - d(p)\,n(p)$")

VERLET_FRICTION = Equation(
    "Coulomb friction (cloth_contact.py): the sliding along the surface loses at most mu times "
    "the push, and stops if that is more",
    r"$|\Delta x_t| \leftarrow \max\left(0,\ |\Delta x_t| - \mu\,|\Delta x_n|\right)$")

SELF_COLLISION = Equation(
    "self-collision: two particles closer than s (not joined by a rod) pushed apart to s, a rod "
    "that may only grow",
    r"$|x_j - x_i| < s:\quad x_i \leftarrow x_i - \frac{1}{2}\,(s - |\delta|)\,"
    r"\frac{\delta}{|\delta|},\ x_j \leftarrow x_j + \frac{1}{2}\,(s - |\delta|)\,"
    r"\frac{\delta}{|\delta|}$")

VELOCITY_FILTER = Equation(
    "projection (the default): to the surface, and the velocity into the obstacle removed, as "
    "Baraff & Witkin constrain a particle",
    r"$p \leftarrow p - d\,n,\quad v \leftarrow v - \min(v\cdot n,\,0)\,n$")

PENALTY = Equation(
    "penalty: a stiff spring pushes back; an explicit step must then stay below",
    r"$f = k_c\,(-d)\,n\ \ (d < 0),\qquad h < \frac{2}{\sqrt{\omega_{max}^2 + k_c/m}}$")

COUPLING = Equation(
    "the coupling (coupling.py): particle i, d_i px inside a body, moves its share out; "
    "w = 1/m, k particles inside",
    r"$\Delta x_i = -d_i\,\frac{w_p}{w_p + k\,w_{body}}\,n_i,\quad "
    r"w_{body} = \frac{1}{M} + \frac{(r_i \times n_i)^2}{I}$")

COUPLING_IMPULSE = Equation(
    "the body takes the opposite of the momentum the particles gained",
    r"$J = -\sum_i \frac{m_p\,\Delta x_i}{h},\quad "
    r"\Delta v = \frac{J}{M},\quad \Delta\omega = -\frac{1}{I}\sum_i r_i \times "
    r"\frac{m_p\,\Delta x_i}{h}$")

_SCENES: dict[str, list[Equation]] = {
    "trampoline": [VERLET_CLOTH, COUPLING, COUPLING_IMPULSE],
    "falling_balls": [PYMUNK_STEP, CONTACT],
    "pivoting_l": [PYMUNK_STEP, NEWTON_EULER, PIN_SLIDE],
    "newtons_cradle": [COLLISION_1D, PYMUNK_STEP],
    "double_pendulum": [DOUBLE_PENDULUM, DOUBLE_PENDULUM_2, PYMUNK_STEP],
    "particle_dance": [PAIR_FORCE, DRAG, INTEGRATOR_UPDATES["symplectic_euler"]],
}


def equations_for(scene) -> list[Equation]:
    """The formulas of `scene` as it is set now ([] for a scene that has none here)."""
    name = scene.name
    if name in ("mass_spring_cloth", "mass_spring_collisions"):
        integrator = scene.p.get("integrator", "implicit_euler")
        update = INTEGRATOR_UPDATES.get(integrator)
        eqs = [HOOKE] + ([update] if update else [])
        if scene.p.get("obstacles", "none") != "none":
            eqs.append(PENALTY if scene.p.get("contact") == "penalty" else VELOCITY_FILTER)
        elif integrator != "implicit_euler":
            eqs.append(EXPLICIT_LIMIT)
        return eqs
    if name in ("cloth", "cloth_collisions"):
        eqs = [VERLET_CLOTH, ROD_PROJECTION, STRAIN]
        on = getattr(scene, "on", set())
        if scene.p.get("obstacles", "none") != "none" and "collisions" in on:
            eqs.append(PROJECTION)
            if "friction" in on:
                eqs.append(VERLET_FRICTION)
        if "self_collision" in on:
            eqs.append(SELF_COLLISION)
        return eqs
    if name == "integrators":
        return list(INTEGRATOR_UPDATES.values())
    own = getattr(scene, "equations", None)       # a scene (or a scene file) may declare its own
    if callable(own):
        return list(own())
    return list(_SCENES.get(name, ()))
