"""The written-out usual steps (FallingBallsScene.advance's step_plan, PivotingLScene.advance's
moving_plan) beside a General subclass (a step of its own calling super: the general way), kept
out of the test suite: seeded random settings (substeps 1-4, hertz 1-240, g, spawn_rate 0-200,
sleeping, gravity, radius, ...), set() calls, mouse drags and clicks, kicks (NaN, inf, 1e300),
snapshot/restore, reset; counts, joint records, _xy, state_hash, resting compared after every
step. Prints a digest of the run so two checkouts can be compared (old code against new).

    python tools/fuzz_written_steps.py SCENE SEED [STEPS] [--trace FILE]
    SCENE: falling_balls, pivoting_l or exercise (pivoting_l's, with the lab's reference),
    each optionally with +after (both classes with an after_step of their own)
    for s in $(seq 1 50); do python tools/fuzz_written_steps.py pivoting_l $s; done
Run it from the checkout's root (it imports app and scenes from there); exit 1 on a difference.
"""
from __future__ import annotations

import hashlib
import math
import os
import random
import sys
import warnings

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
warnings.simplefilter("ignore")

from app.scene import InputEvent, ParamError  # noqa: E402
from scenes.falling_balls import FallingBallsScene  # noqa: E402
from scenes.pivoting_l import PivotingLScene  # noqa: E402


def rand_setting(rng: random.Random, pivoting: bool):
    k = rng.choice(["substeps", "hertz", "g", "spawn_rate", "sleeping", "gravity", "radius",
                    "iterations", "max_balls", "friction"]
                   + (["slide_max", "L_mass", "pivot"] if pivoting else ["container"]))
    v = {"substeps": lambda: rng.randint(1, 4),
         "hertz": lambda: rng.choice([1, 2, 5, 15, 30, 60, 60, 90, 120, 240, rng.randint(1, 240)]),
         "g": lambda: rng.choice([0.0, 900.0, 1500.0, 5000.0, rng.uniform(0, 5000)]),
         "spawn_rate": lambda: rng.choice([0.0, 2.0, 30.0, 200.0, rng.uniform(0, 200)]),
         "sleeping": lambda: rng.random() < 0.5, "gravity": lambda: rng.random() < 0.8,
         "container": lambda: rng.random() < 0.5,
         "radius": lambda: rng.choice([2.0, 4.0, 21.0, 60.0, rng.uniform(2, 60)]),
         "iterations": lambda: rng.randint(1, 30), "max_balls": lambda: rng.randint(1, 200),
         "friction": lambda: rng.uniform(0, 2), "slide_max": lambda: rng.uniform(0, 150),
         "L_mass": lambda: rng.choice([0.1, 10.0, 1000.0]),
         "pivot": lambda: rng.choice(["pin", "pivot"])}[k]()
    return k, v


def observe(s) -> tuple:
    s.flush_xy()
    rec = getattr(s, "record", None)
    return (dict(s.counts), None if rec is None else dict(rec), s.time, s.steps, len(s.balls),
            s._xy[:s._used].tobytes(), s.state_hash(), s.resting, getattr(s, "seen", None))


def same(a, b) -> bool:
    # NaN-aware: compare by repr of bytes (xy and hash already bytes); records may hold NaN
    return repr(a) == repr(b)


def kick(s, rng_choice, which):
    """A test's kick: change a body directly and wake()."""
    if which == "L_angle":
        s.L_body.angle = rng_choice
    elif which == "L_spin":
        s.L_body.angular_velocity = rng_choice
    elif which == "ball_vel" and s.balls:
        s.balls[0].body.velocity = (rng_choice, rng_choice)
    s.wake()


def classes(scene_name: str) -> tuple[type, type]:
    """(written-out, general) classes: the scenes; 'exercise' the pivoting_l exercise bound
    to the lab's reference; '+after' an after_step of their own (the plans' `after`)."""
    if scene_name.startswith("exercise"):
        from app.exercises import get_exercise, scene_class
        from app.exercises.live import bind
        W = bind(scene_class("pivoting_l"), student=get_exercise("pivoting_l").reference())
    else:
        W = PivotingLScene if scene_name.startswith("pivoting_l") else FallingBallsScene

    class G(W):
        def step(self, h):
            super().step(h)
    if scene_name.endswith("+after"):
        def after_step(self):
            self.seen = getattr(self, "seen", 0) * 31 + len(self.balls) + self.steps
        W = type("WA", (W,), {"after_step": after_step})
        G = type("GA", (G,), {"after_step": after_step})
    return W, G


