#!/usr/bin/env python3
"""Hostile command lines against the lab's command-line contract (issue 27), kept out of the
test suite: a few hundred seeded `python -m app ...` runs, each in its own temporary folder.

    python tools/hostile.py                      # ~600 cases, a new seed (printed)
    python tools/hostile.py --seed 27 --jobs 2   # the same cases again
    python tools/hostile.py --seed 27 --only csv --verbose   # the cases whose id holds 'csv'
    python tools/hostile.py --seed 27 --list     # the command lines, not run
    python tools/hostile.py --seed 27 --repo /work/main   # another checkout (before/after)

Every option of the contract (docs/reference.md; `python -m app --help` and each subcommand's
--help) meets NaN, inf, 0, negatives, 1e308, 5e-324, empty, 100k-character, unicode and control
character values, unknown names, and paths that are a folder, a FIFO, /dev/null, /dev/full, a
full disk (a tiny tmpfs, when this process may mount one), a path under a file, /proc, a missing
folder, an existing file, one path for two outputs, an output that is also an input. A few long
runs get SIGINT at a random time, as Ctrl-C sends it (to the whole process group).

The contract checked on every run:
- exit 0 (or 1: the simulation went non-finite, a student's answer failed), with every file it
  promised, non-empty, and its summary saying when it replaced a file; or exit 2 with exactly one
  line on stderr, `python -m app...: error: ...`, at most 300 characters, no raw control
  character; never a traceback, never a signal's death (pymunk's abort), never ffmpeg's log;
- `--json`'s stdout is strict JSON (no NaN, no Infinity);
- an interrupted run exits 130 with one line;
- no temporary file left (`*.part*`, `.probe.*`), an existing output untouched unless exit 0,
  inputs never changed;
- no run past the timeout, no process left behind (same process group, or a working folder
  inside the case's folder).

It prints the seed, each breach (id, kind, command shortened, stderr's first line), and a summary:
cases, held, broke by kind. Exit code 0 if every case held, 1 otherwise.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILES = os.path.join(ROOT, "scenes", "files")
LONG = 100_000
SENTINEL = b"EXISTING FILE: must stay as it was unless the run exits 0\n"

# --- values -----------------------------------------------------------------------------------

NUMBERS = ["nan", "NaN", "-nan", "inf", "-inf", "Infinity", "0", "-0", "-1", "-7.5", "1e308",
           "-1e308", "1e309", "1e-308", "5e-324", "", " ", "0x10", "1_0", "\u0661\u0662",
           "\uff15", "3\n", "3\x1b[31m", "3\t", "abc", "None", "+5", " 7 ", "1e3", "2.5",
           "9" * 400, "9" * LONG, "x" * LONG, "1" + "0" * 30, "0.000001", "\u00b2", "1/2",
           "--", "-", "\u202e5"]
NAMES = ["nosuch", "", " ", "x" * LONG, "\u00fcn\u00efc\u00f6d\u00e9", "\u540d\u524d",
         "a\nb", "a\rb", "\x1b[2J\x1b[31mred", "../../etc/passwd", "-", "--json", "ALL",
         "cloth ", "%s%n{}", "\u202eevil", "a" * 300, "\t", "\x7f", "'\"", "\\", "\udcff"]
SCENES = ["cloth", "cloth_collisions", "mass_spring_cloth", "mass_spring_collisions",
          "trampoline", "falling_balls", "pivoting_l", "newtons_cradle", "double_pendulum",
          "integrators", "particle_dance", "sandbox"]
EXERCISES = ["verlet", "constraints", "spring", "rk4", "solver_interface", "implicit_spring",
             "neighbour_grid", "newtons_cradle", "double_pendulum", "pivoting_l", "collisions"]


def catalogue() -> list[dict]:
    r = subprocess.run([sys.executable, "-m", "app", "--list", "--json"], cwd=ROOT,
                       capture_output=True, text=True, env=env_for(), timeout=120)
    return json.loads(r.stdout)


def env_for() -> dict:
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy",
               PYTHONPATH=ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""),
               PYGAME_HIDE_SUPPORT_PROMPT="1")
    env.pop("PHYSICS_LAB_PROGRESS", None)
    return env


# --- a case -----------------------------------------------------------------------------------

@dataclass
class Case:
    id: str
    argv: list
    expect: frozenset = frozenset({0, 1, 2})   # exit codes the contract allows here
    setup: dict = field(default_factory=dict)   # name -> bytes | 'dir' | 'fifo' | ('link', t)
    outputs: list = field(default_factory=list)  # files the run promises on exit 0
    guarded: list = field(default_factory=list)  # existing files: untouched unless exit 0
    inputs: list = field(default_factory=list)   # files that must never change
    sigint: float | None = None                  # seconds after start: send SIGINT
    full: bool = False                           # needs the full-disk folder FULL/
    words: tuple = ()                            # words the error line must hold


def shorten(text: str, n: int = 160) -> str:
    text = repr(text)
    return text if len(text) <= n else text[:n // 2] + f"...({len(text)})..." + text[-n // 2:]


# --- the generators: each returns a list of cases -----------------------------------------------

def quick_run(rng, scene=None):
    scene = scene or rng.choice(["cloth", "integrators", "falling_balls", "pivoting_l",
                                 "newtons_cradle", "particle_dance", "double_pendulum"])
    return ["--headless", "--scene", scene, "--steps", str(rng.choice([2, 3, 5]))]


def gen_numbers(rng, cat):
    """Every numeric option with every hostile number."""
    out = []
    opts = [
        ("seconds", lambda v: ["--headless", "--scene", "integrators", "--seconds", v, "--json"]),
        ("steps", lambda v: ["--headless", "--scene", "cloth", "--steps", v, "--json"]),
        ("fps", lambda v: quick_run(rng) + ["--video", "o.gif", "--fps", v]),
        ("width", lambda v: quick_run(rng) + ["--screenshot", "o.png", "--width", v]),
        ("size", lambda v: ["--scene", "cloth", "--size", v, "--screenshot", "o.png",
                            "--seconds", "0.3"]),
        ("ex-timeout", lambda v: ["exercise", "check", "verlet", "--reference", "--timeout", v]),
        ("ex-seed", lambda v: ["exercise", "check", "spring", "--reference", "--seed", v]),
        ("grade-jobs", lambda v: ["exercise", "grade", "class", "--jobs", v, "--timeout", "20"]),
        ("grade-seed", lambda v: ["exercise", "grade", "class", "--seed", v]),
        ("grade-timeout", lambda v: ["exercise", "grade", "class", "--timeout", v]),
    ]
    for name, make in opts:
        values = rng.sample(NUMBERS, 9 if name.startswith("grade") else 14)
        for v in values:
            setup = {"class/alice/verlet.py": open(os.path.join(ROOT, "exercises",
                                                                "verlet.py"), "rb").read()} \
                if name.startswith("grade") else {}
            out.append(Case(f"num-{name}-{v[:12]!r}", make(v), setup=setup))
    # --set on every scene's parameters, with hostile numbers (the pymunk abort guard)
    for sc in cat:
        params = [p for p in sc["params"] if p["kind"] in ("int", "float")]
        for p in rng.sample(params, min(3, len(params))):
            v = rng.choice(NUMBERS[:16] + ["1e308", "-1e308", "5e-324", "nan"])
            scene = sc["name"] if "/" not in sc["name"] else os.path.join(ROOT, sc["name"])
            out.append(Case(f"set-{os.path.basename(sc['name'])}-{p['name']}-{v[:10]!r}",
                            ["--headless", "--scene", scene, "--steps", "3", "--set",
                             f"{p['name']}={v}", "--json"]))
        # the extremes of the accepted range: must run (0 or 1), never crash
        for p in rng.sample(params, min(2, len(params))):
            lo, hi = p["range"]
            scene = sc["name"] if "/" not in sc["name"] else os.path.join(ROOT, sc["name"])
            for v in (lo, hi):
                out.append(Case(f"edge-{os.path.basename(sc['name'])}-{p['name']}-{v}",
                                ["--headless", "--scene", scene, "--steps", "4", "--set",
                                 f"{p['name']}={v}", "--json"]))   # 2: a cross-check
        for e in sc["effects"][:2]:
            v = rng.choice(["maybe", "", "ON", "1", "nan", "x" * LONG, "on\n"])
            scene = sc["name"] if "/" not in sc["name"] else os.path.join(ROOT, sc["name"])
            out.append(Case(f"effect-{os.path.basename(sc['name'])}-{e['name']}-{v[:8]!r}",
                            ["--headless", "--scene", scene, "--steps", "2", "--set",
                             f"{e['name']}={v}"]))
    # the mass-spring solver, integrator and CG options: every choice, with stiff extremes
    for solver in ["cg", "direct", "nosuch", "", "CG", "direct\n"]:
        for integ in rng.sample(["implicit_euler", "symplectic_euler", "rk4", "euler", "x"], 2):
            out.append(Case(f"solver-{solver!r}-{integ}",
                            ["--headless", "--scene", "mass_spring_cloth", "--steps", "3",
                             "--set", f"solver={solver}", "--set", f"integrator={integ}",
                             "--set", "rows=8", "--set", "cols=8", "--json"]))
    return out


def gen_names(rng, cat):
    """Every option that takes a name: --scene, --try, --plot, --set KEY, --compare, bench,
    exercise check NAME, exercise copy, scene check."""
    out = []
    for v in NAMES:
        out += [
            Case(f"scene-{v[:10]!r}", ["--headless", "--scene", v, "--steps", "2"], words=()),
            Case(f"try-{v[:10]!r}", ["--headless", "--scene", "cloth", "--try", v,
                                     "--steps", "2"]),
            Case(f"plot-{v[:10]!r}", quick_run(rng) + ["--plot", v, "--screenshot", "p.png"]),
            Case(f"setkey-{v[:10]!r}", quick_run(rng) + ["--set", f"{v}=1"]),
            Case(f"compare-{v[:10]!r}", ["--headless", "--scene", "cloth", "--steps", "2",
                                         "--compare", v, "iterations=3"]),
            Case(f"bench-{v[:10]!r}", ["bench", v, "--quick", "--out", "b"]),
            Case(f"excheck-{v[:10]!r}", ["exercise", "check", v]),
            Case(f"sub-{v[:10]!r}", [v] if v else ["", "--help"]),
        ]
    # the tries and comparisons of real scenes, as a click applies them, with outputs
    for sc in rng.sample([c for c in cat if c["tries"] or c["comparisons"]], 6):
        card = rng.choice(sc["tries"] + sc["comparisons"])
        scene = sc["name"] if "/" not in sc["name"] else os.path.join(ROOT, sc["name"])
        out.append(Case(f"card-{os.path.basename(sc['name'])}",
                        ["--headless", "--scene", scene, "--try", card["label"], "--steps", "3",
                         "--json", "--screenshot", "c.png", "--csv", "c.csv"],
                        expect=frozenset({0, 1}), outputs=["c.png"]))
    # compare specs
    for spec in ["iterations=2", "iterations=2,substeps=nan", "iterations=", "=3", ",",
                 "iterations=2,iterations=3", "hertz=1e308", "nosuch=1", "gravity=off",
                 "x" * LONG + "=1", "iterations=2\n,substeps=3"]:
        for n in (1, 2, 5):
            out.append(Case(f"cmp-{spec[:16]!r}-{n}",
                            ["--headless", "--scene", "cloth", "--steps", "2", "--json",
                             "--compare", *([spec] + ["iterations=4"] * (n - 1))]))
    for p in ["max_stretch", "max_stretch,max_stretch", "max_stretch,", ",", "a,b,c,d,e",
              "mean_stretch,max_stretch,pinned_drift,torn,particles"]:
        out.append(Case(f"plotlist-{p[:14]!r}", ["--headless", "--scene", "cloth", "--steps",
                                                 "3", "--plot", p, "--screenshot", "p.png"]))
    return out


OUT_KINDS = ["plain", "dir", "fifo", "devnull", "devfull", "underfile", "proc", "missingdir",
             "existing", "empty", "space", "newline", "escape", "long", "name300", "unicode",
             "noext", "badext", "full", "fullexisting", "dash", "trailingslash", "symlinkdir",
             "dotdot", "invalidutf8"]


# the kinds whose path needs nothing made beforehand: the path, "{ext}" replaced by the output's
# extension
PLAIN_PATHS = {
    "plain": "out{ext}", "devnull": "/dev/null", "devfull": "/dev/full", "proc": "/proc/x{ext}",
    "missingdir": "new/sub/x{ext}", "empty": "", "space": " ", "newline": "a\nb{ext}",
    "escape": "\x1b[31mred{ext}", "long": "y" * LONG + "{ext}", "name300": "z" * 300 + "{ext}",
    "unicode": "\u00fcn\u00efc\u00f6d\u00e9 \u540d{ext}", "noext": "out", "badext": "out.txt",
    "full": "FULL/x{ext}", "dash": "-", "trailingslash": "out{ext}/",
    "dotdot": "../" * 40 + "x{ext}",
}


def out_path(kind: str, ext: str, setup: dict, guarded: list) -> str | bytes:
    """A path of `kind` for an output ending in `ext`, with what it needs made in setup."""
    if kind in PLAIN_PATHS:
        return PLAIN_PATHS[kind].replace("{ext}", ext)
    if kind == "dir":
        setup["adir"] = "dir"
        return "adir"
    if kind == "fifo":
        setup["fifo" + ext] = "fifo"
        return "fifo" + ext
    if kind == "underfile":
        setup["afile"] = b"a file\n"
        return "afile/x" + ext
    if kind == "existing":
        setup["old" + ext] = SENTINEL
        guarded.append("old" + ext)
        return "old" + ext
    if kind == "fullexisting":
        guarded.append("FULL/old" + ext)
        return "FULL/old" + ext
    if kind == "symlinkdir":
        setup["linkdir"] = ("link", "/proc")
        return "linkdir/x" + ext
    if kind == "invalidutf8":
        return b"bad\xff" + ext.encode()
    raise ValueError(kind)


def gen_outputs(rng, cat):
    """Every output option with every hostile path."""
    out = []
    makers = [
        ("csv", ".csv", lambda p: quick_run(rng) + ["--csv", p]),
        ("shot", ".png", lambda p: quick_run(rng) + ["--screenshot", p]),
        ("gif", ".gif", lambda p: quick_run(rng) + ["--video", p]),
        ("mp4", ".mp4", lambda p: quick_run(rng, "integrators") + ["--video", p]),
        ("cmpshot", ".png", lambda p: ["--headless", "--scene", "cloth", "--steps", "2",
                                       "--compare", "iterations=2", "iterations=9",
                                       "--screenshot", p]),
        ("cmpcsv", ".csv", lambda p: ["--headless", "--scene", "integrators", "--steps", "3",
                                      "--compare", "hertz=30", "hertz=60", "--csv", p]),
        ("record", ".json", lambda p: ["--scene", "cloth", "--screenshot", "w.png",
                                       "--seconds", "0.3", "--record", p]),
        ("winshot", ".png", lambda p: ["--scene", "falling_balls", "--seconds", "0.3",
                                       "--screenshot", p]),
        ("wincsv", ".csv", lambda p: ["--scene", "pivoting_l", "--seconds", "0.3",
                                      "--screenshot", "w.png", "--csv", p]),
        ("benchout", "", lambda p: ["bench", "integrators", "--quick", "--out", p]),
        ("gradeout", ".csv", lambda p: ["exercise", "grade", "class", "--out", p]),
        ("copy", "", lambda p: ["exercise", "copy", p]),
    ]
    for name, ext, make in makers:
        kinds = OUT_KINDS if name in ("csv", "shot", "gif", "mp4") else \
            rng.sample(OUT_KINDS, 12 if name not in ("benchout", "gradeout") else 8)
        for kind in kinds:
            setup, guarded = {}, []
            path = out_path(kind, ext, setup, guarded)
            if name == "gradeout":
                setup["class/alice/verlet.py"] = open(os.path.join(ROOT, "exercises",
                                                                   "verlet.py"), "rb").read()
            argv = make(path)
            promised = [path] if kind in ("plain", "missingdir", "existing", "unicode") and \
                name not in ("benchout", "copy") else []
            # bench's --out is a folder: an existing file there is bad usage (exit 2), the
            # file kept (`guarded` checks that)
            must_run = kind == "plain" and name != "copy" or \
                kind == "existing" and name not in ("copy", "benchout")
            out.append(Case(f"out-{name}-{kind}", argv, setup=setup, guarded=guarded,
                            outputs=promised, full=kind.startswith("full"),
                            expect=frozenset({0, 1}) if must_run else frozenset({0, 1, 2})))
    # --scene all: an output per scene
    for opt, ext in (("--screenshot", ".png"), ("--csv", ".csv"), ("--video", ".gif")):
        out.append(Case(f"all{opt}", ["--headless", "--scene", "all", "--steps", "2", opt,
                                      "all" + ext], expect=frozenset({0, 1})))
    return out


def gen_clashes(rng, cat):
    """One path for two outputs; an output that is also an input; a link to an input."""
    events = b'[{"t": 0.05, "type": "key_down", "key": "r"}]'
    toml = open(os.path.join(FILES, "pivoting_l.toml"), "rb").read()
    verlet = open(os.path.join(ROOT, "exercises", "verlet.py"), "rb").read()
    base = quick_run(rng, "pivoting_l")
    C = []

    def c(cid, argv, setup=None, inputs=(), guarded=()):
        C.append(Case(f"clash-{cid}", argv, expect=frozenset({2}), setup=setup or {},
                      inputs=list(inputs), guarded=list(guarded)))

    c("csv=shot", base + ["--csv", "same.png", "--screenshot", "same.png"])
    c("csv=video", base + ["--csv", "same.gif", "--video", "same.gif"])
    c("shot=video", base + ["--screenshot", "same.gif", "--video", "same.gif"])
    c("csv=shot-dot", base + ["--csv", "./same.png", "--screenshot", "same.png"])
    c("csv=shot-abspath", base + ["--csv", "sub/../same.png", "--screenshot", "same.png"])
    c("csv=input", base + ["--csv", "ev.json", "--input", "ev.json"], {"ev.json": events},
      ["ev.json"])
    c("shot=input", base + ["--screenshot", "ev.json", "--input", "ev.json"],
      {"ev.json": events}, ["ev.json"])
    c("video=input", base + ["--video", "ev.gif", "--input", "ev.gif"], {"ev.gif": events},
      ["ev.gif"])
    c("csv=symlink-input", base + ["--csv", "l.csv", "--input", "ev.json"],
      {"ev.json": events, "l.csv": ("link", "ev.json")}, ["ev.json"])
    c("csv=hardlink-input", base + ["--csv", "h.csv", "--input", "ev.json"],
      {"ev.json": events, "h.csv": ("hardlink", "ev.json")}, ["ev.json"])
    c("csv=scenefile", ["--headless", "--scene", "s.toml", "--steps", "2", "--csv", "s.toml"],
      {"s.toml": toml}, ["s.toml"])
    c("shot=scenefile", ["--headless", "--scene", "s.toml", "--steps", "2", "--screenshot",
                         "s.toml"], {"s.toml": toml}, ["s.toml"])
    c("video=scenefile", ["--headless", "--scene", "s.toml", "--steps", "2", "--video",
                          "s.toml"], {"s.toml": toml}, ["s.toml"])
    c("csv=scenefile-symlink", ["--headless", "--scene", "s.toml", "--steps", "2", "--csv",
                                "l.csv"], {"s.toml": toml, "l.csv": ("link", "s.toml")},
      ["s.toml"])
    c("csv=exercisefile", ["--headless", "--scene", "exercise:v/verlet.py", "--steps", "2",
                           "--csv", "v/verlet.py"], {"v/verlet.py": verlet}, ["v/verlet.py"])
    c("record=input", ["--scene", "cloth", "--seconds", "0.3", "--screenshot", "w.png",
                       "--input", "ev.json", "--record", "ev.json"], {"ev.json": events},
      ["ev.json"])
    c("record=shot", ["--scene", "cloth", "--seconds", "0.3", "--screenshot", "w.png",
                      "--record", "w.png"])
    c("record=csv", ["--scene", "cloth", "--seconds", "0.3", "--screenshot", "w.png",
                     "--csv", "r.json", "--record", "r.json"])
    c("all-shot=csv", ["--headless", "--scene", "all", "--steps", "2", "--screenshot", "a.png",
                       "--csv", "a.png"])
    c("all-shot=video", ["--headless", "--scene", "all", "--steps", "2", "--screenshot",
                         "a.gif", "--video", "a.gif"])
    c("grade-out=student", ["exercise", "grade", "class", "--out", "class/alice/verlet.py"],
      {"class/alice/verlet.py": verlet}, ["class/alice/verlet.py"])
    c("grade-out=class", ["exercise", "grade", "class", "--out", "class"],
      {"class/alice/verlet.py": verlet}, ["class/alice/verlet.py"])
    c("copy=file", ["exercise", "copy", "v.py"], {"v.py": verlet}, ["v.py"])
    c("copy-existing", ["exercise", "copy", "mywork"], {"mywork/verlet.py": b"# mine\n"},
      ["mywork/verlet.py"])
    c("bench-out=file", ["bench", "integrators", "--quick", "--out", "f.txt"],
      {"f.txt": b"mine\n"}, ["f.txt"])
    c("csv=shot-case", base + ["--csv", "ev.json", "--screenshot", "ev.json", "--input",
                               "ev.json"], {"ev.json": events}, ["ev.json"])
    c("csv=input-dev-stdin", base + ["--csv", "/dev/stdin", "--input", "/dev/stdin"])
    c("path=ex-check-fifo", ["exercise", "check", "verlet", "--path", "f.py"], {"f.py": "fifo"})
    return C


def gen_inputs(rng, cat):
    """--input, --scene FILE.toml, scene check, exercise check --path: hostile files."""
    good_toml = open(os.path.join(FILES, "pivoting_l.toml"), encoding="utf-8").read()
    verlet = open(os.path.join(ROOT, "exercises", "verlet.py"), "rb").read()
    files = {
        "missing": None, "dir": "dir", "fifo": "fifo", "devnull": "/dev/null",
        "devzero": "/dev/zero", "devstdin": "/dev/stdin", "empty": b"", "binary": bytes(
            range(256)) * 8, "proc": "/proc/self/status", "loop": ("link", "loop.x"),
        "long": "q" * LONG, "newline": "a\nb.x", "utf8bad": b"bad\xff.x",
        "bigjson": b"[" + b'{"t": 0.01, "type": "key_down", "key": "r"},' * 200000 +
                   b'{"t": 0.02, "type": "key_up", "key": "r"}]',
    }
    events = [b'[{"t": NaN, "type": "key_down", "key": "r"}]',
              b'[{"t": Infinity, "type": "key_down", "key": "r"}]',
              b'[{"t": 1e308, "type": "key_down", "key": "r"}]',
              b'[{"t": -1, "type": "key_down", "key": "r"}]',
              b'[{"t": 0, "type": "mouse_down", "button": 1, "pos": [1e308, -1e308]}]',
              b'[{"t": 0, "type": "mouse_down", "button": 1, "pos": [NaN, 0]}]',
              b'[{"t": 0, "type": "mouse_down", "button": 99, "pos": [1, 1]}]',
              b'[{"t": 0, "type": "key_down", "key": "\\u0000"}]',
              b'[{"t": 0, "type": "key_down", "key": "' + b"k" * 5000 + b'"}]',
              b'[{"t": 0, "type": "nosuch"}]', b'{"t": 0}', b'[]', b'[1, 2]', b'null',
              b'[{"t": 0, "type": "key_down", "key": "r", "extra\\n": 1}]',
              b'\xef\xbb\xbf[]', b'[{"t": 0, "type": "key_down", "key": "r"}',
              b'[{"t": 0.01, "type": "mouse_move", "pos": [5, 5]}]',
              b'[{"t": 0, "type": "mouse_down", "button": 1, "pos": [400, 300]},'
              b' {"t": 0.03, "type": "mouse_move", "pos": [1e9, 1e9]},'
              b' {"t": 0.05, "type": "mouse_up", "button": 1, "pos": [400, 300]}]']
    out = []

    def path_and_setup(kind, ext):
        setup = {}
        v = files[kind]
        if v is None:
            return "missing" + ext, setup
        if isinstance(v, bytes):
            setup["in" + ext] = v
            return "in" + ext, setup
        if v in ("dir", "fifo"):
            setup["in" + ext] = v
            return "in" + ext, setup
        if isinstance(v, tuple):
            setup["loop.x"] = ("link", "loop.x")
            return "loop.x", setup
        if kind in ("long", "newline"):
            return v + ext, setup
        if kind == "utf8bad":
            return v + ext.encode(), setup
        return v, setup

    for kind in files:
        p, s = path_and_setup(kind, ".json")
        out.append(Case(f"input-{kind}", quick_run(rng) + ["--input", p], setup=s))
        p, s = path_and_setup(kind, ".toml")
        out.append(Case(f"scenefile-{kind}", ["--headless", "--scene", p, "--steps", "2"],
                        setup=s))
        p, s = path_and_setup(kind, ".toml")
        out.append(Case(f"scenecheck-{kind}", ["scene", "check", p], setup=s))
        p, s = path_and_setup(kind, ".py")
        out.append(Case(f"expath-{kind}", ["exercise", "check", "verlet", "--path", p,
                                           "--timeout", "10"], setup=s))
        p, s = path_and_setup(kind, ".py")
        out.append(Case(f"exscene-{kind}", ["--headless", "--scene", f"exercise:{p}" if
                                            isinstance(p, str) else b"exercise:" + p,
                                            "--steps", "2"], setup=s))
    for i, ev in enumerate(events):
        out.append(Case(f"events-{i}", ["--headless", "--scene", rng.choice(
            ["cloth", "falling_balls", "sandbox", "particle_dance"]), "--steps", "6",
            "--input", "ev.json", "--json"], setup={"ev.json": ev}, inputs=["ev.json"]))
    # scene files with one value made hostile (TOML holds nan and inf)
    shipped = sorted(f for f in os.listdir(FILES) if f.endswith(".toml"))
    num = re.compile(r"(?<=[=\[, ])-?\d+(\.\d+)?(?=[\],\s])")
    for i in range(60):
        name = rng.choice(shipped)
        text = open(os.path.join(FILES, name), encoding="utf-8").read()
        spots = [m for m in num.finditer(text)]
        if not spots:
            continue
        m = rng.choice(spots)
        v = rng.choice(["nan", "inf", "-inf", "1e308", "-1e308", "0", "-1", "5e-324", "1e9",
                        "0.0", "-0.0", "1e-9", "\"x\"", "[]", "{}", "true", "99999999999999"
                        "99999999999", "\"" + "s" * LONG + "\""])
        hostile = text[:m.start()] + v + text[m.end():]
        line = text.count("\n", 0, m.start()) + 1
        argv = (["scene", "check", "h.toml"] if i % 3 == 0 else
                ["--headless", "--scene", "h.toml", "--steps", "5", "--json"])
        out.append(Case(f"toml-{name[:-5]}-L{line}-{v[:8]}", argv,
                        setup={"h.toml": hostile.encode()}, inputs=["h.toml"]))
    # structural hostility in scene files
    for j, text in enumerate([
            "", "[[[[", "x = " + "[" * 5000 + "]" * 5000, "title = \"" + "t" * LONG + "\"",
            good_toml + "\n[extra]\nfoo = 1\n", good_toml.replace("[", "[ ", 1),
            "\ufeff" + good_toml, good_toml + "\nnosuch = \"\x1b[31m\"\n",
            good_toml * 2]):
        out.append(Case(f"tomlshape-{j}", ["--headless", "--scene", "h.toml", "--steps", "3"],
                        setup={"h.toml": text.encode("utf-8", "surrogatepass")}))
    # student files that misbehave (the sandbox's job; the command line must stay whole)
    for k, src in enumerate([b"def verlet_step(*a, **k):\n    while True: pass\n",
                             b"print('x' * 10_000_000)\n", b"import os\nos._exit(0)\n",
                             b"raise SystemExit('\\n' * 1000)\n", b"def (:\n",
                             b"import sys\nsys.stderr.write('\\x1b[2J' * 1000)\n",
                             b"\xff\xfe\x00bad", verlet + b"\nimport signal, os\n"
                             b"os.kill(os.getppid(), signal.SIGINT)\n"]):
        out.append(Case(f"student-{k}", ["exercise", "check", "verlet", "--path", "s.py",
                                         "--timeout", "3"], setup={"s.py": src},
                        inputs=["s.py"]))
    return out


def gen_misc(rng, cat):
    """Options that do not fit together, flags given twice, options without values."""
    argvs = [
        ["--headless"], ["--headless", "--scene"], ["--scene", "cloth", "--headless", "--steps",
                                                    "2", "--seconds", "1"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--record", "r.json"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--size", "800x600"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--fullscreen"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--clean"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--fps", "10"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--width", "640"],
        ["--scene", "cloth", "--clean", "--screenshot", "a.png", "--seconds", "0.2"],
        ["--scene", "cloth", "--steps", "3"], ["--scene", "cloth", "--json"],
        ["--list", "--scene", "nosuch"], ["--list", "--json", "--csv", "x.csv"],
        ["--set", "iterations=3"], ["--try", "x"], ["--headless", "--scene", "all", "--try", "x"],
        ["--headless", "--scene", "cloth", "--try", "Stretchy: 2 iterations", "--set",
         "iterations=4"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--set", "iterations=3", "--set",
         "iterations=4"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--set", "iterations"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--set", "="],
        ["--headless", "--scene", "cloth", "--steps", "2", "--compare"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--compare", "a=1", "b=2", "c=3",
         "d=4", "e=5"],
        ["--headless", "--scene", "all", "--compare", "hertz=30", "hertz=60", "--steps", "2"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--plot"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--plot", "max_stretch"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--arrows"],
        ["--headless", "--scene", "cloth", "--steps", "2", "--arrows", "--screenshot", "a.png",
         "--plot", "max_stretch", "--clean"],
        ["--headless", "--scene", "sandbox", "--steps", "2", "--screenshot", "a.png"],
        ["--headless", "--scene", "cloth", "--steps", "1000000000"],
        ["--headless", "--scene", "cloth", "--seconds", "1e-300", "--json"],
        ["--headless", "--scene", "cloth", "--steps", "1", "--video", "a.gif"],
        ["--headless", "--scene", "integrators", "--seconds", "400", "--video", "a.gif"],
        ["--headless", "--scene", "integrators", "--steps", "2", "--video", "a.gif", "--fps",
         "1", "--width", "16"],
        ["--headless", "--scene", "integrators", "--steps", "2", "--screenshot", "a.png",
         "--width", "100000"],
        ["--headless", "--scene", "exercise:verlet", "--steps", "3", "--json"],
        ["--headless", "--scene", "exercise:", "--steps", "3"],
        ["--headless", "--scene", "exercise:nosuch", "--steps", "3"],
        ["--headless", "--scene", "exercise:/dev/null", "--steps", "3"],
        ["--headless", "--scene", "exercise:x.py", "--steps", "3"],
        ["bench"] + ["--quick", "--full", "--out", "b"], ["bench", "--json", "--quick",
                                                          "integrators", "--out", "b"],
        ["bench", "nosuch", "--out", "b"], ["bench", "integrators", "--quick", "--out", ""],
        ["bench", "integrators", "--quick", "--out", "b", "extra"],
        ["exercise"], ["exercise", "nosuch"], ["exercise", "check"],
        ["exercise", "check", "verlet", "--reference", "--path", "x.py"],
        ["exercise", "check", "all", "--path", "nosuchdir"],
        ["exercise", "check", "verlet", "--path", ""],
        ["exercise", "check", "all", "--reference", "--json", "--seed", "7"],
        ["exercise", "list", "--json"], ["exercise", "copy"], ["exercise", "copy", ""],
        ["exercise", "grade"], ["exercise", "grade", ""], ["exercise", "grade", "nosuch"],
        ["exercise", "grade", "emptyclass"], ["exercise", "grade", "class", "--gradescope"],
        ["scene"], ["scene", "check"], ["scene", "nosuch"],
        ["scene", "check", os.path.join(FILES, "seesaw.toml"), "missing.toml"],
        ["--help"], ["bench", "--help"], ["exercise", "--help"], ["exercise", "check", "--help"],
        ["exercise", "grade", "--help"], ["scene", "check", "--help"],
        ["--scen", "cloth"], ["--headless", "--scene", "cloth", "--steps", "2", "--jso"],
        ["--version"], ["-h", "extra"],
    ]
    out = []
    setup = {"class/alice/verlet.py": open(os.path.join(ROOT, "exercises", "verlet.py"),
                                           "rb").read(), "emptyclass": "dir"}
    for i, argv in enumerate(argvs):
        out.append(Case(f"misc-{i}-{' '.join(argv)[:30]}", argv, setup=dict(setup)))
    return out


def gen_sigint(rng, cat):
    """Long runs interrupted as Ctrl-C does, at a random time; an existing output must stay."""
    long_runs = [
        ("csv", ["--headless", "--scene", "cloth", "--seconds", "60", "--csv", "old.csv"],
         "old.csv"),
        ("gif", ["--headless", "--scene", "integrators", "--seconds", "10", "--video",
                 "old.gif"], "old.gif"),
        ("mp4", ["--headless", "--scene", "integrators", "--seconds", "30", "--video",
                 "old.mp4"], "old.mp4"),
        ("shot", ["--headless", "--scene", "mass_spring_cloth", "--seconds", "60",
                  "--screenshot", "old.png"], "old.png"),
        ("cmp", ["--headless", "--scene", "cloth", "--seconds", "60", "--compare",
                 "iterations=2", "iterations=20", "--csv", "old.csv"], "old.csv"),
        ("all", ["--headless", "--scene", "all", "--seconds", "5", "--json", "--csv",
                 "old.csv"], None),
        ("bench", ["bench", "cloth", "--quick", "--out", "b"], None),
        ("check", ["exercise", "check", "all", "--reference"], None),
        # the gradebook is rewritten after each student on purpose (the same command goes on
        # from there): not guarded, only checked for temporary files
        ("grade", ["exercise", "grade", "class", "--out", "book.csv"], None),
        ("window", ["--scene", "cloth", "--seconds", "30", "--screenshot", "old.png",
                    "--record", "old.json"], "old.png"),
    ]
    out = []
    for name, argv, guarded in long_runs:
        for k in range(3):
            t = round(rng.uniform(0.05, 4.0) if k else rng.uniform(0.0, 0.6), 2)
            setup = {"class/alice/verlet.py": open(os.path.join(ROOT, "exercises", "verlet.py"),
                                                   "rb").read()}
            if guarded:
                setup[guarded] = SENTINEL
            if name == "window":      # Ctrl-C closes the window as Esc does: the recording
                setup["old.json"] = SENTINEL     # is saved (and says it replaced a file)
            out.append(Case(f"sigint-{name}-{t}", argv, setup=setup,
                            guarded=[guarded] if guarded else [], sigint=t,
                            expect=frozenset({0, 1, 130})))
    return out


GENERATORS = [gen_numbers, gen_names, gen_outputs, gen_clashes, gen_inputs, gen_misc,
              gen_sigint]


def build_cases(seed: int, n: int) -> list[Case]:
    rng = random.Random(seed)
    cat = catalogue()
    cases = [c for g in GENERATORS for c in g(rng, cat)]
    keep = [c for c in cases if c.sigint is not None or c.id.startswith("clash-")]
    rest = [c for c in cases if c not in keep]
    rng.shuffle(rest)
    cases = keep + rest[:max(0, n - len(keep))]
    seen = Counter()
    for c in cases:          # ids unique (the report names them)
        seen[c.id] += 1
        if seen[c.id] > 1:
            c.id += f"#{seen[c.id]}"
    return cases


# --- running one case ---------------------------------------------------------------------------

def make_setup(folder: str, case: Case) -> str | None:
    """Make the case's files; return the full-disk folder's path, or None."""
    full = None
    if case.full:
        full = os.path.join(folder, "FULL")
        os.makedirs(full)
        if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", full],
                          capture_output=True).returncode != 0:
            return "unmountable"
        for g in case.guarded:
            if g.startswith("FULL/"):
                with open(os.path.join(folder, g), "wb") as f:
                    f.write(SENTINEL)
        try:                        # fill it: every write from here on fails with ENOSPC
            with open(os.path.join(full, "filler"), "wb") as f:
                while True:
                    f.write(b"\0" * 4096)
                    f.flush()
        except OSError:
            pass
    for name, v in case.setup.items():
        p = os.path.join(folder, name)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        if v == "dir":
            os.makedirs(p, exist_ok=True)
        elif v == "fifo":
            os.mkfifo(p)
        elif isinstance(v, tuple) and v[0] == "link":
            os.symlink(v[1], p)
        elif isinstance(v, tuple) and v[0] == "hardlink":
            os.link(os.path.join(folder, v[1]), p)
        else:
            with open(p, "wb") as f:
                f.write(v if isinstance(v, bytes) else v.encode())
    return full


def digest(path: str) -> str | None:
    try:
        if not os.path.isfile(path):
            return None
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return None


def arg_for(a, full):
    if isinstance(a, str) and a.startswith("FULL/") and full:
        return os.path.join(full, a[5:])
    return a


def lingering(folder: str, pgid: int) -> list[int]:
    """Processes still alive from this case: in its process group, or working in its folder."""
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            if os.getpgid(int(d)) == pgid:
                pids.append(int(d))
                continue
            cwd = os.readlink(f"/proc/{d}/cwd")
            if cwd == folder or cwd.startswith(folder + "/"):
                pids.append(int(d))
        except OSError:
            pass
    return pids


def strict_json(text: str) -> str | None:
    """None if stdout is one or more strict JSON values, else why not."""
    def bad(c):
        raise ValueError(f"{c} in JSON")
    dec = json.JSONDecoder(parse_constant=bad)
    i, text = 0, text.strip()
    try:
        while i < len(text):
            _, i = dec.raw_decode(text, i)
            while i < len(text) and text[i].isspace():
                i += 1
    except ValueError as e:
        return str(e)[:120]
    return None


PROGRESS = re.compile(r"^\s*\.\. |^[\w/.:-]+: \d+ --input event\(s\) not delivered|"
                      r"^sandbox: |^\S+: \d+/\d+ exercises pass|^\d+ cores?, load average")
# what a run says on stderr besides its result: plain progress lines (app/progress.py), the note
# on events due after the run's end, the grader's sandbox line and a line per student, the
# benchmarks' load line


def run_case(case: Case, timeout: float, base: str) -> tuple[str, list[tuple[str, str]], dict]:
    folder = tempfile.mkdtemp(prefix="case.", dir=base)
    breaches: list[tuple[str, str]] = []
    info: dict = {}
    full = make_setup(folder, case)
    if full == "unmountable":
        shutil.rmtree(folder, ignore_errors=True)
        return case.id, [("skipped: no tmpfs", "")], info
    argv = [arg_for(a, full) for a in case.argv]
    guarded = {g: digest(os.path.join(folder, arg_for(g, None))) for g in case.guarded}
    inputs = {i: digest(os.path.join(folder, i)) for i in case.inputs}
    before = set()
    for d, _, fs in os.walk(folder):
        before |= {os.path.join(d, f) for f in fs}
    cmd = [sys.executable, "-m", "app", *argv]
    t0 = time.monotonic()
    try:
        proc = subprocess.Popen(cmd, cwd=folder, env=env_for(), stdin=subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                start_new_session=True)
    except (ValueError, OSError) as e:
        shutil.rmtree(folder, ignore_errors=True)
        return case.id, [("harness: cannot start", str(e))], info
    pgid = proc.pid
    try:
        if case.sigint is not None:
            try:
                out, err = proc.communicate(timeout=case.sigint)
            except subprocess.TimeoutExpired:
                os.killpg(pgid, signal.SIGINT)        # Ctrl-C: the whole foreground group
                info["sigint_sent"] = True
                out, err = proc.communicate(timeout=timeout)
        else:
            out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(pgid, signal.SIGKILL)
        out, err = proc.communicate()
        breaches.append(("hang past the timeout", f"{timeout:g} s"))
    info["seconds"] = time.monotonic() - t0
    rc = proc.returncode
    info["rc"] = rc
    stdout = out.decode("utf-8", "replace")
    stderr = err.decode("utf-8", "replace")
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    info["err"] = lines[0][:300] if lines else ""
    time.sleep(0.05)
    left = lingering(folder, pgid)
    if left:                      # one that is still dying (a compiler the Ctrl-C reached too)
        time.sleep(1.0)           # is not left behind: look again a second later
        left = lingering(folder, pgid)
    if left:
        breaches.append(("process left behind", str(left)))
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
    if "Traceback" in stderr or "Traceback" in stdout:
        breaches.append(("traceback", next((ln for ln in reversed(lines)), "")[:200]))
    if "ffmpeg version" in stderr or re.search(r"^\[\w+ @ 0x", stderr, re.M):
        breaches.append(("ffmpeg log on stderr", lines[0][:200] if lines else ""))
    if rc is not None and rc < 0:
        breaches.append(("killed by a signal", f"signal {-rc}"))
    elif info.get("sigint_sent") and rc != 130 and not breaches:
        breaches.append(("Ctrl-C not exit 130", f"exit {rc}"))
    elif info.get("sigint_sent") and not (lines and "interrupted" in lines[-1]):
        breaches.append(("Ctrl-C: the last stderr line does not say interrupted",
                         lines[-1][:200] if lines else "(none)"))
    elif rc not in case.expect and not info.get("sigint_sent") and not any(
            b[0] == "hang past the timeout" for b in breaches):
        breaches.append((f"exit {rc} where {sorted(case.expect)} is the contract",
                         lines[0][:200] if lines else ""))
    if rc == 2 or (rc == 130 and not info.get("sigint_sent")):
        lines = [ln for ln in lines if not PROGRESS.match(ln)]   # the error itself: one line
        if len(lines) != 1:
            breaches.append((f"exit {rc} with {len(lines)} stderr lines, not one",
                             " | ".join(ln[:80] for ln in lines[:3])))
        if lines and rc == 2 and not re.match(r"python -m app[\w ]*: error: ", lines[0]):
            breaches.append(("error line not 'python -m app: error: ...'", lines[0][:200]))
    errline = lines[-1] if lines and rc in (2, 130) else ""
    if len(errline) > 300:
        breaches.append(("error line over 300 characters", f"{len(errline):,} characters"))
    if any(len(ln) > 1000 for ln in stderr.splitlines()):   # tables may be wide; an echo not
        breaches.append(("stderr line over 1000 characters",   # shortened is wider still
                         f"{max(len(ln) for ln in stderr.splitlines()):,} characters"))
    if any(ord(ch) < 32 and ch not in "\n" for ch in stderr):
        breaches.append(("raw control character on stderr",
                         repr(next(ch for ch in stderr if ord(ch) < 32 and ch != "\n"))))
    if rc in (0, 1) and not info.get("sigint_sent"):
        stray = [ln for ln in lines if not PROGRESS.match(ln)]
        if stray and rc == 0 and case.argv[:1] not in (["exercise"], ["bench"]):
            # (the benchmarks' tables go to stderr, so that --json's stdout is JSON only)
            breaches.append(("stray stderr on success", stray[0][:200]))
    if rc == 0 and "--json" in case.argv and "--help" not in case.argv:
        why = strict_json(stdout)
        if why:
            breaches.append(("--json stdout not strict JSON", why))
    # files: temporary ones left, guarded ones changed, inputs changed, promised ones missing
    for d, dirs, fs in os.walk(folder):
        for f in fs + dirs:
            if ".part" in f or f.startswith(".probe.") or f.startswith("tmp"):
                breaches.append(("temporary file left", os.path.join(d, f)[len(folder):][:120]))
    for g, h in guarded.items():
        now = digest(os.path.join(folder, g)) if not g.startswith("FULL/") else \
            digest(os.path.join(full, g[5:]))
        if rc != 0 and now != h:
            breaches.append(("existing output changed by a failed run", g))
        if rc == 0 and now != h and "replac" not in (stdout + stderr).lower():
            breaches.append(("existing file replaced without a word", g))
    for i, h in inputs.items():
        if digest(os.path.join(folder, i)) != h:
            breaches.append(("an input was changed", i))
    if rc == 0:
        for o in case.outputs:
            p = o if isinstance(o, str) else os.fsdecode(o)
            p = os.path.join(folder, p)
            if not (os.path.isfile(p) and os.path.getsize(p) > 0):
                breaches.append(("promised output missing or empty", shorten(p, 80)))
    for w in case.words:
        if rc == 2 and lines and w not in lines[0]:
            breaches.append(("error line does not name the problem", w))
    if breaches:
        info["stderr_tail"] = stderr[-1500:]
    if full:
        subprocess.run(["umount", "-l", full], capture_output=True)
    shutil.rmtree(folder, ignore_errors=True)
    return case.id, breaches, info


# --- main -------------------------------------------------------------------------------------

def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--cases", type=int, default=600)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("--only", help="run the cases whose id holds this text")
    ap.add_argument("--list", action="store_true", help="print the command lines, run none")
    ap.add_argument("--verbose", action="store_true", help="a line per case")
    ap.add_argument("--json", metavar="FILE", help="write every case's result here")
    ap.add_argument("--repo", help="run another checkout's app (e.g. main, for a before/after "
                    "count); default: this one")
    a = ap.parse_args()
    if a.repo:
        global ROOT, FILES
        ROOT = os.path.abspath(a.repo)
        FILES = os.path.join(ROOT, "scenes", "files")
    # a run started in the background (`... &`) has SIGINT ignored, and its children would
    # inherit that (Python then installs no KeyboardInterrupt): give them the default back
    signal.signal(signal.SIGINT, signal.default_int_handler)
    seed = a.seed if a.seed is not None else random.SystemRandom().randrange(2 ** 31)
    print(f"hostile command lines: seed {seed} (python tools/hostile.py --seed {seed})",
          flush=True)
    cases = build_cases(seed, a.cases)
    if a.only:
        cases = [c for c in cases if a.only in c.id]
    if a.list:
        for c in cases:
            print(c.id, "::", shorten(" ".join(os.fsdecode(x) for x in c.argv), 200))
        return 0
    base = tempfile.mkdtemp(prefix="hostile.")
    results = []
    t0 = time.monotonic()
    by_id = {c.id: c for c in cases}
    with ThreadPoolExecutor(a.jobs) as pool:
        for k, (cid, breaches, info) in enumerate(
                pool.map(lambda c: run_case(c, a.timeout, base), cases)):
            results.append((cid, breaches, info))
            if breaches or a.verbose:
                cmd = shorten(" ".join(os.fsdecode(x) for x in by_id[cid].argv), 160)
                mark = "BROKE" if breaches else "held "
                print(f"[{k + 1}/{len(cases)}] {mark} {cid}: exit {info.get('rc')} "
                      f"{info.get('seconds', 0):.1f}s :: {cmd}", flush=True)
                for kind, detail in breaches:
                    print(f"        - {kind}: {shorten(detail, 200)}", flush=True)
                if breaches and info.get("err"):
                    print(f"        stderr: {shorten(info['err'], 200)}", flush=True)
    shutil.rmtree(base, ignore_errors=True)
    skipped = [r for r in results if r[1] and r[1][0][0].startswith("skipped")]
    broke = [r for r in results if r[1] and r not in skipped]
    kinds = Counter(kind for _, b, _ in broke for kind, _ in b)
    print(f"\nseed {seed}: {len(results)} cases in {time.monotonic() - t0:.0f} s "
          f"(load {os.getloadavg()[0]:.1f}), held {len(results) - len(broke) - len(skipped)}, "
          f"broke {len(broke)}, skipped {len(skipped)}")
    for kind, n in kinds.most_common():
        print(f"  {n:4d}  {kind}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{"id": cid, "breaches": b, **info} for cid, b, info in results], f,
                      indent=1)
    return 1 if broke else 0


if __name__ == "__main__":
    sys.exit(main())
