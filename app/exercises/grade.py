"""Grading a student's file so that nothing in it can break the lab or change a verdict.

One child process per exercise imports the file ONCE and runs the measuring half of every check
(app/exercises/child.py); the verdicts are the parent's, computed here from the raw values each
check sends back (app/exercises/base.py). On Linux the child runs in the operating system's walls
(app/exercises/sandbox.py): a keeper forked from here gives it PID, network, IPC and UTS
namespaces and a pids cgroup; it drops every capability, restricts itself with Landlock (reads
Python's files and its harness only, writes its own temporary folder only, no TCP, signals
scoped to itself) and execs a fresh `python -I` that imports only the harness (the lab modules
its checks run, the exercise's reference stubbed out): nothing of this process's memory comes
along. Every report's first line says which walls are in force and which this machine lacks.

  * the channel is untrusted (app/exercises/channel.py): framed, JSON, bounded in size, and
    bounded in time by a deadline per check; junk, a forged frame, half a frame is a failed
    check with a one-line reason, never the grader's traceback;
  * a syntax error, a missing package, an exception at import is a failed "imports" check with
    the student's file and line; the other checks are then reported as not run;
  * an exception in a check fails that check (their traceback) and the next check runs;
  * a check's time limit is the floor (--timeout) or LIMIT_FACTOR times the reference's own time
    on that check, measured in this run on this machine (reference_time), whichever is longer;
    a check still running then is stopped, the exercise's remaining checks are skipped (each
    would wait as long again), and the report says what was measured;
  * a child that dies (pymunk aborts the process on some values, os._exit) fails the check it was
    in; a new child imports the file again for the checks after it;
  * when the exercise is done the keeper kills the child, and the kernel every process in its
    PID namespace (a setsid daemon too); the keeper, a subreaper, kills anything else left;
  * a file that hands in the lab's own code (a name of app/ or scenes/ in its module) fails the
    import: the grader grades code the student wrote;
  * the student's output (prints, os.write, subprocesses) is captured and its first OUTPUT_SHOWN
    bytes shown (on stderr, before the report), the rest counted and dropped;
  * the grader's own errors (a judge that raises) are reported as the grader's.
`check all` grades up to JOBS exercises at once, each in its own child. Elsewhere than Linux the
child is a plain fork of this process, unconfined, and the report says so (Windows cannot fork:
there the checks run in the grader's process, which still catches every exception but cannot
stop an endless loop nor keep a verdict out of the student's reach).

Starting and stopping a child (forked, or a keeper in the sandbox) is app/exercises/spawn.py's
ChildLife, which Session inherits; LIMIT_FACTOR, STARTUP, CAN_FORK and SANDBOXED are defined
there and imported here. What the child sends, the verdicts and the time limits are this module's.
"""

from __future__ import annotations

import json
import os
import selectors
import signal
import time
from typing import Iterator

from app.exercises import base, sandbox
from app.exercises.base import Check, Exercise, plain
from app.exercises.channel import ChannelError, Frame, parse
from app.exercises.child import CHANNEL_LOST, READY, import_answer, outcome
from app.exercises.loading import shown, starter_path
from app.exercises.report import OUTPUT_SHOWN, CheckReport, Report, not_run, verdict
from app.exercises.spawn import (CAN_FORK, LIMIT_FACTOR, SANDBOXED, STARTUP, Child,
                                 ChildLife)

CHECK_TIMEOUT = 10.0        # seconds a check may run at least (the floor of its time limit)
#                             LIMIT_FACTOR (app/exercises/spawn.py): ... and at least this many
#                             times the reference's own time
JOBS = max(1, min(4, os.cpu_count() or 1))   # exercises graded at once by `check all`
READ = 1 << 16

DIED = ("the check's process ended without a result: a crash in a library (pymunk aborts on some "
        "values, e.g. a negative radius or mass), os._exit, or a signal")
NO_CHANNEL = ("the check's process could not send its result: the grader's channel was closed "
              "or redirected (did your code close or dup2 file descriptors, os.closerange?)")
ENDLESS = ("stopped after {t:.1f} s{ref}. A check calls your function hundreds of times: a loop "
           "that never ends, a sleep or a print of whole arrays in it adds up")
SKIPPED = ("not run: the check before it ran out of time, and each would wait {t:g} s or more "
           "again; fix that one first")
SETUP = ("the grader's sandbox could not be set up, so your code was not run (a problem of the "
         "machine, not of your file): {why}")


# ----- one exercise: its child (or children) and what came back --------------------------------
REFERENCE_TIMES: dict[tuple[str, str, object], float | None] = {}


