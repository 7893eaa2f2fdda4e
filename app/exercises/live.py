"""What every exercise scene does around the student's code (the scenes themselves live beside
their graders: app/exercises/NAME/scene.py).

    python -m app --scene exercise:verlet               runs exercises/verlet.py
    python -m app --scene exercise:mywork/verlet.py     runs a copy elsewhere (the file's name,
                                                        without .py, says which exercise it is)

The student's file is imported when the scene is built, so R (reset) picks up an edit: change,
save, press R. If their code raises, the scene raises app.scene.SceneError with their message,
file and line (cut to a readable size): the window pauses and shows it; a headless run prints it
and exits 1. A file that does not import is reported the same way at the first step (a
sys.exit() in it too). While the message is up, the lab's own answer plays beside it in orange
(the "demo": an unwritten starter shows the target motion before anyone writes code).

The lab's code around theirs survives whatever their code returns or prints: their prints and
anything written to file descriptor 1 (os.write, a subprocess) go to stderr while their code
runs, so `--json` stays clean; a NaN reaches the metrics as NaN (null in JSON), never as the
lab's traceback; the lab's own measuring or drawing code failing on their values stops the scene
with a message, like their exception.
The scene runs the student's code in the lab's own process (the grader forks; a window cannot):
an endless loop freezes the window (Ctrl-C in the terminal stops it), and os._exit or a value
that aborts pymunk closes it. `python -m app exercise check` first is the safe order.
"""

from __future__ import annotations

import io
import os
import sys
import time
from contextlib import contextmanager, redirect_stdout
from pathlib import Path
from typing import Any, Iterable, Iterator

import numpy as np
import pygame

from app.draw.hud import Line, text_box
from app.draw.view import View
from app.exercises import get_exercise, scene_class
from app.exercises.base import BadAnswer
from app.exercises.child import refuse_borrowed
from app.exercises.grade import CHECK_TIMEOUT, import_probe
from app.exercises.loading import cap_text, lab_frame, load_module, shown, starter_path, \
    student_traceback, their_frames
from app.scene import Scene, SceneError

PREFIX = "exercise:"
MINE = (86, 180, 233)        # the student's system
GHOST = (230, 159, 0)        # the lab's reference
LINK = (220, 220, 230)
FIXED = (150, 150, 160)      # anchors and pivots
ERROR = (240, 110, 90)
# the orange tint of the lab's answer: a pixel of brightness l (its largest channel, 0-255)
# becomes (0.35 + 0.65 l / 255) GHOST, looked up (a float pass over the picture took 24 ms a
# frame at 1000x600; the table takes 9)
TINT = ((0.35 + 0.65 * np.arange(256)[:, None] / 255.0) * np.array(GHOST)).astype(np.uint8)
DEMO_LOOP = 12.0             # seconds of the lab's answer shown beside an error, then again

# what a student's code may raise into the scene: every exception, and sys.exit() (SystemExit),
# which would otherwise close the lab; Ctrl-C (KeyboardInterrupt) still stops it
STUDENT_ERRORS = (Exception, SystemExit)


@contextmanager
def to_stderr() -> Iterator[None]:
    """While the student's code runs: print() and file descriptor 1 both go to stderr (stdout
    carries --json), input() and file descriptor 0 read an empty file (a read would otherwise
    wait for the terminal, freezing the window), and all come back after."""
    for stream in (sys.stdout, sys.__stdout__):
        try:
            stream.flush()
        except (AttributeError, OSError, ValueError):
            pass
    saved: dict[int, int] = {}
    try:
        saved[1] = os.dup(1)
        os.dup2(2, 1)
        null = os.open(os.devnull, os.O_RDONLY)
        saved[0] = os.dup(0)
        os.dup2(null, 0)
        os.close(null)
    except OSError:                     # no fd 0, 1 or 2 (a daemon): what could be done
        pass
    stdin, sys.stdin = sys.stdin, io.StringIO()
    try:
        with redirect_stdout(sys.stderr):
            yield
    finally:
        sys.stdin = stdin
        try:
            sys.stderr.flush()
        except (OSError, ValueError):
            pass
        for fd, copy in saved.items():
            os.dup2(copy, fd)
            os.close(copy)


