"""Clips of a scene for slides: `--video OUT.gif|OUT.mp4` headless, and F9 in the window.

What a clip holds. Frames come from the fixed-step clock, never the wall clock: frame k shows
the scene after the first fixed step that ends at or after k/fps simulated seconds (frame 0: the
scene as built). So the same command gives the same frames, the clip plays in simulated time
(a 10 s run at 30 fps is 300 frames, 10 s long), and recording changes nothing in the run: the
same steps, the same events, the same final `state_hash` as without `--video`.

How it is encoded, with well-kept libraries (not an encoder of our own):
  * GIF with Pillow: ONE palette for the whole clip (255 colours chosen from frames spread
    through the clip, no dithering: flat colours stay flat and compress well); pixels
    that do not change from one frame to the next are left transparent (Pillow's `optimize`),
    and frame durations are rounded to GIF's 10 ms so that they add up to real time (30 fps
    plays 30, 40, 30 ms, ...). A GIF is written when the clip ends, so its frames are kept
    until then, zlib-compressed by a worker thread while the next frame is drawn, and Pillow
    holds every frame while it writes the file (~2 bytes per pixel: 2.4 GB measured for 900
    frames of 1280 x 960): a GIF is at most GIF_MEGAPIXELS megapixels of frames (~1 GB), at
    1280 px wide 366 frames (12 s at 30 fps); longer clips are MP4s.
  * MP4 (H.264, yuv420p, plays in slide programs and browsers) with imageio-ffmpeg, whose wheel
    ships its own ffmpeg: frames stream to it, any length. It is an optional install (68 MB
    download, 165 MB on disk: two thirds of all other requirements together, 255 MB with
    matplotlib): `MP4_INSTALL`.

Frame size: `width` pixels wide (default 1280), drawn at that size, not scaled up from a
screenshot, so lines and text stay sharp (the HUD's text grows with the width: the picture
looks like the screenshot). With the HUD, the frame has the world's shape (4:3); `--clean`
leaves HUD and metrics out and crops the frame to the scene's content. Sizes are even numbers
(H.264's 4:2:0 colour needs them).
"""

from __future__ import annotations

import math
import os
import re
import signal
import sys
import zlib
from abc import ABC, abstractmethod
from concurrent.futures import Future, ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Iterator

if TYPE_CHECKING:
    import pygame

    from app.runner import SceneRunner
    from app.scene import Scene

FORMATS = {".gif": "GIF (Pillow)", ".mp4": "MP4 (H.264, imageio-ffmpeg)"}
DEFAULT_FPS = 30
DEFAULT_WIDTH = 1280          # a 16:9 slide is 1280 or 1920 px wide when projected
MIN_WIDTH, MAX_WIDTH = 160, 1920
MAX_FPS = 60
MAX_GIF_FPS = 50              # browsers and slide programs play GIF frames shorter than 20 ms
                              # at 100 ms: a 60 fps GIF would crawl
GIF_MEGAPIXELS = 450          # frames x pixels of a GIF (~1 GB while Pillow writes it)
MP4_INSTALL = "pip install imageio-ffmpeg"
MP4_CRF = 30                  # x264 quality, sized for slides: the busiest clip, `--scene cloth
                              # --set wind=on` 10 s at 1280x960, is 3.1 MB (14.3 MB at crf 18, 4.9
                              # at 28), SSIM 0.963 against crf 18 (luma 0.98), its HUD text and
                              # rods sharp to the eye (measured 2026-11-26, load ~12)
MP4_PRESET = "veryfast"       # x264: half the CPU of "medium" for 5% larger files (measured)


def video_format(path: str) -> str | None:
    """'.gif' or '.mp4' for a clip's file name (any case), else None."""
    ext = os.path.splitext(path)[1].lower()
    return ext if ext in FORMATS else None


def mp4_problem() -> str | None:
    """None if MP4 clips can be written here, else why not (one line, with the install)."""
    try:
        import imageio_ffmpeg
        imageio_ffmpeg.get_ffmpeg_exe()
    except ImportError:
        return f"MP4 clips need imageio-ffmpeg (it ships its own ffmpeg): {MP4_INSTALL}"
    except RuntimeError as e:          # installed, but its ffmpeg cannot be found
        return f"MP4 clips need imageio-ffmpeg's ffmpeg, which is missing ({e}): {MP4_INSTALL}"
    return None


