"""The channel from a check's child process back to the grader, and how the grader reads it.

The child imports the student's file, so whatever runs in it may write on the channel too (it is
a pipe, found in /proc/self/fd in a moment). The parent therefore trusts nothing it reads:

  * framing: each message is MAGIC (4 bytes), a length (4 bytes, big-endian) and that many bytes
    of UTF-8 JSON; anything else is junk and ends the check;
  * size: a frame longer than MAX_FRAME bytes is refused as soon as its header says so (nothing
    is buffered past it); time is bounded by the reader's caller (a deadline per check);
  * content: JSON only (no pickle: unpickling runs code), at most MAX_DEPTH deep, text at most
    MAX_TEXT characters; the frame must carry this run's token and the index of the check the
    parent waits for, with a known status. `Frame` is what passes.

The token (random per child, known to the parent and the child's own code) keeps junk and blind
forgeries out; code written to find it in the child's memory could forge a frame, but a frame
only carries raw values, and the verdict on them is the parent's (app/exercises/base.py).
"""

from __future__ import annotations

import json
import os
import struct
from dataclasses import dataclass, field
from typing import Any

MAGIC = b"LABx"
HEADER = struct.Struct(">4sI")
MAX_FRAME = 8 << 20          # bytes of one frame's JSON (the largest check sends ~0.3 MB)
MAX_DEPTH = 6                # nesting of lists and objects
MAX_TEXT = 64_000            # characters of one string (a traceback is capped at ~12 000)
STATUSES = ("ok", "bad", "unwritten", "error", "lab")


class ChannelError(Exception):
    """What came over the channel is not a frame of this run (the message says what it was)."""


@dataclass
class Frame:
    check: int               # -1: the import; k: the exercise's k-th check
    status: str              # ok | bad (a BadAnswer) | unwritten | error (theirs) | lab (ours)
    raw: dict[str, Any] = field(default_factory=dict)
    error: str = ""
    notes: list[str] = field(default_factory=list)


def encode(token: str, check: int, status: str, raw: Any = None, error: str = "",
           notes: list[str] | None = None) -> bytes:
    """One frame's bytes. NaN and infinities are kept (JSON's NaN/Infinity words): a NaN that
    came back must reach the judge, which fails it."""
    payload = json.dumps({"token": token, "check": check, "status": status, "raw": raw or {},
                          "error": error[:MAX_TEXT // 2], "notes": notes or []},
                         allow_nan=True).encode()
    if len(payload) > MAX_FRAME:
        payload = json.dumps({"token": token, "check": check, "status": "lab", "raw": {},
                              "error": f"the check's values took {len(payload):,} bytes, more "
                              f"than the channel's {MAX_FRAME:,}", "notes": []}).encode()
    return HEADER.pack(MAGIC, len(payload)) + payload


def write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        n = os.write(fd, view)
        view = view[n:]


def _depth_ok(value: Any, depth: int = 0) -> bool:
    if depth > MAX_DEPTH:
        return False
    if isinstance(value, dict):
        return all(isinstance(k, str) and _depth_ok(v, depth + 1) for k, v in value.items())
    if isinstance(value, list):
        return all(_depth_ok(v, depth + 1) for v in value)
    if isinstance(value, str):
        return len(value) <= MAX_TEXT
    return value is None or isinstance(value, (bool, int, float))


def _no_deep_nesting(payload: bytes) -> bool:
    """Refuse '[[[[...' before json.loads recurses into it (a RecursionError otherwise)."""
    depth = deepest = 0
    in_string = escaped = False
    for byte in payload:
        if in_string:
            if escaped:
                escaped = False
            elif byte == 0x5C:                  # backslash
                escaped = True
            elif byte == 0x22:                  # closing quote
                in_string = False
        elif byte == 0x22:
            in_string = True
        elif byte in (0x5B, 0x7B):              # [ {
            depth += 1
            deepest = max(deepest, depth)
            if deepest > MAX_DEPTH + 1:
                return False
        elif byte in (0x5D, 0x7D):
            depth -= 1
    return True


def parse(payload: bytes, token: str, expected: int) -> Frame:
    """A frame's JSON, validated; ChannelError saying what is wrong otherwise."""
    if not _no_deep_nesting(payload):
        raise ChannelError(f"a frame nested deeper than {MAX_DEPTH} levels")
    try:
        data = json.loads(payload.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as e:
        raise ChannelError(f"a frame that is not JSON ({type(e).__name__})") from None
    if not isinstance(data, dict) or not _depth_ok(data):
        raise ChannelError("a frame of the wrong form")
    if data.get("token") != token:
        raise ChannelError("a frame without this run's token (not written by the grader)")
    check, status = data.get("check"), data.get("status")
    if isinstance(check, bool) or check != expected:
        raise ChannelError(f"a frame for check {check!r} while check {expected} was running")
    if status not in STATUSES:
        raise ChannelError(f"a frame with an unknown status {str(status)[:20]!r}")
    raw, error, notes = data.get("raw"), data.get("error"), data.get("notes")
    if not isinstance(raw, dict) or not isinstance(error, str) or not isinstance(notes, list) \
            or not all(isinstance(n, str) for n in notes):
        raise ChannelError("a frame of the wrong form")
    return Frame(check, status, raw, error, notes[:20])


class FrameReader:
    """Bytes in, frames' payloads out: feed() what the pipe gave and take the payloads complete
    so far (parse() validates each). Junk or a frame too large stops the reading: the payloads
    before it still count, and `junk` says what came after them."""

    def __init__(self) -> None:
        self.buffer = bytearray()
        self.junk: str | None = None

    def feed(self, data: bytes) -> list[bytes]:
        if self.junk is not None:
            return []
        self.buffer += data
        frames = []
        while len(self.buffer) >= HEADER.size:
            magic, length = HEADER.unpack_from(self.buffer)
            if magic != MAGIC:
                self.junk = f"bytes that are not a frame ({bytes(self.buffer[:12])!r}...)"
                break
            if length > MAX_FRAME:
                self.junk = f"a frame of {length:,} bytes (at most {MAX_FRAME:,})"
                break
            if len(self.buffer) < HEADER.size + length:
                break
            frames.append(bytes(self.buffer[HEADER.size:HEADER.size + length]))
            del self.buffer[:HEADER.size + length]
        return frames

    def partial(self) -> bool:
        """True while part of a frame is buffered (a child that ends now cut it short)."""
        return bool(self.buffer)


__all__ = ["MAGIC", "HEADER", "MAX_FRAME", "Frame", "FrameReader", "ChannelError", "encode",
           "parse", "write_all"]
