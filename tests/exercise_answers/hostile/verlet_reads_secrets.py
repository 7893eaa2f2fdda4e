"""Hostile (issue 23): reads what is not its to read: /etc/shadow, root's home, the repository's
own files (its git config, the tests), another folder in /tmp; its step is right. Landlock lets
it read Python's files and its harness only: every read is refused (it runs as uid 0 without
capabilities here, the owner of /etc/shadow)."""
from pathlib import Path

_repo = Path(__file__).resolve().parents[3]
for _path in ("/etc/shadow", "/root", _repo / ".git", _repo / "tests" / "test_exercises.py",
              "/tmp"):
    try:
        _p = Path(_path)
        _got = sorted(x.name for x in _p.iterdir()) if _p.is_dir() else _p.read_bytes()[:10]
        print(f"READ {_path}")
    except OSError as _e:
        print(f"refused {_path}: {type(_e).__name__}")


def verlet_step(x, x_prev, a, h, drag):
    return x + (1 - drag) * (x - x_prev) + a * h * h, x
