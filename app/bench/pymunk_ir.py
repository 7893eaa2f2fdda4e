"""The lab's step against the bare loop in instructions, not seconds: part of `python -m app bench
pymunk --full`, when valgrind is installed (`apt-get install valgrind`; without it the bench
says so and prints the CPU times alone).

CPU time on a shared machine moves with the load: the same code measured 1.47 and 1.56 x a bare
loop in two runs a minute apart. An instruction count does not: valgrind's callgrind counts
every instruction the process executes, the same on every run of the same code and state. Each
case (pymunk_cost.cases) is built in a child process under callgrind with counting off, stepped
WARM steps, then counted over STEPS steps of the lab (advance + is_finite) or of the bare loop
(pymunk_cost's Replay of the same schedule), in two children, less what switching the count on
and off costs (a third child counts that alone, once); the ratio of the two counts is
the lab's work in units of the engine's, free of the load. It is not the time: the lab's Python
executes fewer instructions per cycle than pymunk's C (1.33 x the instructions measured
1.47-1.50 x the time on falling_balls), so the CPU-time ratio stays the goal's measure; this
one says whether a change did less work, where timing cannot tell.

    child:  python -m app.bench.pymunk_ir LABEL lab|bare|none STEPS
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile

from app.bench import Report
from app.bench.bare_pymunk import Replay, record
from app.bench.pymunk_cost import WARM, cases

STEPS = 120          # counted steps a child: the timing's (the counts are exact: no repeats)
_COLLECTED = re.compile(r"Collected\s*:\s*(\d+)")


def available() -> str | None:
    """None if callgrind can count here, else why not (one line)."""
    missing = [t for t in ("valgrind", "callgrind_control") if shutil.which(t) is None]
    return f"{' and '.join(missing)} not found (apt-get install valgrind)" if missing else None


def collected(stderr: str) -> int:
    """The instructions callgrind counted, from its summary on stderr ('Collected : N')."""
    found = _COLLECTED.findall(stderr)
    if not found:
        raise RuntimeError("callgrind printed no count:\n" + stderr[-2000:])
    return int(found[-1])


def count(label: str, mode: str, steps: int = STEPS, timeout: float = 900.0) -> int:
    """Instructions of `steps` steps of `mode` ('lab' or 'bare') on the case `label`, counted by
    callgrind in a child process (only the counted steps, and switching the count on and off:
    mode 'none' counts that alone; the build, imports and warm-up are not counted)."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = ["valgrind", "--tool=callgrind", "--instr-atstart=no",
               f"--callgrind-out-file={os.path.join(tmp, 'cg.out')}",
               sys.executable, "-m", "app.bench.pymunk_ir", label, mode, str(steps)]
        env = {**os.environ, "PYTHONHASHSEED": "0"}
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env,
                              cwd=os.path.dirname(os.path.dirname(os.path.dirname(
                                  os.path.abspath(__file__)))))
        if done.returncode != 0:
            raise RuntimeError(f"the counted child failed ({done.returncode}):\n"
                               + done.stderr[-2000:])
        return collected(done.stderr)


def per_step(labels: list[str], steps: int = STEPS) -> list[tuple[str, float, float]]:
    """(label, lab, bare): instructions a step of each case, each less the cost of switching
    the count (counted once)."""
    fixed = count(labels[0], "none", 0)
    return [(label, (count(label, "lab", steps) - fixed) / steps,
             (count(label, "bare", steps) - fixed) / steps) for label in labels]


def instructions(report: Report, labels: list[str]) -> list[dict] | str:
    """With --full: the same cases' lab and bare steps in instructions (callgrind's counts, free of
    the load), or why they could not be counted."""
    missing = available()
    if missing:
        report.say(f"\nInstruction counts: not measured, {missing}.")
        return f"not measured: {missing}"
    report.progress(f"instructions (callgrind, {len(labels)} cases, ~10 s each)")
    counts = per_step(labels)
    report.table(
        f"the same in instructions a step (valgrind callgrind over the timed {STEPS} "
        "steps: the same on every run, whatever the load; the lab's Python runs fewer "
        "instructions a cycle than pymunk's C, so its time ratio is higher)",
        ["scene", "lab", "bare pymunk", "lab/bare"],
        [[label, f"{lab:,.0f}", f"{bare:,.0f}", lab / bare] for label, lab, bare in counts])
    return [{"scene": label, "lab": lab, "bare": bare, "ratio": lab / bare}
            for label, lab, bare in counts]


def _child(label: str, mode: str, steps: int) -> None:
    """Build the case, step it WARM steps, count `steps` steps of the lab or the bare loop."""
    builds = dict(cases(quick=False))
    if label not in builds:
        raise SystemExit(f"no case {label!r}: {', '.join(builds)}")
    build = builds[label]
    if mode == "none":              # switching the count on and off, nothing between
        def run() -> None:
            pass
    elif mode == "lab":
        scene = build()
        for _ in range(WARM):
            scene.advance()
            scene.is_finite()

        def run() -> None:
            for _ in range(steps):
                scene.advance()
                scene.is_finite()
    else:
        replay = Replay(build(), record(build, WARM + steps))
        replay.run(WARM)

        def run() -> None:
            replay.run(steps)
    toggle = ["callgrind_control", "-i"]
    pid = str(os.getpid())
    subprocess.run(toggle + ["on", pid], capture_output=True, check=True)
    run()
    subprocess.run(toggle + ["off", pid], capture_output=True, check=True)


if __name__ == "__main__":
    _child(sys.argv[1], sys.argv[2], int(sys.argv[3]))