class StudentCode:
    """Mixin for an exercise scene: imports the student's module at build, keeps the lab's
    reference answer at hand, and turns the student's exceptions into SceneError. While it holds
    an error, the scene's other hooks do nothing (there may be no world to draw) and draw() shows
    the message beside the lab's answer running."""

    exercise = ""                  # the exercise's name (app/exercises)
    student_path = ""              # the file to import
    student: Any = None            # a module given directly (the grader), instead of the file
    base_scene: type | None = None  # the exercise's scene class this one is bound from
    is_demo = False                # the lab's answer shown beside an error (drawn as the ghost)
    error: str | None = None
    error_kind = ""                # the exception's class name, for the HUD
    draws_own_error = True         # draw() shows the traceback (headless screenshots too)
    ghost_note = "orange: the lab's"   # what the HUD says the reference looks like

    @classmethod
    def import_problem(cls, timeout: float = CHECK_TIMEOUT) -> str | None:
        """Why the student's file cannot be imported safely, or None: imported first in a child
        process (as the grader does), a file that calls os._exit, kills its own process or
        loops forever at import would take the lab down with it. An exception at import is
        not a problem here: the scene reports it with the student's file and line."""
        if cls.student is not None:
            return None
        report = import_probe(get_exercise(cls.exercise), cls.student_path, timeout)
        if report.measured.startswith(("the process died", "still running", "a damaged")):
            return f"{cls.student_path}: importing it, {report.measured}: {report.error}"
        return None

    def build(self) -> None:
        self.error = None
        self.demo = None
        try:
            with to_stderr():
                self.impl = self.student if self.student is not None else load_module(
                    self.student_path)
                missing = [f for f in get_exercise(self.exercise).functions
                           if not callable(getattr(self.impl, f, None))]
                if missing:
                    raise BadAnswer(f"{self.student_path} defines no function "
                                    f"{', '.join(missing)}")
                if self.student is None:
                    refuse_borrowed(self.impl, self.student_path)
                self.reference = get_exercise(self.exercise).reference()
                super().build()
        except STUDENT_ERRORS as e:     # any failure of the student's code
            self.fail(e)

    def fail(self, e: BaseException, lab: str = "") -> SceneError:
        """Hold the error (their traceback, or the lab's code failing on their values)."""
        self.error_kind = type(e).__name__[:60]
        message = student_traceback(e, self.student_path)
        if not lab and not isinstance(e, (SyntaxError, BadAnswer, SceneError, SystemExit)) \
                and not their_frames(e, self.student_path):
            lab = "code"          # raised in the lab's code, none of theirs on the way: say so
        if lab:
            message = cap_text(f"the lab's {lab} failed on what your code returned (at "
                               f"{lab_frame(e)}): {message}")
        self.error = message if 'File "' in message else f"{self.student_path}: {message}"
        return SceneError(self.error)

    def advance(self) -> None:
        if self.error is not None:
            raise SceneError(self.error)
        try:
            with to_stderr():
                super().advance()
        except STUDENT_ERRORS as e:
            raise self.fail(e) from None

    # ----- the other hooks, safe while an error is held, and on whatever came back ------------
    def metrics(self) -> dict[str, float]:
        if self.error:
            return {}
        try:
            return super().metrics()
        except Exception as e:          # noqa: BLE001 - the lab's measuring, on their values
            self.fail(e, "measuring code")   # held: the next step raises it (the HUD reads
            return {}                        # metrics while drawing, where no raise may go)

    @property
    def content_fills(self) -> bool:
        """While an error is held, the message and the lab's answer below it lay themselves out
        in all the room the window gives (a fitted 4:3 box left the answer a ~130 px strip
        under a large-text message at 1024x768, issue 26)."""
        return self.error is not None

    def fit_to(self, size: tuple[float, float]) -> None:
        self.error_room = size

    def content_bounds(self) -> tuple[float, float, float, float]:
        if self.error and getattr(self, "error_room", None):
            return (0.0, 0.0, *self.error_room)
        if self.error:
            demo = self.demo_scene()
            if demo is None:            # the world may not exist: the whole world area
                return Scene.content_bounds(self)
            x, y, w, h = demo.content_bounds()
            # room above the demo for the message, and at least 4:3 so the message is wide
            wide = max(w, 1.33 * 1.6 * h)
            return (x - (wide - w) / 2, y - 0.6 * h, wide, 1.6 * h)
        return super().content_bounds()

    def blowup_hint(self) -> str:
        """After the state went NaN or inf: their code is the first suspect, and the grader
        names the likely mistake (a smaller dt is the shell's advice for the lab's scenes)."""
        own = super().blowup_hint()
        if self.student is not None:            # the lab's reference itself
            return own
        check = f"python -m app exercise check {self.exercise} --path {self.student_path}"
        return (f"What your code returned went NaN or inf (or past the scene's bounds): "
                f"`{check}` names the likely mistake. If every check passes: "
                + (own or "a smaller dt (raise hertz) or more substeps."))

    def effect_costs(self) -> dict[str, float]:
        return {} if self.error else super().effect_costs()

    def hud_lines(self) -> list[str]:
        if self.error:
            lines = [f"your code raised {self.error_kind}: fix it, save, press R"]
            if self.demo_scene() is not None:
                lines.append("orange: the lab's answer, running: what yours should do")
            return lines
        try:
            return [f"yours: {self.student_path}; {self.ghost_note}"] + super().hud_lines()
        except Exception as e:          # noqa: BLE001
            self.fail(e, "measuring code")
            return self.hud_lines()

    def draw(self, surface, view) -> None:
        if self.error:
            self.draw_error(surface, view)
            return
        try:
            super().draw(surface, view)
        except Exception as e:          # noqa: BLE001 - the lab's drawing, on their values
            self.fail(e, "drawing code")
            self.draw_error(surface, view)

    def handle_event(self, event) -> None:
        if not self.error:
            super().handle_event(event)

    def state_arrays(self) -> Iterable[np.ndarray]:
        return () if self.error else super().state_arrays()

    def snapshot(self) -> Any:
        return None if self.error else super().snapshot()

    # ----- the lab's answer beside the error -------------------------------------------------
    def demo_scene(self) -> Scene | None:
        """The same scene run by the lab's answer (built when first drawn), or None if even
        that cannot be built."""
        if self.is_demo or self.base_scene is None:
            return None
        if self.demo is None:
            try:
                cls = bind(self.base_scene, student=get_exercise(self.exercise).reference(),
                           spec=self.exercise)
                cls.is_demo = True
                self.demo = cls(self.settings())
                self.demo_clock = time.perf_counter()
            except Exception:           # noqa: BLE001 - no demo, the message alone
                self.demo = False
        return self.demo if self.demo and not self.demo.error else None

    def run_demo(self, demo: Scene) -> None:
        """Advance the demo by the wall time since the last frame (at most 0.1 s of it), and
        start it again every DEMO_LOOP seconds."""
        now = time.perf_counter()
        due, self.demo_clock = min(now - self.demo_clock, 0.1), now
        steps = int(due / demo.dt + getattr(self, "demo_debt", 0.0))
        self.demo_debt = due / demo.dt + getattr(self, "demo_debt", 0.0) - steps
        try:
            for _ in range(steps):
                demo.advance()
            if demo.time > DEMO_LOOP:
                demo.reset()
        except Exception:               # noqa: BLE001
            self.demo = False

    def draw_error(self, surface, view) -> None:
        """The message at the top of the content, the lab's answer running below it."""
        x, y, w, h = self.content_bounds()
        (left, top), (right, bottom) = view.pt((x, y)), view.pt((x + w, y + h))
        lines = [Line(t, ERROR) for t in self.error.splitlines()]
        demo = self.demo_scene()          # (the HUD says what the orange answer is: its two
                                          # lines here too left the answer a strip at F2)
        box = text_box(surface, lines, (left, top), max_width=max(200, right - left))
        if demo is None:
            return
        self.run_demo(demo)
        demo = self.demo_scene()
        area = pygame.Rect(left, box.bottom + 8, right - left, bottom - box.bottom - 8)
        area = area.clip(surface.get_clip() or surface.get_rect())
        self.demo_rect = area           # (where the answer was drawn last: tests measure it)
        if demo is None or area.width < 40 or area.height < 40:
            return
        # drawn on its own layer and tinted orange, whatever colours the scene draws with:
        # the lab's answer is the orange ghost, as in the running exercise
        layer = pygame.Surface(area.size, pygame.SRCALPHA)
        demo.draw(layer, View.fit_bounds(demo.content_bounds(), (0, 0, *area.size)))
        rgb = pygame.surfarray.pixels3d(layer)
        rgb[...] = TINT[np.maximum(np.maximum(rgb[..., 0], rgb[..., 1]), rgb[..., 2])]
        del rgb                          # the surface is locked while the array lives
        surface.blit(layer, area.topleft)