def max_gif_frames(width: int, height: int | None = None) -> int:
    """The most frames a GIF of this size may hold (GIF_MEGAPIXELS; a 4:3 frame if no height)."""
    return int(GIF_MEGAPIXELS * 1e6 / (width * (height or width * 3 / 4)))


def check_video(path: str, fps: int, frames: int | None = None, what: str = "--video",
                width: int = DEFAULT_WIDTH) -> str | None:
    """None if a clip can be written to `path` at `fps` (with `frames` frames `width` px wide,
    if known), else a one-line reason. (Whether the folder is writable:
    app.headless.check_output_path.)"""
    if not path.strip():
        return f"{what} needs a file name ending in .gif or .mp4"
    fmt = video_format(path)
    if fmt is None:
        return f"{what} '{path}': accepted: a file name ending in .gif or .mp4"
    if fmt == ".gif":
        if fps > MAX_GIF_FPS:
            return (f"{what} '{path}': a GIF plays at most {MAX_GIF_FPS} fps (players slow "
                    f"faster GIFs down); give --fps {MAX_GIF_FPS} or less, or an .mp4")
        most = max_gif_frames(width)
        if frames is not None and frames > most:
            return (f"{what} '{path}': {frames} frames; a GIF {width} px wide holds at most "
                    f"{most} ({most / fps:.3g} s at {fps} fps: it is made in memory): give "
                    "fewer --seconds, a lower --fps or --width, or an .mp4 (any length)")
    elif fmt == ".mp4":
        problem = mp4_problem()
        if problem:
            return f"{what} '{path}': {problem}; or give a .gif"
    return None


def frame_count(steps: int, dt: float, fps: int) -> int:
    """Frames in a clip of `steps` fixed steps of `dt`: one per 1/fps of simulated time."""
    return max(1, round(steps * dt * fps))


def frame_steps(steps: int, dt: float, fps: int) -> list[int]:
    """For each frame, how many fixed steps have run when it is taken: the first step count
    whose time reaches the frame's time k/fps (0 for frame 0)."""
    return [min(steps, math.ceil(k / (fps * dt) - 1e-9)) for k in range(frame_count(steps, dt,
                                                                                      fps))]


