"""BLAS threads, pinned to one where they hurt.

NumPy's `np.vdot` (CG's dot products, app/physics/linear_solve.py) hands vectors above ~10,000
elements to OpenBLAS, which then splits them over every core. On a machine whose cores are busy
with other work the threads wait for each other: a 128 x 128 mass-spring step with CG took
2.1-3.2 s with OpenBLAS's 2 threads against 0.17-0.28 s with one (measured side by side, 2 cores
at load 16, `bench mass_spring`); at 64 x 64 (8,192 elements) nothing changes. So a step on
vectors this long runs with BLAS held to one thread (threadpoolctl, ~3 us to set and restore);
below that nothing is touched.
"""

from __future__ import annotations

from contextlib import nullcontext
from typing import ContextManager

PIN_ABOVE = 10_000          # vector elements above which OpenBLAS goes multithreaded

_controller = None


def one_blas_thread(elements: int) -> ContextManager:
    """A context in which BLAS uses one thread, for work on vectors of `elements` floats (a
    context that does nothing below PIN_ABOVE)."""
    global _controller
    if elements <= PIN_ABOVE:
        return nullcontext()
    if _controller is None:
        from threadpoolctl import ThreadpoolController
        _controller = ThreadpoolController()
    return _controller.limit(limits=1, user_api="blas")
