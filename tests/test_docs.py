"""The documentation checked like code (issue 18): the README stays short, the generated blocks
match the code, every relative link lands on a file and an anchor, the pictures are the ones
app/docs/images.py makes, every `python -m app ...` command written in README.md and docs/ parses
and runs (headless, shortened), and the numbers the lesson plans state are measured here where a
test can hold them on every machine (the others are written as measured, with date and load)."""

from __future__ import annotations

import contextlib
import io
import json
import re
import runpy
import shlex
from pathlib import Path

import pytest

from app.__main__ import build_bench_parser, build_exercise_parser, main
from tests.toy_scenes import close_the_window_after
from app.docs.__main__ import MARKER, ROOT, doc_files, stale_blocks

DOCS = doc_files()
PLACEHOLDERS = ("[", "|", "...", "NAME", "LABEL", "DIR", "FILE", "EVENTS", "OUT.")


def text_of(name: str) -> str:
    return (ROOT / name).read_text()


# ----- the README and the generated blocks ---------------------------------------------------------
def test_the_readme_is_short_and_links_into_docs():
    readme = text_of("README.md")
    assert len(readme) < 8000, len(readme)
    for page in ("instructors.md", "students.md", "reference.md", "scenes.md", "developers.md"):
        assert f"(docs/{page}" in readme, page


def test_the_readmes_counts_are_the_codes():
    """'eleven graded exercises', 'Up to 5000 particles', a table row per scene."""
    from app.exercises import exercise_names
    from scenes import SCENES
    from scenes.particle_dance import ParticleDanceScene
    readme = text_of("README.md")
    assert "eleven graded exercises" in readme and len(exercise_names()) == 11
    assert "Up to 5000 particles" in readme
    assert next(p for p in ParticleDanceScene.all_params() if p.name == "particles").hi == 5000
    tour = readme.split("## A tour of the scenes", 1)[1].split("\n## ", 1)[0]
    assert [c.name for c in SCENES] == re.findall(r"^\| `(\w+)` \|", tour, re.M)


def test_the_readmes_test_command_is_the_one_ci_runs():
    """The README's two commands; .ci/run runs the test one (pip quiet) on a clean checkout."""
    readme = text_of("README.md")
    assert "    pip install -r requirements.txt && python -m app\n" in readme
    assert "    pip install -r requirements-dev.txt && python -m pytest\n" in readme
    assert "pip install -q -r requirements-dev.txt && python -m pytest\n" in text_of(".ci/run")


def test_every_generated_block_matches_the_code():
    names = {m.group("name") for p in DOCS for m in MARKER.finditer(p.read_text())}
    assert {"keys", "options", "summary-fields", "scenes", "metrics", "exercises",
            "benchmarks"} <= names
    assert stale_blocks() == [], "run python -m app.docs"


