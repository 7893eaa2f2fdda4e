"""Ctrl-C held back across code that would drop it (app/ctrl_c.py): numba's compile dropped a
KeyboardInterrupt raised in llvmlite's ctypes callback, and `import numba` wrapped one in a
RuntimeError (hostile command lines, seed 6)."""

import ctypes
import os
import signal

import pytest

from app import ctrl_c
from app.__main__ import main


@pytest.fixture(autouse=True)
def pythons_own_handler():
    """Python's KeyboardInterrupt handler during each test, whatever this process inherited (a
    suite started in the background by a shell, or under nohup, has SIGINT ignored: held()
    then rightly holds nothing, and a Ctrl-C sent here would do nothing)."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def ctrl_c_now():
    os.kill(os.getpid(), signal.SIGINT)


def test_a_ctrl_c_inside_the_block_is_raised_when_it_ends_not_before():
    done = []
    with pytest.raises(KeyboardInterrupt):
        with ctrl_c.held():
            ctrl_c_now()
            done.append("the block went on")
    assert done == ["the block went on"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_ctrl_c_dropped_by_a_ctypes_callback_is_kept():
    # what llvmlite does while numba compiles: Python calls C, which calls back into Python; a
    # KeyboardInterrupt raised in the callback is printed and dropped by ctypes
    callback = ctypes.CFUNCTYPE(None)(ctrl_c_now)
    with pytest.raises(KeyboardInterrupt):
        with ctrl_c.held():
            callback()          # (without held(): printed as "Exception ignored", dropped)


def test_a_compiled_kernel_holds_ctrl_c_on_its_first_call_for_each_key():
    made, held_calls = [], []

    def kernel(x):
        held_calls.append(signal.getsignal(signal.SIGINT) is not signal.default_int_handler)
        return 2 * x
    call = ctrl_c.compiled(lambda: made.append(1) or kernel, key=lambda args: type(args[0]))
    assert [call(1), call(2), call(1.5), call(3.5)] == [2, 4, 3.0, 7.0]
    assert made == [1] and held_calls == [True, False, True, False]


def test_a_ctrl_c_wrapped_in_another_error_is_found():
    def wrapped():
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as e:
            raise RuntimeError("Error calling __set_name__ on 'cached_property'") from e
    with pytest.raises(RuntimeError) as e:
        wrapped()
    assert ctrl_c.interrupted_inside(e.value)
    assert not ctrl_c.interrupted_inside(RuntimeError("nothing to do with Ctrl-C"))


def test_the_command_line_says_interrupted_for_a_wrapped_ctrl_c(monkeypatch, capsys):
    import app.__main__ as cli

    def app_main(argv):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as e:
            raise RuntimeError("wrapped") from e
    monkeypatch.setattr(cli, "app_main", app_main)
    assert main(["--list"]) == 130
    err = capsys.readouterr().err
    assert err.startswith("python -m app: interrupted (Ctrl-C)") and "Traceback" not in err


def test_a_ctrl_c_while_python_shuts_down_after_the_command_is_not_a_death_by_signal():
    """The command done, Python's shutdown puts SIGINT's default action back: a Ctrl-C there
    (a __del__ at the very end, here; the hostile runs: 6 of 80 at the end of a run) ended the
    process by the signal (-2), not with the command's exit code."""
    import subprocess
    import sys
    code = ("import os, signal, time\n"
            "import app.__main__ as cli\n"
            "class Late:\n"
            "    def __del__(self):\n"
            "        os.kill(os.getpid(), signal.SIGINT)\n"
            "        time.sleep(0.01)\n"
            "late = Late()\n"
            "cli.leave(0)\n")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    run = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True,
                         timeout=60)
    assert run.returncode == 0 and "Traceback" not in run.stderr, (run.returncode, run.stderr)
