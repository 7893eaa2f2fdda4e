"""The harness: the lab modules a check's child needs, without the exercise's answer.

The grader's sandboxed child (app/exercises/sandbox.py) is a fresh `python -I` that may read
Python's own files and one folder of the lab's: its harness, made here once per exercise and
process. It holds the modules the exercise's checks import, found by following every import of
app/exercises/child.py and the exercise's grader (but those inside its `reference()`), and in
them the exercise's reference answer is a stub that raises: the functions `reference()` imports
(and, for a class, the methods it uses), and in a module that holds them every other function
the harness does not need. A package file that knows only this exercise replaces
app/exercises/__init__.py (the real one imports every grader). The folders are removed when the
grader's process ends.
"""

from __future__ import annotations

import ast
import compileall
import importlib.util
import os
import shutil
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LAB_PACKAGES = ("app", "scenes")


def _module_file(name: str) -> Path | None:
    parts = name.split(".")
    if parts[0] not in LAB_PACKAGES:
        return None
    base = REPO.joinpath(*parts)
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    return None


def _imports(tree: ast.AST, here: str, skip: set[ast.AST]) -> set[str]:
    """The lab modules a module's code imports anywhere (but in the nodes of `skip`)."""
    return _lab_modules(_import_nodes(tree, skip), here)


def _import_nodes(tree: ast.AST, skip: set[ast.AST] | tuple = ()) -> list[ast.stmt]:
    """Every import statement in `tree`, however deep (but in the nodes of `skip`)."""
    found: list[ast.stmt] = []
    stack = [tree]
    while stack:
        node = stack.pop()
        if node in skip:
            continue
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append(node)
        elif not isinstance(node, ast.expr):    # no import statement lives in an expression
            stack.extend(ast.iter_child_nodes(node))
    return found


def _lab_modules(nodes: list[ast.stmt], here: str) -> set[str]:
    found: set[str] = set()
    for node in nodes:
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
        else:
            mod = node.module or ""
            if node.level:
                pkg = here.split(".")[:-node.level]
                mod = ".".join(pkg + ([mod] if mod else []))
            found.add(mod)
            found |= {f"{mod}.{a.name}" for a in node.names}
    return {m for m in found if m.split(".")[0] in LAB_PACKAGES}


_PARSED: dict[tuple[Path, int, int], tuple[str, list[ast.stmt]]] = {}


def _parsed(path: Path) -> tuple[str, list[ast.stmt]]:
    """A lab module's source and its import statements, parsed once per process and version of
    the file (the pymunk exercises share ~90 modules: parsing them for each exercise was most of
    a harness's cost)."""
    st = path.stat()
    key = (path, st.st_mtime_ns, st.st_size)
    if key not in _PARSED:
        source = path.read_text()
        _PARSED[key] = source, _import_nodes(ast.parse(source))
    return _PARSED[key]


def reference_of(grader: Path) -> tuple[ast.FunctionDef | None, list[tuple[str, str, str | None]]]:
    """The grader's `reference()` and what it takes from the lab: (module, name, attribute)."""
    tree = ast.parse(grader.read_text())
    ref = next((n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "reference"),
               None)
    taken: list[tuple[str, str, str | None]] = []
    if ref is None:
        return None, taken
    names: dict[str, str] = {}
    for node in ast.walk(ref):
        if isinstance(node, ast.ImportFrom) and node.module:
            for a in node.names:
                names[a.asname or a.name] = node.module
                taken.append((node.module, a.name, None))
    for node in ast.walk(ref):                  # Class.method: only the method is the answer
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                and node.value.id in names:
            taken.append((names[node.value.id], node.value.id, node.attr))
    return ref, taken


STUB = ("raise RuntimeError(\"the lab's answer is not in the grader's sandbox: the grader grades "
        "the code you write\")")


def _used_names(node: ast.AST) -> set[str]:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | \
        {n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)}


def strip(source: str, answer: set[str], methods: set[tuple[str, str]],
          wanted: set[str] | None) -> str:
    """`source` with the exercise's answer taken out: the bodies of the functions `answer`, the
    methods `methods` (class, name), and (when `wanted` is a set: the names the harness imports
    from this module) every other top-level function that those names do not need, replaced by a
    stub that raises. Docstrings stay: they are the exercise's text."""
    tree = ast.parse(source)
    defs = {n.name: n for n in tree.body
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))}
    cut = set(answer)
    if wanted is not None:
        keep: set[str] = set()
        todo = [n for n in wanted if n in defs]
        while todo:
            name = todo.pop()
            if name in keep or name in answer:
                continue
            keep.add(name)
            todo += [n for n in _used_names(defs[name]) if n in defs]
        cut |= {n for n, d in defs.items() if n not in keep
                and isinstance(d, (ast.FunctionDef, ast.AsyncFunctionDef))}
    lines = source.splitlines(keepends=True)
    spans = []
    for node in tree.body:
        targets = []
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name in cut:
            targets.append(node)
        if isinstance(node, ast.ClassDef):
            targets += [f for f in node.body
                        if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))
                        and (node.name, f.name) in methods]
        for f in targets:
            body = f.body
            first = body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) \
                    and isinstance(first.value.value, str) and len(body) > 1:
                body = body[1:]                 # keep the docstring: it is the exercise's text
            indent = " " * body[0].col_offset
            spans.append((body[0].lineno - 1, body[-1].end_lineno, indent))
    for start, end, indent in sorted(spans, reverse=True):
        lines[start:end] = [f"{indent}{STUB}\n"]
    return "".join(lines)