def reference_time(exercise: Exercise, check: Check) -> float | None:
    """Seconds the lab's reference takes on `check` on this machine now (measured in this
    process, once per run and seed: the time limit of a check is a multiple of it); None if the
    reference cannot be timed here."""
    key = (exercise.name, check.name, getattr(base, "SEED", None))
    if key not in REFERENCE_TIMES:
        try:
            ref = exercise.reference()
            start = time.perf_counter()
            check.measure(ref)
            REFERENCE_TIMES[key] = time.perf_counter() - start
        except Exception:            # noqa: BLE001 - the floor of the limit still holds
            REFERENCE_TIMES[key] = None
        base.NOTES.clear()
    return REFERENCE_TIMES[key]


class Session(ChildLife):
    """Grading one exercise: starts children, reads their frames and output, keeps the reports."""

    def __init__(self, exercise: Exercise, path: str | None, timeout: float,
                 checks: list[Check]):
        self.exercise, self.path, self.timeout, self.checks = exercise, path, timeout, checks
        self.reports: list[CheckReport | None] = [None] * len(checks)
        self.imports: CheckReport | None = None
        self.output = bytearray()
        self.output_bytes = 0
        self.child: Child | None = None
        self.done = False
        self.sel: selectors.BaseSelector | None = None
        self.sandbox = sandbox.protections().line() if SANDBOXED else \
            "sandbox: none (not Linux: the checks run in a forked process, unconfined)"
        self.copy: str | None = None         # the student's file, as read once
        self.refused: str | None = None      # why it could not be read

    def limit(self, k: int) -> tuple[float, float | None]:
        """Check k's time limit and the reference's time it comes from (None: the floor)."""
        if k < 0 or self.path is None:
            return self.timeout, None
        ref = reference_time(self.exercise, self.checks[k])
        if ref is None:
            return self.timeout, None
        return max(self.timeout, LIMIT_FACTOR * ref), ref

    # --- events --------------------------------------------------------------------------------
    def on_output(self, fd: int) -> None:
        self.read_output(fd)

    def read_output(self, fd: int, drain: bool = False) -> None:
        for _ in range(64 if drain else 1):
            try:
                data = os.read(fd, READ)
            except (BlockingIOError, OSError):
                return
            if not data:
                self._unregister(fd)
                return
            self.output_bytes += len(data)
            room = OUTPUT_SHOWN - len(self.output)
            if room > 0:
                self.output += data[:room]

    def on_channel(self, fd: int) -> None:
        c = self.child
        try:
            data = os.read(fd, READ)
        except OSError:                    # nothing yet (or closed meanwhile)
            return
        if not data:                       # every writer closed it: wait for the exit
            self._unregister(fd)
            return
        self.take(c, data)

    def take(self, c: Child, data: bytes) -> None:
        """Judge the complete frames in `data`; junk or a bad frame breaks the check running."""
        try:
            for payload in c.reader.feed(data):
                self.accept(parse(payload, c.token, c.expected))
                if self.child is not c:    # the session moved on (done, or a new child)
                    return
            if c.reader.junk is not None:
                raise ChannelError(c.reader.junk)
        except ChannelError as e:
            self.broken(f"the check's process sent {e}: nothing but the grader may write on its "
                        "channel (did your code write to every open file descriptor?)",
                        "a damaged channel")

    def on_exit(self, fd: int | None = None) -> None:
        """The child ended: take the frames it wrote first, then judge what is missing."""
        c = self.child
        try:
            _, status = os.waitpid(c.pid, 0)
        except ChildProcessError:
            status = 0
        c.exited = True
        while self.child is c:             # frames still in the pipe
            try:
                data = os.read(c.channel, READ)
            except (BlockingIOError, OSError):
                break
            if not data:
                break
            self.take(c, data)
        if self.child is not c:
            return
        why = DIED
        if os.WIFSIGNALED(status):
            sig = os.WTERMSIG(status)
            how = f"killed by signal {sig} ({signal.Signals(sig).name})"
        else:
            how = f"exit code {os.WEXITSTATUS(status)}"
            if os.WEXITSTATUS(status) == CHANNEL_LOST:    # the child's own way out
                why = NO_CHANNEL
            elif c.control is not None and c.expected == READY and os.WEXITSTATUS(status) in (
                    sandbox.SETUP_FAILED, sandbox.KEEPER_FAILED):
                self.read_output(c.output, drain=True)
                text = bytes(self.output).decode("utf-8", "replace").strip().splitlines()
                why = SETUP.format(why=text[-1] if text else f"exit code {os.WEXITSTATUS(status)}")
            elif os.WEXITSTATUS(status) == 0:             # a clean exit, and no result
                why = DIED + "; or its channel was closed or redirected by your code"
        cut = " (in the middle of a frame)" if c.reader.partial() else ""
        self.broken(why + cut, f"the process died ({how})")

    def tick(self, now: float) -> None:
        c = self.child
        if c is None:
            return
        if c.pidfd is None:                # no pidfd: poll for the exit
            try:
                pid, _ = os.waitpid(c.pid, os.WNOHANG)
            except ChildProcessError:
                pid = c.pid
            if pid:
                c.exited = True
                self.broken(DIED, "the process died")
                return
        if now >= c.deadline:
            self.timed_out()

    # --- what the frames and the failures mean ---------------------------------------------------
    def accept(self, frame: Frame) -> None:
        c = self.child
        if frame.check == READY:               # the harness is in: the import's time starts now
            c.expected = -1
            c.started = time.monotonic()
            c.deadline = c.started + self.timeout
            return
        if frame.check == -1:
            if frame.status != "ok":
                self.import_failed(verdict(Check("imports", None, None), frame))
                return
            if self.imports is None:
                self.imports = CheckReport("imports", True, "it imports", "no error at import")
            c.expected = c.first
        else:
            self.reports[frame.check] = verdict(self.checks[frame.check], frame)
            c.expected = frame.check + 1
        c.started = time.monotonic()
        c.deadline = c.started + self.timeout
        if c.expected >= len(self.checks):
            self.finish()

    def import_failed(self, report: CheckReport) -> None:
        if self.imports is None:           # the first import: only it gets a line of its own
            self.imports = report
            why = "not run: the module does not import (see above)"
        else:                              # imported again after a crash, and failed now
            why = f"not run: importing the file again after the crash failed: {report.error}"
        for k, r in enumerate(self.reports):
            if r is None:
                self.reports[k] = not_run(self.checks[k], why)
        self.finish()

    def broken(self, error: str, measured: str) -> None:
        """The child died or its channel is damaged while check `expected` ran: that check
        fails; a new child goes on with the checks after it."""
        c = self.child
        if c.expected < 0:
            self.import_failed(CheckReport("imports", False, measured, "a normal import",
                                           error=error))
            return
        k = c.expected
        self.reports[k] = CheckReport(self.checks[k].name, False, measured, "a normal return",
                                      error=error)
        self.stop_child()
        if k + 1 < len(self.checks):
            self.start(self.sel, k + 1)
        else:
            self.finish()

    def timed_out(self) -> None:
        """The check (or the import) ran past its deadline. A check's limit is the floor
        (--timeout) or LIMIT_FACTOR times the reference's own time on this machine, whichever is
        longer: measured now, on the same machine under the same load. If that is later than the
        floor, the check goes on until then; else it is stopped, and the report says what was
        measured (not a guessed cause)."""
        c = self.child
        now = time.monotonic()
        t = now - c.started
        if c.expected == READY:
            self.import_failed(CheckReport(
                "imports", False, f"the grader's sandbox did not start in {STARTUP:g} s",
                f"started within {STARTUP:g} s", error=SETUP.format(
                    why="Python, NumPy and the harness took too long to import (a machine "
                        "loaded far beyond its cores?)")))
            return
        if c.expected == -1:
            self.import_failed(CheckReport("imports", False, f"still running after {t:.1f} s",
                                           f"done within {self.timeout:g} s",
                                           error=ENDLESS.format(t=t, ref="")))
            return
        k = c.expected
        limit, ref = self.limit(k)
        if c.started + limit > time.monotonic() + 0.01:     # the reference asks for more time
            c.deadline = c.started + limit
            return
        t = time.monotonic() - c.started
        bound = f"done within {limit:.3g} s"
        why = ""
        if ref is not None:
            bound += f" ({LIMIT_FACTOR}x the reference's {ref:.2g} s, at least {self.timeout:g} s)"
            why = f"; the reference took {ref:.2g} s on this machine"
        self.reports[k] = CheckReport(self.checks[k].name, False, f"still running after {t:.1f} s",
                                      bound, error=ENDLESS.format(t=t, ref=why))
        for j in range(k + 1, len(self.checks)):
            self.reports[j] = not_run(self.checks[j], SKIPPED.format(t=self.timeout))
        self.finish()

    def finish(self) -> None:
        self.stop_child()
        self.done = True

    def report(self) -> Report:
        where = "the lab's reference" if self.path is None else str(self.path)
        checks = [r for r in self.reports]
        if self.imports is not None and not self.imports.passed:
            checks = [self.imports] + checks
        text = self.output.decode("utf-8", "replace")
        text = "".join(ch if ch in "\n\t" or ch.isprintable() else "?" for ch in text)
        report = Report(self.exercise.name, where, checks, text, self.output_bytes)
        report.sandbox = self.sandbox
        return report


