"""Wrapping overlay text into rows of a given width in pixels, between phrases ("t = 3.82 s |
physics 6.84 ms/step": never "physics" / "6.84 ms/step"), then between words (a number keeps its
unit), a word wider than a row cut after a '/', ',' or '='. app/draw/hud.py re-exports these."""

from __future__ import annotations

import re
from functools import lru_cache

import pygame

from app.draw.text import font, text_width

# units the wrap keeps on the line of the number before them ('6.84 ms/step', never '6.84' then
# 'ms/step' on the next line)
UNITS = {"ms", "s", "ms/step", "J", "px", "px/s", "Hz", "%", "kg", "1/s", "MB", "us",
         "frames", "steps", "sweeps/step"}


def _is_unit(word: str) -> bool:
    return word.rstrip(",;:.)") in UNITS


def _cut(text: str, f: pygame.font.Font, width: int) -> tuple[str, str]:
    """Split a line holding one word wider than `width` (a file's path, a setting): the longest
    head that fits, cut after its last '/' if there is one in its second half, else after its
    last ',' or '=' ("integrator=" / "implicit_euler", never "implicit_eul" / "er")."""
    n = 1
    while n < len(text) and f.size(text[: n + 1])[0] <= width:
        n += 1
    if n >= len(text):
        return text, ""
    slash = max(text.rfind("/", 0, n), text.rfind("\\", 0, n))
    joint = max(text.rfind(",", 0, n), text.rfind("=", 0, n))
    if slash + 1 > n // 2:
        n = slash + 1
    elif joint > 0:
        n = joint + 1
    return text[:n], text[n:]


def longest_word(text: str, size: int) -> int:
    """The width in pixels, at text `size`, of the widest piece `wrap` keeps whole: a word, or
    a setting's part after '=' or ',' ("integrator=" / "implicit_euler")."""
    f = font(size)
    pieces = re.split(r"\s+|(?<=[=,])", text)
    return max((f.size(p)[0] for p in pieces if p), default=0)


def wrap(text: str, f: pygame.font.Font, width: int) -> list[str]:
    """Split `text` into lines no wider than `width` pixels (paragraph breaks kept). A number
    keeps its unit on its line; a word wider than the line (a file's path) is cut, after a '/'
    where it can be. Remembered: most of a HUD's text is the same frame after frame, and
    measuring it word by word cost a 4-pane frame ~1,300 font measurements (bench frames)."""
    return list(_wrap_cached(text, f, width))


@lru_cache(maxsize=4096)
def _wrap_cached(text: str, f: pygame.font.Font, width: int) -> tuple[str, ...]:
    return tuple(_wrap(text, f, width))


# what parts the phrases of a line: ' | ', '; ' (its ';' kept) or two spaces, unless a number a
# format padded follows ("slide  37.7 px" is one phrase)
PHRASE_GAP = re.compile(r"(\s+\|\s+| {2,}(?![-+]?\.?\d)|; )")


def _wrap(text: str, f: pygame.font.Font, width: int) -> list[str]:
    """Phrases are kept whole where they fit a row: a row breaks between phrases (a ' | '
    dropped there), never inside one ("physics" / "2.47 ms/step" read as two things); a
    phrase wider than a row breaks between its words."""
    lines: list[str] = []
    for para in text.split("\n"):
        indent = para[: len(para) - len(para.lstrip())]
        parts = PHRASE_GAP.split(para.strip())
        if not para.strip():
            lines.append("")
            continue
        line = ""
        for k, (phrase, sep) in enumerate(zip(parts[::2], [""] + parts[1::2])):
            joined = line + sep + phrase if line else indent + phrase
            if text_width(f, joined) <= width:
                line = joined
                continue
            if line:
                lines.append(line + (";" if sep == "; " else ""))
            rows = _wrap_words(phrase, f, width, indent if k == 0 else
                               (indent + "  " if indent else ""), indent)
            lines.extend(rows[:-1])
            line = rows[-1]
        lines.append(line)
    return lines


def _wrap_words(para: str, f: pygame.font.Font, width: int, first: str, indent: str) -> list:
    """A phrase broken between its words (a number keeps its unit), its first row after `first`,
    the next indented under `indent`; a word wider than a row is cut."""
    lines: list[str] = []
    words: list[str] = []
    for w in para.split():    # '=' holds its right side, and its left unless that follows a
        # number ("h = 16.667 ms" whole; "2 iterations x 1 substeps" / "= 2 sweeps/step")
        after_number = len(words) > 1 and words[-2][-1:].isdigit()
        if words and ((w == "=" and not after_number) or words[-1] == "=" or
                      words[-1].endswith(" =") or (_is_unit(w) and words[-1][-1:].isdigit())):
            words[-1] += " " + w
        else:
            words.append(w)
    line = first + words[0]
    for w in words[1:] + [None]:
        while text_width(f, line) > width and len(line) > 1:
            head, line = _cut(line, f, width)
            lines.append(head)
        if w is None:
            break
        candidate = line + " " + w
        if text_width(f, candidate) <= width:
            line = candidate
        else:
            lines.append(line)
            line = indent + "  " + w if indent else w
    lines.append(line)
    return lines


def pack(items: list[str], f: pygame.font.Font, width: int, sep: str = "  |  ") -> list[str]:
    """Join items with `sep` into lines no wider than `width`, never splitting an item."""
    lines: list[str] = []
    for item in items:
        if lines and text_width(f, lines[-1] + sep + item) <= width:
            lines[-1] += sep + item
        else:
            lines.append(item)
    return lines
