"""Ctrl-C held back across code that would drop it or garble it, and raised once that code is done.

numba is where it was seen (hostile command lines, seed 6, 2026-11-26):
  * while numba compiles a kernel, llvmlite calls back into Python through ctypes (its object
    cache). A KeyboardInterrupt raised inside such a callback is printed ("Exception ignored on
    calling ctypes callback function") and dropped, and the compile goes on: a Ctrl-C pressed in
    those ~0.5 s was lost, and `bench cloth` ran on to its end;
  * while `import numba` runs, one raised as a class is being made comes out as a RuntimeError
    ("Error calling __set_name__"): a traceback instead of the one line of an interrupted run.
Across `held()` a Ctrl-C is only noted; when the block ends, the handler that was there before
is called with it (Python's own raises KeyboardInterrupt), so the command line stops as it does
anywhere else. `compiled()` gives numba's kernels this treatment on their first call for each
type of array (that call compiles, or loads numba's cache).
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager
from typing import Callable, Iterator


@contextmanager
def held() -> Iterator[None]:
    """Run the block with Ctrl-C noted, not raised; raise it (through the handler that was
    there) once the block is done. Outside the main thread, or where Python's handler is not a
    function (ignored, the default, or set outside Python), the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    before = signal.getsignal(signal.SIGINT)
    if not callable(before):
        yield
        return
    noted: list = []
    signal.signal(signal.SIGINT, lambda sig, frame: noted.append(frame))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, before)
        if noted:
            before(signal.SIGINT, noted[-1])


def compiled(make: Callable[[], Callable], key: Callable = lambda args: args[0].dtype) -> Callable:
    """A numba kernel whose making (`make`: it imports numba and returns the jitted function) and
    first call for each `key(args)` (the dtype of its first array: a new one compiles again) run
    with Ctrl-C held; later calls cost one set lookup."""
    kernel: list = []
    warm: set = set()

    def call(*args):
        k = key(args)
        if k in warm:
            return kernel[0](*args)
        with held():
            if not kernel:
                kernel.append(make())
            out = kernel[0](*args)
        warm.add(k)
        return out
    return call


def interrupted_inside(exc: BaseException) -> bool:
    """Whether a KeyboardInterrupt lies in exc's chain (its cause or context): a Ctrl-C that some
    library wrapped in its own error (Python wraps one raised in __set_name__ in a RuntimeError)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False
