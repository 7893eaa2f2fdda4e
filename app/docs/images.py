"""The pictures in docs/images/: every one made here from headless runs, so none goes stale.

`python -m app.docs --images` remakes them all (4.4 s measured on 2026-11-24, 2 cores, load
~2.5). Each picture is one command of the lab (`--headless ... --screenshot`), the same command a reader can run; the tour in the README
is eight such screenshots (`--clean`: the scene alone) laid out in one PNG with their names. The
command of each picture is written under it in the docs (tests/test_docs.py checks that the docs
show exactly these pictures, and runs the commands shortened).

The HUD in a screenshot shows measured timings (ms per step), so remaking a picture changes a few
pixels even when nothing else changed: that is why the pictures are not compared byte for byte.
"""

from __future__ import annotations

import shlex
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
IMAGES = ROOT / "docs" / "images"


@dataclass(frozen=True)
class Picture:
    """docs/images/<file>, made by `command` (run with --screenshot docs/images/<file>);
    `code` is its expected exit code (1: a pane that blows up on purpose)."""

    file: str
    command: str
    code: int = 0

    def argv(self, out: Path) -> list[str]:
        """The command's arguments, its screenshot written to `out` (the docs print it writing
        to lab-output/, the folder their commands write to)."""
        args = shlex.split(self.command)[3:]
        return [str(out) if a == f"lab-output/{self.file}" else a for a in args]


# the README's tour: one tile per scene (the scene alone, 400 px wide), in the registry's order
TOUR_TILE = 400
TOUR: dict[str, str] = {
    "cloth": "--set wind=on --seconds 3",
    "cloth_collisions": "--try 'Pull the tablecloth' --seconds 3",
    "mass_spring_cloth": "--try 'Silk in the wind' --seconds 3",
    "falling_balls": "--try 'Catch 60 balls in a box' --seconds 8",
    "pivoting_l": "--seconds 12",
    "newtons_cradle": "--seconds 0.4",
    "double_pendulum": "--seconds 6",
    "integrators": "--seconds 3",
    "particle_dance": "--try 'Like your own kind' --seconds 10",
}

PICTURES: tuple[Picture, ...] = (
    Picture("cloth-1x10-vs-10x1.png",
            "python -m app --headless --scene cloth --try '1x10 vs 10x1' --seconds 2 --width 960 "
            "--screenshot lab-output/cloth-1x10-vs-10x1.png"),
    Picture("explicit-vs-implicit.png",
            "python -m app --headless --scene mass_spring_cloth --try 'Explicit vs implicit at 60 Hz' "
            "--seconds 1 --width 960 --screenshot lab-output/explicit-vs-implicit.png", code=1),
    Picture("integrators-hertz-4.png",
            "python -m app --headless --scene integrators --try 'hertz 4: past Verlet' "
            "--seconds 4 --width 960 --screenshot lab-output/integrators-hertz-4.png"),
    Picture("particle-dance-all-pairs-vs-grid.png",
            "python -m app --headless --scene particle_dance --try 'All pairs vs grid' "
            "--seconds 1 --width 960 "
            "--screenshot lab-output/particle-dance-all-pairs-vs-grid.png"),
)


def tour_command(scene: str) -> str:
    return (f"python -m app --headless --scene {scene} {TOUR[scene]} --clean "
            f"--width {TOUR_TILE}")


def files() -> list[str]:
    """Every file this module makes: what docs/images/ must hold."""
    return ["tour.png"] + [p.file for p in PICTURES]


def _run(argv: list[str], code: int) -> None:
    import contextlib
    import io
    from app.__main__ import main
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        got = main(argv)
    if got != code:
        raise RuntimeError(f"python -m app {shlex.join(argv)} exited {got}, not {code}")


def make_tour(out: Path) -> None:
    """Every scene in one picture: rows of 4 tiles, each scene's name under it."""
    import pygame

    from app.draw import save_png
    from app.draw.text import font
    cols, cell_h, label_h = 4, 300, 26
    with tempfile.TemporaryDirectory() as tmp:
        tiles = []
        for scene in TOUR:
            shot = Path(tmp) / f"{scene}.png"
            _run(shlex.split(tour_command(scene))[3:] + ["--screenshot", str(shot)], 0)
            tiles.append((scene, pygame.image.load(str(shot))))
        rows = -(-len(tiles) // cols)
        sheet = pygame.Surface((cols * TOUR_TILE, rows * (cell_h + label_h)))
        sheet.fill(tiles[0][1].get_at((0, 0)))          # the scenes' own background
        for i, (scene, tile) in enumerate(tiles):
            scale = min(1.0, cell_h / tile.get_height())
            if scale < 1.0:
                tile = pygame.transform.smoothscale(
                    tile, (round(tile.get_width() * scale), round(tile.get_height() * scale)))
            x0, y0 = (i % cols) * TOUR_TILE, (i // cols) * (cell_h + label_h)
            sheet.blit(tile, (x0 + (TOUR_TILE - tile.get_width()) // 2,
                              y0 + (cell_h - tile.get_height()) // 2))
            label = font(24).render(scene, True, (230, 230, 235))
            sheet.blit(label, (x0 + (TOUR_TILE - label.get_width()) // 2, y0 + cell_h + 2))
        save_png(sheet, out, what="the picture")     # whole or not at all


def make_images(folder: Path = IMAGES) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    make_tour(folder / "tour.png")
    print(f"made {folder / 'tour.png'}")
    for p in PICTURES:
        _run(p.argv(folder / p.file), p.code)
        print(f"made {folder / p.file}")
