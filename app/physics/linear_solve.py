"""The linear solve of an implicit step, and how it ended.

Implicit Euler solves one linear system A dv = b per step (app/physics/integrators.py for any
particle system, app/physics/mass_spring.py for the cloth) with conjugate gradients (CG), the
lecture's method: only products A w, no matrix. CG is made for a symmetric positive definite A,
and it can stop short of its tolerance:

  * breakdown: p.Ap <= 0 along a search direction, so A is not positive definite there (two
    bodies pulling each other harder the closer they get, at a large step: h^2 df/dx outweighs
    M), or rounding has destroyed the directions' conjugacy;
  * the iteration cap (by default the number of unknowns, enough in exact arithmetic; not
    always in floating point when A is badly conditioned: a stiff cloth at a step of a second).

Like SciPy's cg, which returns `info` beside its answer, the solve says how it ended: a
`SolveReport` (the iterations, the true relative residual |b - A x| / |b| of the answer, whether
it met the tolerance, and why it stopped). Where CG stops short, the caller can solve the same
system another way (`solve`'s `fallback`: a dense LU for a few unknowns, a sparse direct solve
for the cloth), which gives the true linearised step wherever A is not singular; the report says
which answer the step took. A direct solver chosen instead of CG (`solve_directly`: the cloth's
`solver=direct`) fills in the same report, so the metrics and the HUD read one object whatever
solved the step.

CG is handed two functions and nothing else: the product w -> A w (for the cloth a sparse matrix
refreshed in place each step, app/physics/cloth_matrix.py) and the preconditioner r -> z, an easy
approximation of A^-1 r (Jacobi: r / diag(A); the cloth's 2x2 block Jacobi: each particle's own
2x2 block of A inverted). It may also be handed a first guess x0, such as the last step's
answer: a cloth that moves smoothly needs a dv much like the last one (a warm start).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np


def one_blas_thread() -> None:
    """Run NumPy's BLAS on one thread for the rest of the process (threadpoolctl). The lab's
    vectors are small to medium (a 128x128 cloth: 32,768 unknowns), and on a busy 2-core machine
    BLAS's second thread waits for a core: np.vdot of 32,768 doubles took 450-510 us with two
    threads against 32 us with one (median of 7, load ~18, 2026-11-26), so a CG iteration ran
    many times slower. Threads never paid here: pinned once, for every step, solve and bench."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:              # not installed: BLAS keeps its own threads
        return
    threadpool_limits(limits=1, user_api="blas")

Product = Callable[[np.ndarray], np.ndarray]
Preconditioner = Callable[[np.ndarray], np.ndarray]     # r -> z, an approximation of A^-1 r
DENSE_LIMIT = 400       # unknowns up to which dense_solve builds the matrix (400 products + LU)


@dataclass
class SolveReport:
    """How the last linear solve of an implicit step ended.

    method: the solver tried first ("cg", or a direct solve's name such as "sparse LU"; "" before
    the first solve). iterations: CG's iterations (0 for a direct solve). residual: |b - A x| / |b|
    of its answer (recomputed, not CG's running estimate), tolerance: what it had to reach.
    converged: residual <= tolerance. stop: why it stopped ("converged", "breakdown", "iteration
    cap", "rounding", "budget": a caller's cap for time; a direct solve: "solved", or "failed"
    where it had no answer). fallback: the solve that gave the step instead ("dense LU", "sparse
    LU", "cg"), None if the first answer was used or no other solve was possible;
    fallback_residual: that answer's |b - A x| / |b|. warm: CG started from the caller's first
    guess (x0). fill: a direct solve's factor size (non-zeros of L and U), None for CG."""

    method: str = ""
    iterations: int = 0
    residual: float = 0.0
    tolerance: float = 0.0
    converged: bool = True
    stop: str = ""
    fallback: str | None = None
    fallback_residual: float | None = None
    warm: bool = False
    fill: int | None = None

    @property
    def step_residual(self) -> float:
        """The relative residual of the answer the step used."""
        return self.residual if self.fallback_residual is None else self.fallback_residual

    def words(self) -> str:
        """One line for the HUD: '' when CG converged; else what happened and what the step used."""
        if self.converged:
            return ""
        if self.method != "cg":
            what = (f"the {self.method} solve had no answer (A singular or not finite)"
                    if self.stop == "failed" else
                    f"the {self.method} solve left a residual {self.residual:.1e} > "
                    f"{self.tolerance:.0e} (rounding: A badly conditioned)")
            used = (f"used CG (residual {self.fallback_residual:.1e})" if self.fallback
                    else "no other solve: used its answer" if self.stop == "solved"
                    else "no other solve: dv = 0")
            return f"{what}; {used}"
        why = {"breakdown": "broke down (p.Ap <= 0: A not positive definite)",
               "iteration cap": f"hit its cap of {self.iterations} iterations",
               "budget": f"stopped at {self.iterations} iterations, all the step's time "
                         "budget holds",
               "rounding": "met its tolerance in its running residual only"}[self.stop]
        used = (f"used a {self.fallback} solve (residual {self.fallback_residual:.1e})"
                if self.fallback else "no other solve: used CG's last iterate")
        return f"CG {why}, residual {self.residual:.1e} > {self.tolerance:.0e}; {used}"