def even(n: float) -> int:
    """The even number of pixels at or below n (never above: a frame is never scaled up)."""
    return max(2, int(n + 1e-9) // 2 * 2)


def clip_size(scene: "Scene", width: int, clean: bool) -> tuple[int, int]:
    """A frame's size in pixels: `width` wide, the world's shape with the HUD, the content's
    shape (`content_bounds()`) without it; even numbers."""
    if clean:
        _, _, w, h = scene.content_bounds()
    else:
        w, h = scene.world_size
    return even(width), even(width * float(h) / float(w))


@dataclass
class Clip:
    """A clip written: where, how many frames and seconds (counted back from the file, not from
    what was sent), how many bytes, and whether it replaced a file that was there."""
    path: str
    frames: int
    size: tuple[int, int]
    fps: int
    bytes: int
    seconds: float = 0.0
    replaced: bool = False

    def text(self) -> str:
        return (f"{self.path} ({self.frames} frames, {self.size[0]}x{self.size[1]}, "
                f"{self.seconds:.3g} s at {self.fps} fps, {self.bytes / 1e6:.2f} MB"
                + (", replaced the file that was there)" if self.replaced else ")"))


def read_back(path: str) -> tuple[int, float]:
    """(frames, seconds) of a clip file, as a player reads them: a GIF's frames and the sum of
    their durations (Pillow), an MP4's video frames and duration (ffmpeg, stream copied, no
    decoding). OSError if the file cannot be read as a clip."""
    if video_format(path) == ".gif":
        from PIL import Image, UnidentifiedImageError
        try:
            with Image.open(path) as im:
                frames, ms = 0, 0
                for k in range(getattr(im, "n_frames", 1)):
                    im.seek(k)
                    frames += 1
                    ms += im.info.get("duration", 0)
        except (UnidentifiedImageError, EOFError, ValueError) as e:
            raise OSError(0, f"the GIF written cannot be read back ({e})") from None
        return frames, ms / 1000
    import subprocess

    import imageio_ffmpeg
    try:
        return imageio_ffmpeg.count_frames_and_secs(path)
    except (RuntimeError, subprocess.CalledProcessError, ValueError) as e:
        raise OSError(0, f"the MP4 written cannot be read back ({str(e).splitlines()[0]})") \
            from None


RAW = "BGRX" if sys.byteorder == "little" else "XRGB"     # a 32-bit pygame surface's bytes
_FFMPEG_RAW = {"BGRX": "bgr0", "XRGB": "0rgb"}


def raw_frame(surface: "pygame.Surface", fresh: bool = False) -> bytes | memoryview:
    """A surface's pixels as RAW bytes (4 per pixel, rows top to bottom), converted first if it
    is not a 32-bit surface with the usual masks. A `fresh` surface (drawn for this frame only,
    never drawn on again) is handed over as a view of its own pixels, no copy."""
    import pygame
    w, h = surface.get_size()
    if surface.get_bitsize() != 32 or surface.get_masks()[:3] != (0xFF0000, 0xFF00, 0xFF) \
            or surface.get_pitch() != 4 * w:        # another format, or a subsurface's rows
        plain = pygame.Surface((w, h), 0, 32, (0xFF0000, 0xFF00, 0xFF, 0))
        plain.blit(surface, (0, 0))
        surface, fresh = plain, True
    return memoryview(surface.get_buffer()) if fresh else surface.get_buffer().raw


class ClipWriter(ABC):
    """Frames in, a clip file out: add_surface(surface) for each frame, then close().
    open_clip() picks the writer for the file's extension. The file is written beside `path`
    and renamed into place by close() once it is complete and reads back (app/outputs.py):
    a clip that fails or is interrupted leaves the old file as it was."""

    def __init__(self, path: str, size: tuple[int, int], fps: int, what: str = "the clip"):
        from app.outputs import Pending
        self.path, self.size, self.fps = path, size, fps
        self.frames = 0
        self.pending = Pending(path, what)
        self.tmp = self.pending.tmp

    def failed(self, e: BaseException | str) -> str:
        """The one line that says the clip could not be written, and why."""
        return self.pending.failed(e)

    def finish(self) -> Clip:
        """Check the temporary file (frames and seconds read back from it: what a player will
        show) and rename it into place; OutputError if it holds no frame or cannot be read."""
        from app.outputs import OutputError
        try:
            frames, seconds = read_back(self.tmp)
            if frames == 0:
                raise OSError(0, "the file written holds no frame")
            size = os.path.getsize(self.tmp)
        except OSError as e:
            self.pending.discard()
            raise OutputError(self.failed(e)) from None
        self.pending.commit()
        return Clip(self.path, frames, self.size, self.fps, size, seconds, self.pending.replaced)

    def add_surface(self, surface: "pygame.Surface", fresh: bool = False) -> None:
        """Add a pygame surface as the next frame (scaled to the clip's size if it differs);
        `fresh`: see raw_frame."""
        import pygame
        if surface.get_size() != self.size:
            surface, fresh = pygame.transform.smoothscale(raw_surface(surface), self.size), True
        self.add(raw_frame(surface, fresh))

    @abstractmethod
    def add(self, raw: bytes | memoryview) -> None:
        """Add a frame of RAW bytes of the clip's size."""

    @abstractmethod
    def close(self) -> Clip:
        """Write the file; return what was written."""

    @abstractmethod
    def abandon(self) -> None:
        """Stop without writing (an error elsewhere): free what is held."""


def raw_surface(surface: "pygame.Surface") -> "pygame.Surface":
    """A 32-bit copy of a surface (smoothscale needs 24 or 32 bits)."""
    import pygame
    plain = pygame.Surface(surface.get_size(), 0, 32, (0xFF0000, 0xFF00, 0xFF, 0))
    plain.blit(surface, (0, 0))
    return plain


class GifWriter(ClipWriter):
    """GIF with Pillow: frames kept zlib-compressed (a worker thread compresses while the next
    frame is drawn), one palette for the clip chosen at the end, written on close() (two
    threads turn frames into palette images while the file is written)."""

    PALETTE_FRAMES = 8      # frames, spread over the clip, whose colours choose the palette

    def __init__(self, path: str, size: tuple[int, int], fps: int, what: str = "the clip"):
        super().__init__(path, size, fps, what)
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="gif-frames")
        self._packed: list[Future[bytes]] = []

    def add(self, raw: bytes | memoryview) -> None:
        self._packed.append(self._pool.submit(zlib.compress, raw, 1))
        self.frames += 1

    def durations(self) -> list[int]:
        """Each frame's duration in ms, multiples of 10 (GIF's unit) that add up to the clip's
        real time: frame k ends at round(100 (k+1) / fps) centiseconds."""
        ends = [round(100 * (k + 1) / self.fps) * 10 for k in range(self.frames)]
        return [b - a for a, b in zip([0] + ends[:-1], ends)]

    def _frame(self, k: int):
        from PIL import Image
        raw = zlib.decompress(self._packed[k].result())
        return Image.frombuffer("RGB", self.size, raw, "raw", RAW, 0, 1)

    def palette(self):
        """A palette image of 255 colours (one index left free for transparency) for the whole
        clip: Pillow's maximum-coverage quantizer over up to PALETTE_FRAMES frames spread
        through the clip, every other pixel of every other row (4x faster than every pixel, and
        as close: measured on the cloth, the balls, the integrator lab and the dance)."""
        from PIL import Image
        n = self.frames
        picks = sorted({round(i * (n - 1) / max(1, self.PALETTE_FRAMES - 1))
                        for i in range(min(n, self.PALETTE_FRAMES))})
        w, h = max(1, self.size[0] // 2), max(1, self.size[1] // 2)
        sample = Image.new("RGB", (w, h * len(picks)))
        for row, k in enumerate(picks):
            sample.paste(self._frame(k).resize((w, h), Image.Resampling.NEAREST), (0, row * h))
        return sample.quantize(colors=255, method=Image.Quantize.MAXCOVERAGE,
                               dither=Image.Dither.NONE)

    def close(self) -> Clip:
        from PIL import Image

        from app.outputs import OutputError
        try:
            if not self.frames:
                raise ValueError("no frame to write")
            palette = self.palette()

            def indexed(k: int):
                return self._frame(k).quantize(palette=palette, dither=Image.Dither.NONE)
            with ThreadPoolExecutor(max_workers=2, thread_name_prefix="gif-palette") as pool:
                frames = _ahead(pool, indexed, self.frames, 4)
                first = next(frames)
                first.save(self.tmp, format="GIF", save_all=True, append_images=frames,
                           duration=self.durations(), loop=0, optimize=True, disposal=1)
        except (OSError, ValueError, RuntimeError) as e:
            self.abandon()
            raise OutputError(self.failed(e)) from None
        except BaseException:
            self.abandon()
            raise
        self._free()
        return self.finish()

    def _free(self) -> None:
        self._pool.shutdown(wait=True, cancel_futures=True)
        self._packed = []

    def abandon(self) -> None:
        self._free()
        self.pending.discard()


def _ahead(pool: ThreadPoolExecutor, fn: Callable, n: int, lookahead: int):
    """fn(0), ..., fn(n - 1) in order, computed by `pool` at most `lookahead` ahead of the
    consumer (Executor.map would start them all at once: every frame in memory twice)."""
    pending: list[Future] = []
    for k in range(n):
        pending.append(pool.submit(fn, k))
        if len(pending) > lookahead:
            yield pending.pop(0).result()
    for future in pending:
        yield future.result()


@contextmanager
def _ctrl_c_held() -> Iterator[None]:
    """A Ctrl-C during the block is remembered and raised after it. Around the start of
    ffmpeg: a KeyboardInterrupt raised inside Popen (after the fork, before `_proc` was set)
    left an ffmpeg no one could stop, which wrote the temporary file again after the run had
    removed it (a 225-byte '.part.mp4' left in ~1 of 10 interrupted runs). Blocking the signal
    (pthread_sigmask) does not do: the kernel hands it to another thread (BLAS, the frame pool)
    and Python raises it in the main thread all the same. Only the main thread may set a
    handler; elsewhere the block runs as it is."""
    import threading
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[tuple] = []
    before = signal.signal(signal.SIGINT, lambda *how: caught.append(how))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, before)
        if caught and callable(before):
            before(*caught[0])            # Python's own: raises KeyboardInterrupt here
        elif caught and before == signal.SIG_DFL:
            signal.raise_signal(signal.SIGINT)