def run(scene_name: str, seed: int, steps: int, trace_file: str | None) -> int:
    rng = random.Random(seed)
    pivoting = not scene_name.startswith("falling")
    W, G = classes(scene_name)
    settings = {"seed": seed % 1000, "spawn_rate": rng.choice([2.0, 30.0, 100.0]),
                "sleeping": rng.random() < 0.6, "substeps": rng.randint(1, 4),
                "hertz": rng.choice([30, 60, 60, 120]), "max_balls": rng.randint(20, 150)}
    if not pivoting:
        settings["container"] = rng.random() < 0.4
    w, g = W(settings), G(settings)
    general_adv = [0, 0]
    orig_step = type(w).step

    def counting(h):
        general_adv[0] += 1
        orig_step(w, h)
    w.step = counting           # (instance attr: the plans look at the class; counts general)
    snaps = []
    h = hashlib.sha256()
    mode_counts = {"ops": 0}
    quiet = rng.choice([1, 1, 5])          # (fewer changes: longer runs of usual steps)
    for i in range(steps):
        r = rng.random() * quiet
        ops = []
        if r < 0.04:
            ops.append(("set",) + rand_setting(rng, pivoting))
        elif r < 0.07:
            pos = (rng.uniform(0, 960), rng.uniform(0, 720))
            if rng.random() < 0.5 and w.balls:          # on a ball (a drag)
                x, y = w.balls[rng.randrange(len(w.balls))].body.position
                pos = (x + rng.uniform(-3, 3), y + rng.uniform(-3, 3))
            if pivoting and rng.random() < 0.3:
                pos = (400.0 + rng.uniform(-200, 350), 440.0 + rng.uniform(-4, 4))  # the L
            ops.append(("ev", "mouse_down", pos, rng.choice([1, 1, 1, 3])))
        elif r < 0.12:
            ops.append(("ev", "mouse_move", (rng.uniform(-50, 1010), rng.uniform(-50, 770)), 0))
        elif r < 0.14:
            ops.append(("ev", "mouse_up", (rng.uniform(0, 960), rng.uniform(0, 720)), 1))
        elif r < 0.155:
            ops.append(("snap",))
        elif r < 0.165 and snaps:
            ops.append(("restore", rng.randrange(len(snaps))))
        elif r < 0.17:
            ops.append(("kick", rng.choice([math.inf, -math.inf, math.nan, 1e300, 3.0, 0.0]),
                        rng.choice(["L_angle", "L_spin", "ball_vel"] if pivoting
                                   else ["ball_vel"])))
        elif r < 0.18:
            ops.append(("read",))
        elif r < 0.185:
            ops.append(("reset",))
        for op in ops:
            mode_counts["ops"] += 1
            outs = [[], []]
            for idx, s in enumerate((w, g)):
                out = outs[idx]
                try:
                    if op[0] == "set":
                        s.set(op[1], op[2])
                    elif op[0] == "ev":
                        s.handle_event(InputEvent(op[1], pos=op[2], button=op[3]))
                    elif op[0] == "snap":
                        if idx == 0:
                            snaps.append([s.snapshot(), None])
                        else:
                            snaps[-1][1] = s.snapshot()
                    elif op[0] == "restore":
                        s.restore(snaps[op[1]][idx])
                    elif op[0] == "kick":
                        kick(s, op[1], op[2])
                    elif op[0] == "read":
                        try:
                            out.append((s.is_finite(), repr(s.metrics())))
                        except (OverflowError, ValueError) as e:   # (a 1e300 kick's metrics)
                            out.append(repr(e))
                    elif op[0] == "reset":
                        s.reset()
                    out.append("ok")
                except ParamError as e:
                    out.append(("ParamError", str(e)))
            if not same(outs[0], outs[1]):
                print(f"DIFF seed={seed} step={i} op={op}: {outs}")
                return 1
        ew = eg = None
        before = general_adv[0]
        try:
            w.advance()
        except Exception as e:  # noqa: BLE001
            ew = repr(e)
        try:
            g.advance()
        except Exception as e:  # noqa: BLE001
            eg = repr(e)
        general_adv[1] += general_adv[0] == before
        if ew != eg:
            print(f"DIFF seed={seed} step={i} exceptions: written {ew} general {eg}")
            return 1
        a, b = observe(w), observe(g)
        if not same(a, b):
            names = ["counts", "record", "time", "steps", "balls", "xy", "hash", "resting", "seen"]
            bad = [n for n, x, y in zip(names, a, b) if not same(x, y)]
            print(f"DIFF seed={seed} step={i} ops={ops} in {bad}: "
                  f"{[(x, y) for n, x, y in zip(names, a, b) if n in bad and n != 'xy']}")
            print("  settings", w.p, sorted(w.on))
            return 1
        if "sleeping" not in w.on and (w.space.sleep_time_threshold != math.inf
                                       or w.resting and w.balls):
            print(f"SLEEPS seed={seed} step={i}: sleeping off, threshold "
                  f"{w.space.sleep_time_threshold}, resting {w.resting}")
            return 1
        h.update(repr(a).encode())
        if ew:
            h.update(ew.encode())
    if trace_file:
        with open(trace_file, "a") as f:
            f.write(f"{scene_name} {seed} {h.hexdigest()[:16]}\n")
    print(f"ok {scene_name} seed={seed} steps={steps} balls={len(w.balls)} "
          f"counts={w.counts} ops={mode_counts['ops']} written_out={general_adv[1]} "
          f"trace={h.hexdigest()[:16]}")
    return 0


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    trace = None
    if "--trace" in sys.argv:
        trace = sys.argv[sys.argv.index("--trace") + 1]
        args.remove(trace)
    name, seed = args[0], int(args[1])
    n = int(args[2]) if len(args) > 2 else 600
    print(f"seed {seed}")
    sys.exit(run(name, seed, n, trace))
