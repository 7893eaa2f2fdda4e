"""`python -m app.docs`: rewrite the generated parts of README.md and docs/*.md from the code.

    python -m app.docs            rewrite every generated block in place
    python -m app.docs --check    say which blocks differ from what the code generates (exit 1)
    python -m app.docs --images   remake the pictures in docs/images/ (headless runs, a few seconds)

A generated block sits between two markers that name it:

    <!-- generated: keys (python -m app.docs) -->
    ...
    <!-- end generated: keys -->

What each block holds and where it comes from: app/docs/blocks.py. The hand-written words about
metrics and --json fields: app/docs/texts.py.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from pathlib import Path

from app.outputs import write_text

ROOT = Path(__file__).resolve().parents[2]
MARKER = re.compile(r"(<!-- generated: (?P<name>[\w-]+) \(python -m app\.docs\) -->\n)"
                    r"(?P<body>.*?)"
                    r"(<!-- end generated: (?P=name) -->)", re.S)


def doc_files(root: Path = ROOT) -> list[Path]:
    """README.md and every Markdown file under docs/."""
    return [root / "README.md", *sorted((root / "docs").glob("*.md"))]


def filled(text: str, made: dict[str, str]) -> str:
    """`text` with every generated block replaced by what the code makes now."""
    def block(m: re.Match) -> str:
        return m.group(1) + made[m.group("name")] + "\n" + m.group(4)
    return MARKER.sub(block, text)


def generate(names: set[str]) -> dict[str, str]:
    from app.docs.blocks import BLOCKS
    unknown = names - set(BLOCKS)
    if unknown:
        raise SystemExit(f"python -m app.docs: unknown generated block(s) {sorted(unknown)}; "
                         f"known: {', '.join(BLOCKS)}")
    return {name: BLOCKS[name]().rstrip("\n") for name in sorted(names)}


def stale_blocks(root: Path = ROOT) -> list[tuple[Path, str]]:
    """(file, block name) of every generated block that differs from what the code makes."""
    texts = {path: path.read_text() for path in doc_files(root)}
    made = generate({m.group("name") for t in texts.values() for m in MARKER.finditer(t)})
    return [(path, m.group("name")) for path, t in texts.items()
            for m in MARKER.finditer(t) if m.group("body") != made[m.group("name")] + "\n"]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m app.docs", allow_abbrev=False,
                                description="rewrite the generated parts of the docs")
    p.add_argument("--check", action="store_true", help="only say which blocks are stale")
    p.add_argument("--images", action="store_true", help="remake docs/images/ as well")
    args = p.parse_args(argv)
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    if args.check:
        stale = stale_blocks()
        for path, name in stale:
            print(f"{path.relative_to(ROOT)}: block '{name}' differs from the code; "
                  "run python -m app.docs")
        if not stale:
            print("the generated parts of the docs match the code")
        return 1 if stale else 0
    texts = {path: path.read_text() for path in doc_files()}
    made = generate({m.group("name") for t in texts.values() for m in MARKER.finditer(t)})
    for path, text in texts.items():
        new = filled(text, made)
        if new != text:
            write_text(path, new, what="the docs")    # whole or not at all
            print(f"rewrote {path.relative_to(ROOT)}")
    if args.images:
        from app.docs.images import make_images
        make_images()
    return 0


if __name__ == "__main__":
    sys.exit(main())