class Mp4Writer(ClipWriter):
    """MP4 (H.264) through imageio-ffmpeg's ffmpeg: frames stream to it as they come (as raw
    surface bytes: ffmpeg converts them to yuv420p in its own process). ffmpeg runs in a
    session of its own (Ctrl-C reaches the lab, which stops it), its messages go to a
    temporary file, not to the terminal, and its exit status is checked: the last of its
    messages is the reason a clip failed."""

    def __init__(self, path: str, size: tuple[int, int], fps: int, what: str = "the clip"):
        import subprocess
        import tempfile

        import imageio_ffmpeg
        super().__init__(path, size, fps, what)
        self._log = tempfile.TemporaryFile()
        cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-nostats", "-hide_banner",
               "-loglevel", "error", "-f", "rawvideo", "-vcodec", "rawvideo",
               "-s", f"{size[0]}x{size[1]}", "-pix_fmt", _FFMPEG_RAW[RAW], "-r", str(fps),
               "-i", "-", "-an", "-vcodec", "libx264", "-pix_fmt", "yuv420p",
               *mp4_quality_params(), "-tune", "animation",
               "-movflags", "+faststart", "-map_metadata", "-1",
               "-fflags", "+bitexact", "-flags:v", "+bitexact", self.tmp]
        self._proc = None
        self.pending.stop.append(self._kill)     # Ctrl-C at any moment: ffmpeg goes too
        try:
            with _ctrl_c_held():
                self._proc = subprocess.Popen(cmd, stdin=subprocess.PIPE,
                                              stdout=subprocess.DEVNULL, stderr=self._log,
                                              start_new_session=True)
        except OSError as e:
            self.pending.discard()
            self._log.close()
            from app.outputs import OutputError
            raise OutputError(self.failed(e)) from None

    def add(self, raw: bytes | memoryview) -> None:
        try:
            self._proc.stdin.write(raw)
        except (BrokenPipeError, OSError):
            self._proc.wait()
            raise OSError(0, self._why())
        self.frames += 1

    def _why(self) -> str:
        """ffmpeg's last message (why it stopped), or its exit status."""
        self._log.seek(0)
        lines = [re.sub(r"^(\[[^\]]*\]\s*)+", "", ln.strip())    # '[out#0/mp4 @ 0x..] '
                 for ln in self._log.read().decode("utf-8", "replace").splitlines()
                 if ln.strip()]
        code = self._proc.returncode
        what = f"ffmpeg stopped (exit status {code})" if code else "ffmpeg stopped"
        return f"{what}: {lines[-1]}" if lines else what

    def close(self) -> Clip:
        from app.outputs import OutputError
        try:
            try:
                self._proc.stdin.close()            # ffmpeg finishes the file and exits
            except OSError:
                pass
            code = self._proc.wait()
            if not self.frames:
                raise OSError(0, "no frame to write")
            if code != 0:
                raise OSError(0, self._why())
        except OSError as e:
            self.abandon()
            raise OutputError(self.failed(e)) from None
        except BaseException:
            self.abandon()
            raise
        self._log.close()
        return self.finish()

    def _kill(self) -> None:
        """Stop ffmpeg now (it runs in a session of its own: Ctrl-C does not reach it, and left
        alone it would finish the temporary file after the lab is gone)."""
        if self._proc is not None and self._proc.poll() is None:
            self._proc.kill()
            self._proc.wait()

    def abandon(self) -> None:
        self._kill()
        for f in (self._proc.stdin if self._proc else None, self._log):
            try:
                if f is not None:
                    f.close()
            except OSError:
                pass
        self.pending.discard()