def run_sessions(sessions: list[Session], jobs: int = JOBS) -> Iterator[Report]:
    """Run the sessions, at most `jobs` at once; yield their reports in the order given."""
    sel = selectors.DefaultSelector()
    waiting, running, done = list(sessions), [], 0
    try:
        while done < len(sessions):
            while waiting and len(running) < jobs:
                s = waiting.pop(0)
                s.start(sel, 0)
                running.append(s)
            now = time.monotonic()
            deadlines = [s.child.deadline for s in running if s.child]
            limit = min(deadlines) - now if deadlines else 0
            if any(s.child and s.child.pidfd is None for s in running):
                limit = min(limit, 0.05)
            for key, _ in sel.select(max(0.0, limit)):
                try:                        # an earlier callback may have closed this fd
                    current = sel.get_key(key.fd)
                except KeyError:
                    continue
                if current.data == key.data:
                    key.data(key.fd)
            now = time.monotonic()
            for s in running:
                if not s.done:
                    s.tick(now)
            running = [s for s in running if not s.done]
            while done < len(sessions) and sessions[done].done:
                yield sessions[done].report()
                done += 1
    finally:                                # Ctrl-C, or a reader gone: leave no child behind
        for s in sessions:
            if s.child is not None:
                s.stop_child()
        sel.close()