# ----- links -----------------------------------------------------------------------------------------
def slug(heading: str) -> str:
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[`*_]", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path: Path) -> set[str]:
    text = path.read_text()
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    found = {slug(m.group(1)) for m in re.finditer(r"^#{1,6} (.+)$", text, re.M)}
    return found | set(re.findall(r'<a id="([^"]+)"></a>', text))


def links(path: Path) -> list[str]:
    text = re.sub(r"```.*?```", "", path.read_text(), flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    return re.findall(r"\]\(([^)\s]+)\)", text)


def test_every_metric_has_a_unit_and_the_csv_header_writes_it():
    """Each metric's entry (app/docs/texts.py) and each scene-file metric kind names a unit, the
    one the --csv header writes after the name (pure numbers and counts: none)."""
    from app.docs.texts import METRICS, UNITLESS, unit_of
    from app.scenefile.schema import METRIC_HELP
    from app.series import header
    for scene, table in METRICS.items():
        for name, (unit, meaning) in table.items():
            assert unit.strip() and meaning.strip(), (scene, name)
    assert all(unit.strip() for unit, _, _ in METRIC_HELP.values())
    assert unit_of("integrators", "rk4_step_us") == "us"        # a pattern's unit
    assert header("energy", unit_of("mass_spring_cloth", "energy")) == "energy (kg px^2/s^2)"
    assert all(header("x", u) == "x" for u in UNITLESS)


def test_slugs_are_githubs():
    assert slug("Lesson plan 1: Physics in Computer Animations and Games") == \
        "lesson-plan-1-physics-in-computer-animations-and-games"
    assert slug("Compare mode, live plots, arrows") == "compare-mode-live-plots-arrows"
    assert slug("The `--json` summary") == "the---json-summary"


@pytest.mark.parametrize("doc", DOCS, ids=[p.name for p in DOCS])
def test_every_relative_link_lands_on_a_file_and_an_anchor(doc):
    checked = 0
    for target in links(doc):
        if re.match(r"[a-z]+:", target):             # http:, https:, mailto:
            continue
        file, _, anchor = target.partition("#")
        where = (doc.parent / file).resolve() if file else doc
        assert where.exists(), f"{doc.name}: {target}: no such file"
        if anchor:
            assert where.suffix == ".md", f"{doc.name}: {target}"
            assert anchor in anchors(where), f"{doc.name}: {target}: no such anchor"
        checked += 1
    assert checked > 0 or doc.name == "students.md"


# ----- pictures ----------------------------------------------------------------------------------
def test_the_pictures_are_the_scripts_and_each_shows_its_command():
    from app.docs import images
    folder = ROOT / "docs" / "images"
    assert sorted(p.name for p in folder.iterdir()) == sorted(images.files())
    assert sum(p.stat().st_size for p in folder.iterdir()) < 600_000       # bytes: small
    shown = "\n".join(p.read_text() for p in DOCS)
    assert "](docs/images/tour.png)" in text_of("README.md")
    for picture in images.PICTURES:
        assert f"](images/{picture.file})" in shown, picture.file
        assert picture.command in shown, picture.command       # the command under the picture


# ----- every command written in the docs ---------------------------------------------------------
def commands() -> list[tuple[str, str, str]]:
    """(file, command, its comment) for every `python -m app...` line in a code block and every
    inline `python -m app ...` that is a whole command (no placeholders)."""
    found = []
    for doc in DOCS:
        text = MARKER.sub("", doc.read_text())      # generated blocks: checked against the code
        for line in text.splitlines():
            line = line.strip()
            if line.startswith("python -m app"):
                command, _, comment = line.partition("#")
                found.append((doc.name, command.strip(), comment))
        for m in re.finditer(r"`(python -m app[^`]*)`", text):
            command = " ".join(m.group(1).split())
            if len(command.split()) > 4 and not any(p in command for p in PLACEHOLDERS):
                found.append((doc.name, command, ""))
    return found


def expected_code(comment: str) -> int:
    m = re.search(r"exit code (\d)", comment)
    return int(m.group(1)) if m else 0


SHORT_SECONDS = "0.1"     # a headless command's --seconds, unless it must blow up (exit code 1)
WINDOW_FRAMES = 4         # frames a window command draws before the test closes its window
WINDOW_FRAMES_TO_FAIL = 60   # ... and one that must exit 1 (a student's code at hertz 2 runs
                             # its first step after half a simulated second)
WINDOW_FRAMES_TO_FAIL_SOON = 8   # ... at the default hertz: a starter raises in its first
                                 # step, by the third frame (tests/test_exercises.py's starters)


def as_run(args: list[str], code: int) -> list[str]:
    """The command as the docs print it, every option kept: only a headless run's --seconds is
    made short (its value, not the option: the run is the same, shorter), unless the command
    must blow up (exit code 1), which runs as long as written."""
    out = list(args)
    if "--headless" in out and code == 0:
        for i, a in enumerate(out[:-1]):
            if a == "--seconds":
                out[i + 1] = SHORT_SECONDS
    return out


def test_the_docs_commands_are_found():
    found = commands()
    files = {f for f, _, _ in found}
    assert {"README.md", "instructors.md", "reference.md", "students.md"} <= files
    assert len(found) > 60


def unique_commands() -> list[tuple[str, str, str]]:
    seen, out = set(), []
    for doc, command, comment in commands():
        if command not in seen:
            seen.add(command)
            out.append((doc, command, comment))
    return out


@pytest.fixture
def docs_folder(tmp_path, monkeypatch):
    """A folder like the repository's root (docs/ and exercises/ are there, as when a reader
    runs the docs' commands at the root) with a fresh copy of the starters in mywork/."""
    for name in ("docs", "exercises", "scenes"):
        (tmp_path / name).symlink_to(ROOT / name)
    monkeypatch.chdir(tmp_path)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["exercise", "copy", "mywork"]) == 0
    return tmp_path


@pytest.mark.parametrize("doc,command,comment", unique_commands(),
                         ids=[f"{d}:{c[14:60]}" for d, c, _ in unique_commands()])
def test_every_command_in_the_docs_runs_as_written(doc, command, comment, docs_folder,
                                                   monkeypatch, capsys):
    """Each command as printed, every option kept (as_run), in a folder like the repository's
    root: headless ones headless (their --seconds short), window ones in a window (the dummy
    video driver) closed after a few frames, exercise commands on a fresh copy of the starters;
    benchmarks and `exercise check all` are parsed here (their runs are tests/test_bench*.py's and
    tests/test_exercises.py's: tens of seconds); `python -m app.keys` prints the table
    reference.md shows. The exit code is the one the docs give ("exit code N"), else 0. Their
    outputs land in lab-output/ (one folder the docs name, in .gitignore)."""
    words = shlex.split(command)
    module, args, code = words[2], words[3:], expected_code(comment)
    where = f"{doc}: {command}"
    if module == "app.docs":
        assert set(args) <= {"--check", "--images"}, where
        return
    if module == "app.keys":
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            runpy.run_path(str(ROOT / "app" / "keys.py"), run_name="__main__")
        assert out.getvalue().strip() in text_of("docs/reference.md"), where
        return
    assert module == "app", where
    if args and args[0] == "bench":
        from app.bench import BENCHMARKS
        parsed = build_bench_parser(list(BENCHMARKS) + ["all"]).parse_args(args[1:])
        assert parsed.which in list(BENCHMARKS) + ["all"], where
        return
    if args and args[0] == "scene":              # scene check FILE: parsed, then run as written
        from app.__main__ import build_scene_parser
        build_scene_parser().parse_args(args[1:])
    elif args and args[0] == "exercise":
        from app.exercises import exercise_names
        parsed = build_exercise_parser(exercise_names()).parse_args(args[1:])
        if parsed.command == "check" and parsed.name == "all":
            return
        if parsed.command == "grade":            # tests/test_exercises_class.py runs it
            return
        if parsed.command == "copy":
            args = ["exercise", "copy", "another"]       # mywork/ holds the copy already
    elif "--headless" not in args and "--list" not in args:
        close_the_window_after(monkeypatch, WINDOW_FRAMES if not code else
                               WINDOW_FRAMES_TO_FAIL if "hertz=2" in command
                               else WINDOW_FRAMES_TO_FAIL_SOON)
    got = main(as_run(args, code))
    err = capsys.readouterr().err
    assert got == code, (where, got, err[-2000:])
    written = [p.name for p in docs_folder.iterdir()
               if p.name not in ("docs", "exercises", "scenes", "mywork", "another",
                                  "lab-output")]
    assert written == [], (where, "writes outside lab-output/", written)


def test_the_input_example_grabs_the_corner_as_reference_md_says(capsys):
    """reference.md: 'events=5 locked=41' for docs/examples/pull-a-corner.json."""
    line = next(c for d, c, _ in commands() if "pull-a-corner" in c)
    args = shlex.split(line)[3:]
    args[args.index("--input") + 1] = str(ROOT / "docs/examples/pull-a-corner.json")
    assert main(args) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["events"] == 5 and summary["metrics"]["locked"] == 41


# ----- what the lesson plans say, measured ----------------------------------------------------------
def test_lesson_2_the_materials_explicit_limits_at_rest():
    """instructors.md, lesson 2, step 1: omega_max 1513, 1353, 3026, 478, 1235 1/s and the
    explicit limit 0.62, 0.47, 0.072, 1.37, 1.62 ms (cotton, denim, leather, rubber, silk),
    after one step from rest: within 5 % (a power iteration's estimate)."""
    from scenes.mass_spring_cloth import MassSpringClothScene
    text = text_of("docs/instructors.md")
    assert "omega_max is 1513, 1353, 3026, 478\nand 1235 1/s" in text
    assert "0.62, 0.47,\n0.072, 1.37 and 1.62 ms" in text
    stated = {"cotton": (1513, 0.62e-3), "denim": (1353, 0.47e-3), "leather": (3026, 0.072e-3),
              "rubber": (478, 1.37e-3), "silk": (1235, 1.62e-3)}
    for material, (omega, limit) in stated.items():
        scene = MassSpringClothScene({"material": material})
        scene.advance()
        m = scene.metrics()
        assert m["omega_max"] == pytest.approx(omega, rel=0.05), material
        assert m["explicit_limit_h"] == pytest.approx(limit, rel=0.05), material


def test_lesson_1_integrators_after_10_s_and_past_the_limit_at_hertz_4():
    """instructors.md, lesson 1, step 2: at 60 Hz forward Euler's E/E0 ~6.3e5 after 10 s,
    symplectic Euler and Verlet near 1 (1.075, 1.013), RK4 0.99990, implicit Euler ~2e-6; at
    hertz 4, forward Euler, symplectic Euler, Verlet and midpoint blow up, RK4 and implicit Euler
    do not. Asserted as orders of magnitude and bounds."""
    from scenes.integrators import IntegratorsScene
    scene = IntegratorsScene({})
    for _ in range(600):
        scene.advance()
    m = scene.metrics()
    assert 1e5 < m["euler_energy_ratio"] < 1e7
    assert 0.95 < m["symplectic_euler_energy_ratio"] < 1.15
    assert 0.98 < m["verlet_energy_ratio"] < 1.05
    assert abs(m["rk4_energy_ratio"] - 1) < 1e-3
    assert m["implicit_euler_energy_ratio"] < 1e-4
    lab = IntegratorsScene(dict(IntegratorsScene.find_card("hertz 4: past Verlet").settings))
    for _ in range(40):
        lab.advance()
    m = lab.metrics()
    for name in ("euler", "symplectic_euler", "verlet", "midpoint"):
        assert m[f"{name}_blew_up_t"] is not None, name
    assert m["rk4_blew_up_t"] is None and m["implicit_euler_blew_up_t"] is None


def test_lesson_1_the_cloths_stretch_falls_with_the_iterations():
    """instructors.md, lesson 1, step 5: after 2 s the largest stretch is 55 %, 8.7 % and 1.4 %
    at 2, 10 and 50 iterations (asserted: each a band around it, and the order)."""
    from scenes.cloth import ClothScene
    stretch = {}
    for iterations in (2, 10, 50):
        scene = ClothScene({"iterations": iterations})
        for _ in range(120):
            scene.advance()
        stretch[iterations] = scene.metrics()["max_stretch"]
    assert 0.3 < stretch[2] < 0.9 and 0.04 < stretch[10] < 0.15 and 0.005 < stretch[50] < 0.03


def test_lesson_1_tunneling_most_balls_pass_through_the_l():
    """instructors.md, lesson 1, step 6: 'Look for tunneling': 37 of 40 balls through the L in
    10 s (asserted: more than half of those spawned)."""
    from scenes.falling_balls import FallingBallsScene
    card = FallingBallsScene.find_card("Look for tunneling")
    scene = FallingBallsScene(dict(card.settings))
    while scene.time < 10.0 - 1e-9:
        scene.advance()
    m = scene.metrics()
    assert m["balls_spawned"] == 40 and m["tunneled"] > m["balls_spawned"] / 2