HARNESS_INIT = '''"""The grader's sandbox: this exercise only (made by app/exercises/harness.py)."""
import importlib

NAMES = ({name!r},)


def _grader(name):
    return importlib.import_module(f"app.exercises.{{name}}.grader")


def get_exercise(name):
    return _grader(name).EXERCISE if name in NAMES else None


def exercise_names():
    return list(NAMES)


def scene_class(name):
    if name not in NAMES:
        return None
    return importlib.import_module(f"app.exercises.{{name}}.scene").SCENE
'''

CHILD_SIDE = ("app.exercises.child", "app.exercises.channel", "app.exercises.loading",
              "app.exercises.base")


def harness_files(exercise: str, stub: bool = True) -> dict[str, str]:
    """The harness of one exercise: relative path -> source. The lab modules its checks import
    (followed through every import but those inside `reference()`), the exercise's reference
    stubbed out, and a package file that knows this exercise only."""
    grader = REPO / "app" / "exercises" / exercise / "grader.py"
    ref, taken = reference_of(grader)
    roots = [*CHILD_SIDE, f"app.exercises.{exercise}.grader"]
    if not stub:                                # the reference's own run: follow it too
        roots += [module for module, _, _ in taken]
        ref, taken = None, []
    seen: dict[str, Path] = {}
    imports: dict[str, list[ast.stmt]] = {}     # each module's import statements
    todo = list(roots)
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        path = _module_file(name)
        if path is None:
            continue
        seen[name] = path
        parts = name.split(".")
        todo += [".".join(parts[:k]) for k in range(1, len(parts))]     # its packages
        if name == "app.exercises":
            continue                            # replaced by HARNESS_INIT
        nodes = _parsed(path)[1]
        if path == grader and ref is not None:  # what `reference()` imports is the answer's
            nodes = [n for n in nodes if not ref.lineno <= n.lineno <= ref.end_lineno]
        imports[name] = nodes
        here = name + (".__init__" if path.name == "__init__.py" else "")
        todo += sorted(_lab_modules(nodes, here))
        if name == "app.exercises.pymunk_run":    # it finds the exercise's scene by name
            todo.append(f"app.exercises.{exercise}.scene")
    by_module: dict[str, tuple[set[str], set[tuple[str, str]]]] = {}
    for module, name, attr in taken:
        names, methods = by_module.setdefault(module, (set(), set()))
        if attr is None:
            names.add(name)
        else:
            methods.add((name, attr))
    # what the harness takes from each module that holds the answer (None: all of it)
    wanted: dict[str, set[str] | None] = {m: set() for m in by_module}
    for nodes in imports.values():
        for node in nodes:
            if isinstance(node, ast.ImportFrom) and node.module in wanted \
                    and wanted[node.module] is not None:
                wanted[node.module] |= {a.name for a in node.names}
            elif isinstance(node, ast.Import):
                for a in node.names:
                    if a.name in wanted:
                        wanted[a.name] = None
    files = {}
    for name, path in seen.items():
        rel = str(path.relative_to(REPO))
        source = _parsed(path)[0]
        if name == "app.exercises":
            source = HARNESS_INIT.format(name=exercise)
        elif name in by_module:
            names, methods = by_module[name]
            classes = {c for c, _ in methods}
            source = strip(source, names - classes, methods, wanted[name])
        files[rel] = source
    return files


_HARNESS: dict[str, str] = {}
_ROOT: list[str] = []
_OWNER: list[int] = []


def root() -> str:
    """This process's temporary folder for harnesses and the children's folders."""
    if not _ROOT:
        import atexit
        root = tempfile.mkdtemp(prefix="lab-grader-")
        os.chmod(root, 0o755)
        _ROOT.append(root)
        _OWNER[:] = [os.getpid()]
        atexit.register(cleanup)
    return _ROOT[0]


def cleanup() -> None:
    """Remove this process's harnesses and folders (atexit does it too; os._exit skips atexit)."""
    if _OWNER and _OWNER[0] != os.getpid():      # a forked copy: the folders are not its own
        return
    for root in _ROOT:
        shutil.rmtree(root, ignore_errors=True)
    _ROOT.clear()
    _HARNESS.clear()


def harness(exercise: str, stub: bool = True) -> str:
    """The folder of the exercise's harness (made once per process, compiled, read-only to the
    child). stub=False keeps the reference (the grader's own `--reference` run)."""
    key = exercise + ("" if stub else "+reference")
    if key not in _HARNESS:
        folder = tempfile.mkdtemp(prefix=f"harness-{key}-", dir=root())
        os.chmod(folder, 0o755)
        for rel, source in harness_files(exercise, stub).items():
            target = Path(folder, rel)
            target.parent.mkdir(parents=True, exist_ok=True)
            original = REPO / rel
            if source == original.read_text():     # unchanged: its compiled form is still good
                shutil.copy2(original, target)
                try:
                    cached = importlib.util.cache_from_source(str(original))
                    pyc = importlib.util.cache_from_source(str(target))
                    os.makedirs(os.path.dirname(pyc), exist_ok=True)
                    shutil.copy2(cached, pyc)
                except (OSError, NotImplementedError):
                    pass
            else:
                target.write_text(source)
        compileall.compile_dir(folder, quiet=2)      # what was not compiled yet
        for d, dirs, files in os.walk(folder):
            os.chmod(d, 0o755)
            for f in files:
                os.chmod(os.path.join(d, f), 0o644)
        _HARNESS[key] = folder
    return _HARNESS[key]


__all__ = ["harness", "harness_files", "cleanup", "root", "STUB", "REPO", "LAB_PACKAGES"]
