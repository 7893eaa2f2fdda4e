"""The lab's engine and shell: scene contract, fixed-step loop, window, headless runner, benchmarks.

Nothing in `app/` is scene content; scenes live in `scenes/` and are listed in `scenes/__init__.py`.
"""

import os as _os

# pygame prints a greeting on import; keep stdout clean for --json and the tests.
_os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