def mp4_quality_params() -> list[str]:
    """x264's settings: quality (crf) and speed (preset)."""
    return ["-crf", str(MP4_CRF), "-preset", MP4_PRESET]


def open_clip(path: str, size: tuple[int, int], fps: int, what: str = "the clip") -> ClipWriter:
    """The writer for `path`'s extension (.gif or .mp4; check_video first). OutputError (one
    line) if it cannot start."""
    return (Mp4Writer if video_format(path) == ".mp4" else GifWriter)(path, size, fps, what)


def record_run(runner: "SceneRunner", steps: int, fps: int,
               capture: Callable[[], "pygame.Surface"], writer: ClipWriter,
               progress=None) -> None:
    """Run `steps` fixed steps with `runner`, adding `capture()` (a new surface each time) to
    `writer` at each frame's step (frame_steps); stop capturing if the run stops early
    (non-finite, a SceneError). The runner runs exactly the steps it would without a clip.
    `progress` (app.progress.Progress over the frames) is told of each frame."""
    dt = runner.tick if hasattr(runner, "tick") else runner.scene.dt   # a comparison's clock
    for at in frame_steps(steps, dt, fps):
        runner.run(at - runner.steps)
        if runner.stopped:
            break
        writer.add_surface(capture(), fresh=True)
        if progress is not None:
            progress.update(1)
    runner.run(steps - runner.steps)
