"""The lab's engine and shell: scene contract, fixed-step loop, window, headless runner, benchmarks.

Nothing in `app/` is scene content; scenes live in `scenes/` and are listed in `scenes/__init__.py`.
"""

import os as _os

# pygame prints a greeting on import; keep stdout clean for --json and the tests.
_os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


def _ctrl_c_while_starting(signum, frame):
    """Ctrl-C while `python -m app` imports its modules (numpy, pygame, pymunk: up to a second
    on a busy machine): nothing is written yet, so say so in one line and leave with exit code
    130, not a KeyboardInterrupt traceback from inside an import. app/__main__.py puts Python's
    own handler back before the command runs (its outputs are cleaned up on Ctrl-C there)."""
    try:
        _os.write(2, b"python -m app: interrupted (Ctrl-C) while starting; nothing was written\n")
    finally:
        _os._exit(130)


def _launched_as_the_command_line() -> bool:
    import sys
    argv = getattr(sys, "orig_argv", [])
    return any(a == "-m" and b == "app" for a, b in zip(argv, argv[1:]))


if _launched_as_the_command_line():          # `python -m app ...`, not an import by a test
    import signal as _signal
    if _signal.getsignal(_signal.SIGINT) is _signal.default_int_handler:
        _signal.signal(_signal.SIGINT, _ctrl_c_while_starting)


def started() -> None:
    """`python -m app` has imported its modules: Ctrl-C is Python's KeyboardInterrupt again,
    which the command line turns into one line and exit code 130, its outputs cleaned up."""
    import signal
    if signal.getsignal(signal.SIGINT) is _ctrl_c_while_starting:
        signal.signal(signal.SIGINT, signal.default_int_handler)