# ----- without fork (Windows): in this process ---------------------------------------------------
def in_process(exercise: Exercise, path: str | None, checks: list[Check]) -> Report:
    where = "the lab's reference" if path is None else str(path)
    try:
        module = import_answer(path, exercise)
    except BaseException as e:      # noqa: BLE001
        status, error = outcome(e, path)
        first = verdict(Check("imports", None, None), Frame(-1, status, {}, error))
        return Report(exercise.name, where, [first] + [
            not_run(c, "not run: the module does not import (see above)") for c in checks])
    reports = []
    for c in checks:
        base.NOTES.clear()
        try:
            raw = json.loads(json.dumps(plain(c.measure(module))))   # as the channel carries it
            frame = Frame(0, "ok", raw, "", list(base.NOTES.values()))
        except BaseException as e:  # noqa: BLE001
            status, error = outcome(e, path)
            frame = Frame(0, status, {}, error, list(base.NOTES.values()))
        reports.append(verdict(c, frame))
    return Report(exercise.name, where, reports)


# ----- the grader's entry points ----------------------------------------------------------------
def chosen(exercise: Exercise, only: tuple[str, ...] | None) -> list[Check]:
    return [c for c in exercise.checks if only is None or c.name in only]


def grade_many(jobs: list[tuple[Exercise, str | None]], timeout: float = CHECK_TIMEOUT,
               only: tuple[str, ...] | None = None, parallel: int = JOBS,
               seed: int | None = None) -> Iterator[Report]:
    """Grade each (exercise, path) (path None: the lab's reference answer); yield the reports
    in order, as soon as each is complete. `seed` picks the checks' random cases (None: a new
    one; each report carries it)."""
    base.set_seed(seed)
    if not CAN_FORK:
        for exercise, path in jobs:
            yield in_process(exercise, path, chosen(exercise, only))
        return
    sessions = [Session(e, p, timeout, chosen(e, only)) for e, p in jobs]
    yield from run_sessions(sessions, parallel)


def grade(exercise: Exercise, path: str | None, timeout: float = CHECK_TIMEOUT,
          only: tuple[str, ...] | None = None, seed: int | None = None) -> Report:
    """Grade the module at `path` (None: the lab's reference answer): the import, then every
    check (or those named in `only`), on the random cases of `seed` (None: a new one)."""
    return next(grade_many([(exercise, path)], timeout, only, 1, seed))


def import_probe(exercise: Exercise, path: str, timeout: float = CHECK_TIMEOUT) -> CheckReport:
    """Only import the file, in a child, as the grader does (the exercise scenes ask this
    before they import it in the lab's own process)."""
    if not CAN_FORK:
        return CheckReport("imports", True, "not probed (no fork here)", "-")
    report = next(run_sessions([Session(exercise, path, timeout, [])], 1))
    return report.checks[0] if report.checks else CheckReport("imports", True, "it imports",
                                                              "no error at import")


__all__ = ["grade", "grade_many", "import_probe", "Report", "CheckReport", "CHECK_TIMEOUT",
           "JOBS", "OUTPUT_SHOWN", "starter_path", "shown"]