def bind(base: type[Scene], student: Any = None, path: str | None = None,
         spec: str | None = None) -> type[Scene]:
    """The exercise scene `base` bound to the file `path` (default: the starter), or to
    `student` (a module, or the reference's namespace: the grader), named exercise:SPEC."""
    spec = spec or base.exercise
    file = path or (spec if spec.endswith(".py") else shown(starter_path(base.exercise)))
    if student is not None:
        file = getattr(student, "__file__", "the lab's reference")
    return type(base.__name__, (base,), {"name": PREFIX + spec, "student_path": file,
                                         "student": student, "base_scene": base,
                                         "__doc__": base.__doc__})


def exercise_scene(spec: str, student: Any = None, path: str | None = None
                   ) -> type[Scene] | None:
    """The scene class for `exercise:SPEC` (SPEC: an exercise's name, or a path to a .py file
    whose name is one), bound to that file, to the file `path` if given, or to `student`; None
    if SPEC names no exercise."""
    name = Path(spec).stem if spec.endswith(".py") else spec
    base = scene_class(name)
    if base is None:
        return None
    return bind(base, student=student, path=path, spec=spec)


__all__ = ["StudentCode", "bind", "exercise_scene", "to_stderr", "PREFIX", "MINE", "GHOST",
           "LINK", "FIXED", "ERROR", "STUDENT_ERRORS"]