def relative_residual(A: Product, b: np.ndarray, x: np.ndarray, free: np.ndarray) -> float:
    """|b - A x| / |b| over the free rows (0 if b = 0)."""
    b_norm = float(np.linalg.norm(b * free))
    if b_norm == 0.0:
        return 0.0
    return float(np.linalg.norm((b - A(x)) * free)) / b_norm


def preconditioned_cg(A: Product, b: np.ndarray, free: np.ndarray,
                      precondition: Preconditioner | None = None, tolerance: float = 1e-12,
                      max_iterations: int | None = None, x0: np.ndarray | None = None
                      ) -> tuple[np.ndarray, SolveReport]:
    """Conjugate gradients for A x = b on the free rows (free: 1.0 free / 0.0 fixed, broadcast
    against b; fixed rows of x stay 0, Baraff & Witkin's filter), preconditioned: each residual r
    is handed to `precondition`, which returns z ~ A^-1 r (None: z = r, no preconditioning); a
    good z evens out heavy and light, stiff and soft rows, and CG needs fewer iterations. The
    preconditioner must be symmetric positive definite and must keep fixed rows at 0.

    x0: a first guess (the last step's answer), used only if it leaves a smaller residual than
    x = 0 does (else CG starts from 0 as usual). Stops when |r| <= tolerance |b|, after
    `max_iterations` (default: the number of unknowns), or on a breakdown (p.Ap <= 0: A is not
    positive definite along p). Returns (x, report): x is the last iterate x_k (x0 or 0 if it
    broke down before its first step). For a positive definite A, x_k is the best answer in A's
    energy norm among x0 plus all combinations of the k directions searched so far; for any other
    A it is only where CG stopped. The report's residual is recomputed from x_k (one more
    product), because CG's running residual drifts from the true one in rounding."""
    precondition = precondition or (lambda r: r)
    r = b * free                                 # the residual b - A x at x = 0
    b_norm = math.sqrt(float(np.vdot(r, r)))
    x, warm = np.zeros_like(b), False
    if x0 is not None and b_norm > 0.0:
        r_warm = (b - A(x0 * free)) * free       # ... and at x = x0: keep the smaller one
        if float(np.vdot(r_warm, r_warm)) < b_norm * b_norm:
            x, r, warm = x0 * free, r_warm, True
    z = precondition(r)
    p = z.copy()
    rz = float(np.vdot(r, z))
    r_norm = math.sqrt(float(np.vdot(r, r)))
    limit = max_iterations or int(np.broadcast_to(free, b.shape).sum()) + 1   # the unknowns
    iterations, stop = 0, "converged"
    while r_norm > tolerance * b_norm:
        if iterations >= limit:
            stop = "iteration cap"
            break
        Ap = A(p) * free
        pAp = float(np.vdot(p, Ap))
        if pAp <= 0.0 or rz <= 0.0:              # no descent along p: A is not definite here
            stop = "breakdown"
            break
        alpha = rz / pAp
        x += alpha * p                           # step along p to the minimum of the energy
        r -= alpha * Ap
        z = precondition(r)
        rz_new = float(np.vdot(r, z))
        p = z + (rz_new / rz) * p                # the next direction, conjugate to the last
        rz = rz_new
        r_norm = math.sqrt(float(np.vdot(r, r)))
        iterations += 1
    if iterations or warm:
        residual = relative_residual(A, b, x, free)
    else:
        residual = 1.0 if b_norm else 0.0
    report = SolveReport("cg", iterations, residual, tolerance, stop == "converged"
                         and residual <= tolerance, stop, warm=warm)
    if stop == "converged" and not report.converged:
        report.stop = "rounding"                 # the running residual met it, the true one not
    return x, report


