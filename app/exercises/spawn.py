"""The grader's side of a grading child's life: starting it and stopping it (moved here from
app/exercises/grade.py, whose Session inherits these methods from ChildLife).

`start` forks the child: on Linux (SANDBOXED) a keeper in the operating system's walls
(app/exercises/sandbox.py), in which a fresh `python -I` imports the harness and the student's
file; elsewhere, and for a test's made-up exercise, a plain fork that runs
app/exercises/child.py's `child_main`. `stop_child` kills the child (or closes the keeper's control
pipe, and the keeper kills it and every process in its PID namespace), reaps it, keeps the output
it left and removes its folder. The frames it sends and what they mean are grade.py's.
"""

from __future__ import annotations

import json
import os
import secrets
import select
import selectors
import signal
import sys
import time
from dataclasses import dataclass, field

from app.exercises import base, sandbox
from app.exercises.forking import fork, raise_noted_ctrl_c  # noqa: F401 (tests: spawn.fork)
from app.exercises.channel import FrameReader
from app.exercises.child import READY, child_main
from app.exercises.loading import NotASourceFile, read_source
from app.exercises.report import CheckReport

LIMIT_FACTOR = 20           # a check's time limit is at least this many times the reference's
#                             own time (grade.py); the sandboxed child's CPU rlimit allows it
STARTUP = 60.0              # seconds a sandboxed child may take to start (Python, NumPy, pymunk)
CAN_FORK = hasattr(os, "fork")
SANDBOXED = CAN_FORK and sys.platform.startswith("linux") and hasattr(os, "pidfd_open")


@dataclass
class Child:
    pid: int
    token: str
    channel: int
    output: int
    pidfd: int | None
    expected: int                # the check whose frame comes next (-1: the import; -2: ready)
    first: int                   # the first check this child runs
    deadline: float
    reader: FrameReader = field(default_factory=FrameReader)
    exited: bool = False
    control: int | None = None   # the keeper's control pipe (closed: the keeper ends the child)
    folder: str | None = None    # the child's own temporary folder
    started: float = 0.0         # when the running check (or the import) started


class ChildLife:
    """Session's child management (a mixin: Session in app/exercises/grade.py has the exercise,
    path, timeout, checks, refused, sel and child it reads, and the on_channel, on_output,
    on_exit, read_output and import_failed it calls)."""

    # --- the child's life ------------------------------------------------------------------------
    def start(self, sel: selectors.BaseSelector, first: int) -> None:
        from app.exercises import NAMES
        if SANDBOXED and self.exercise.name in NAMES:   # (a test's made-up exercise: forked)
            self.start_sandboxed(sel, first)
            return
        self.sel = sel
        token = secrets.token_hex(16)
        chan_r, chan_w = os.pipe()
        out_r, out_w = os.pipe()
        sys.stdout.flush()
        sys.stderr.flush()
        pid = fork()
        if pid == 0:                      # the child: never returns
            child_main(self.exercise, self.path,
                       [(k, self.checks[k]) for k in range(first, len(self.checks))],
                       token, chan_w, out_w)
        os.close(chan_w)
        os.close(out_w)
        try:
            os.setpgid(pid, pid)          # the child does it too: whoever runs first
        except OSError:
            pass
        for fd in (chan_r, out_r):
            os.set_blocking(fd, False)
        try:
            pidfd = os.pidfd_open(pid)    # readable when the child ends (Linux 5.3+)
        except (AttributeError, OSError):
            pidfd = None
        self.child = Child(pid, token, chan_r, out_r, pidfd, -1, first,
                           time.monotonic() + self.timeout)
        sel.register(chan_r, selectors.EVENT_READ, self.on_channel)
        sel.register(out_r, selectors.EVENT_READ, self.on_output)
        if pidfd is not None:
            sel.register(pidfd, selectors.EVENT_READ, self.on_exit)
        raise_noted_ctrl_c()

    def start_sandboxed(self, sel: selectors.BaseSelector, first: int) -> None:
        """A child in the operating system's walls (app/exercises/sandbox.py): a keeper forked
        from here, and in it a fresh Python that imports the harness and the student's file."""
        self.sel = sel
        p = sandbox.protections()
        data = None
        if self.path is not None and self.refused is None:
            try:
                data = read_source(self.path)
            except NotASourceFile as e:
                self.refused = str(e)
        if self.refused is not None and first == 0:    # nothing to run: no child
            self.import_failed(CheckReport("imports", False, "not read", "a Python file",
                                           error=self.refused))
            return
        folder = sandbox.new_folder(p)
        copy = None
        if data is not None:
            try:
                copy = os.path.join(folder, os.path.basename(self.path))
                with open(copy, "wb") as f:
                    f.write(data)
                if p.uid is not None:
                    os.chown(copy, p.uid, p.uid)
            except OSError as e:
                self.refused, copy = f"the grader could not copy the file: {e}", None
        token = secrets.token_hex(16)
        n = max(1, len(self.checks) - first)
        argument = json.dumps({"exercise": self.exercise.name, "path": self.path, "copy": copy,
                               "refused": self.refused, "token": token, "first": first,
                               "only": [c.name for c in self.checks],
                               "seed": getattr(base, "SEED", None)})
        box = sandbox.Box(sandbox.harness(self.exercise.name, stub=self.path is not None), folder,
                          argument, int(STARTUP + self.timeout * LIMIT_FACTOR * (n + 1)), p)
        chan_r, chan_w = os.pipe()
        out_r, out_w = os.pipe()
        ctl_r, ctl_w = os.pipe()
        sys.stdout.flush()
        sys.stderr.flush()
        pid = fork()
        if pid == 0:                      # the keeper: never returns
            sandbox.keeper(box, chan_w, out_w, ctl_r)
        for fd in (chan_w, out_w, ctl_r):
            os.close(fd)
        for fd in (chan_r, out_r):
            os.set_blocking(fd, False)
        pidfd = os.pidfd_open(pid)
        now = time.monotonic()
        self.child = Child(pid, token, chan_r, out_r, pidfd, READY, first, now + STARTUP,
                           control=ctl_w, folder=folder, started=now)
        sel.register(chan_r, selectors.EVENT_READ, self.on_channel)
        sel.register(out_r, selectors.EVENT_READ, self.on_output)
        sel.register(pidfd, selectors.EVENT_READ, self.on_exit)
        raise_noted_ctrl_c()

    def fds(self) -> list[int]:
        c = self.child
        if c is None:
            return []
        return [fd for fd in (c.channel, c.output, c.pidfd) if fd is not None and fd >= 0]

    def _unregister(self, fd: int) -> None:
        try:
            self.sel.unregister(fd)
        except (KeyError, ValueError):
            pass

    def stop_child(self) -> None:
        """Kill the child's whole process group, reap it, keep the output it left, close."""
        c = self.child
        if c is None:
            return
        if c.control is not None:
            self.stop_keeper(c)
            return
        try:
            os.killpg(c.pid, signal.SIGKILL)     # the student's background processes too
        except OSError:
            pass
        if not c.exited:
            try:
                os.kill(c.pid, signal.SIGKILL)
            except OSError:
                pass
            try:
                os.waitpid(c.pid, 0)
            except ChildProcessError:
                pass
        self._close_pipes(c)
        self.child = None

    def _close_pipes(self, c: Child) -> None:
        """Keep what the child printed, then close and forget its pipes."""
        self.read_output(c.output, drain=True)
        for fd in self.fds():
            self._unregister(fd)
            os.close(fd)

    def stop_keeper(self, c: Child) -> None:
        """Close the keeper's control pipe (it kills the child, and the kernel every process in
        the child's PID namespace), reap the keeper, keep the output, remove the folder."""
        os.close(c.control)
        c.control = None
        if not c.exited:
            ready, _, _ = select.select([c.pidfd], [], [], 10.0)
            if not ready:                        # a keeper that hangs: should never happen
                try:
                    signal.pidfd_send_signal(c.pidfd, signal.SIGKILL)
                except OSError:
                    pass
            try:
                os.waitpid(c.pid, 0)
            except ChildProcessError:
                pass
        self._close_pipes(c)
        if c.folder:
            sandbox.remove_folder(c.folder)
        self.child = None