def jacobi(inv_diagonal: np.ndarray) -> Preconditioner:
    """The Jacobi preconditioner z = r / diag(A), given 1/diag(A) (the shape of b)."""
    return lambda r: inv_diagonal * r


def solve(A: Product, b: np.ndarray, free: np.ndarray, precondition: Preconditioner | None,
          tolerance: float, max_iterations: int | None,
          fallback: tuple[str, Callable[[], np.ndarray | None]] | None = None,
          x0: np.ndarray | None = None) -> tuple[np.ndarray, SolveReport]:
    """CG (preconditioned_cg, from x0 if given); if it stops short and a fallback (name, function
    returning the solution or None where it has none) is given, the fallback's answer when its
    residual is smaller. Returns (the answer the step uses, the report)."""
    x, report = preconditioned_cg(A, b, free, precondition, tolerance, max_iterations, x0)
    if report.converged or fallback is None:
        return x, report
    name, other = fallback
    y = other()
    if y is not None and np.isfinite(y).all():
        residual = relative_residual(A, b, y, free)
        if residual < report.residual:
            report.fallback, report.fallback_residual = name, residual
            return y, report
    return x, report


def solve_directly(A: Product, b: np.ndarray, free: np.ndarray, name: str,
                   direct: Callable[[], tuple[np.ndarray | None, int | None]], tolerance: float,
                   fallback: Callable[[], tuple[np.ndarray, SolveReport]] | None = None
                   ) -> tuple[np.ndarray, SolveReport]:
    """A x = b by a direct solve (`direct` returns (x, the factor's non-zeros), x None where it
    has no answer), reported like CG: 0 iterations, the true residual |b - A x| / |b|, converged
    when it is within `tolerance` (a direct solve's answer is exact up to rounding, which a badly
    conditioned A amplifies). Where it has no answer or a larger residual than allowed, the
    fallback (CG) is tried and the smaller residual's answer used."""
    x, fill = direct()
    ok = x is not None and bool(np.isfinite(x).all())
    residual = relative_residual(A, b, x, free) if ok else 1.0
    report = SolveReport(name, 0, residual, tolerance, ok and residual <= tolerance,
                         "solved" if ok else "failed", fill=fill)
    if not ok:
        x = np.zeros_like(b)
    if report.converged or fallback is None:
        return x, report
    y, other = fallback()
    if other.residual < residual:
        report.fallback, report.fallback_residual = "cg", other.residual
        return y, report
    return x, report


def dense_solve(A: Product, b: np.ndarray, free: np.ndarray) -> np.ndarray | None:
    """A x = b on the free rows by building A column by column from its products (A e_j) and an
    LU solve: for a few unknowns (at most DENSE_LIMIT), the exact answer whether or not A is
    definite. None if there are too many unknowns or A is singular there."""
    mask = np.broadcast_to(free, b.shape).ravel() > 0
    unknowns = np.flatnonzero(mask)
    if unknowns.size == 0 or unknowns.size > DENSE_LIMIT:
        return None
    columns = []
    for j in unknowns:
        e = np.zeros(b.size)
        e[j] = 1.0
        columns.append(A(e.reshape(b.shape)).ravel()[unknowns])
    matrix = np.array(columns).T
    try:
        solution = np.linalg.solve(matrix, b.ravel()[unknowns])
    except np.linalg.LinAlgError:
        return None
    x = np.zeros(b.size)
    x[unknowns] = solution
    return x.reshape(b.shape)


__all__ = ["SolveReport", "preconditioned_cg", "jacobi", "solve", "solve_directly", "dense_solve",
           "relative_residual", "DENSE_LIMIT", "Preconditioner"]
