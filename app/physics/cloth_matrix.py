"""Implicit Euler's matrix for the mass-spring cloth, as a sparse matrix that is built once and
refreshed in place each step; the 2x2 block Jacobi preconditioner; and the direct solve.

The system matrix A = M - h df/dv - h^2 df/dx of app/physics/mass_spring.py is a 2x2 block per
pair of particles joined by a spring (-B, with B = h D + h^2 K the spring's combined block) plus
one 2x2 block per particle on the diagonal (its mass, its drag and the B of every spring that
touches it). Which blocks are non-zero depends only on the grid and the spring families that are
on, not on where the particles are: so the pattern (which diagonals hold entries, and where) is
built once, and each step only writes the new numbers into `data`, at positions worked out once
(`slots`). The product A w is then one call into SciPy's compiled sparse product: measured at
64x64, 4x faster than the same blocks applied as NumPy slices (spring_forces.block_product), and
the diagonal storage (DIA) 1.6x faster than the usual row storage (CSR).

Vectors are component-major, as everywhere in the implicit solve: w has shape (2, n), w[0] the x
components of all n particles and w[1] the y; entry (c, i) of w is entry c * n + i of the flat
vector the matrix multiplies.

The preconditioner (`block_jacobi`): CG converges faster on M^-1 A than on A when M^-1 is an easy
approximation of A^-1. Jacobi takes M = diag(A); the block Jacobi takes each particle's own 2x2
block, which also holds how a spring couples that particle's x and y (a diagonal spring pulls
along both): measured on the 64x64 denim cloth, it needs ~0.6x Jacobi's iterations.

The direct solve (`factorize`): SciPy's SuperLU factors A = LU with a symmetric fill-reducing
ordering (minimum degree on A + A^T) and solves by substitution. It is exact up to rounding, but
the factors hold many more non-zeros than A (the "fill": ~11x A's at 64x64, 8x with shear
on, and it grows faster than the cloth), and a cloth's A changes every step, so every step pays
a new factorization.

SciPy is imported only here, and only when a matrix is first built (an implicit step) or a
direct solve is asked for: no other scene imports it. Where it is not installed (a browser build:
docs/developers.md) the product runs down the same diagonals in NumPy (`DiagonalMatrix`,
measured 2.3x SciPy's time at 64x64: 450 against 200 us), and the direct solve says it needs
SciPy.
"""

from __future__ import annotations

import numpy as np

from app.physics.rods import Family

NO_SCIPY = ("the direct solve (solver=direct, and CG's fallback) needs SciPy, which is not "
            "installed here: pip install scipy, or use solver=cg")


def scipy_sparse():
    """SciPy's sparse module, or None where SciPy is not installed."""
    try:
        from scipy import sparse
    except ImportError:
        return None
    return sparse


class DiagonalMatrix:
    """The DIA storage without SciPy: data[k, j] is the entry in column j of diagonal
    offsets[k] (row j - offsets[k]), as SciPy's dia_matrix keeps it; `@` a vector."""

    def __init__(self, data: np.ndarray, offsets: np.ndarray, shape: tuple[int, int]):
        self.data, self.offsets, self.shape = data, offsets, shape

    def __matmul__(self, x: np.ndarray) -> np.ndarray:
        n = self.shape[0]
        y = np.zeros(n)
        for k, off in enumerate(self.offsets):       # one slice per diagonal, not per entry
            if off >= 0:
                y[:n - off] += self.data[k, off:] * x[off:]
            else:
                y[-off:] += self.data[k, :n + off] * x[:n + off]
        return y

Blocks = list[tuple[Family, np.ndarray]]     # (family, B of shape (2, 2, m_r, m_c)) per family


class ClothMatrix:
    """A's pattern for a rows x cols grid and these spring families; `refresh` writes a step's
    numbers into it. `matrix` is the SciPy sparse matrix (2n x 2n, component-major, DIA)."""

    def __init__(self, families: list[Family], rows: int, cols: int, storage: str = "dia"):
        self.families, self.rows, self.cols = list(families), rows, cols
        n = self.n = rows * cols
        ids = np.arange(n).reshape(rows, cols)
        # Every non-zero, listed once in a fixed ("canonical") order: first the diagonal blocks,
        # entry (c, d) of particle i at row c n + i, column d n + i (c, d = 0, 1: x, y); then per
        # family its off-diagonal blocks, (a, b) and then (b, a), in the order of B.ravel()
        # (component pair first, then the springs). No two entries share a place: the families'
        # offsets differ, and none is another's negative.
        rows_at, cols_at = [], []
        for c in range(2):
            for d in range(2):
                rows_at.append(c * n + np.arange(n))
                cols_at.append(d * n + np.arange(n))
        self.family_entries: list[tuple[int, int]] = []       # (first, count) per family
        start = 4 * n
        for fam in self.families:
            ia, ib = ids[fam.a].ravel(), ids[fam.b].ravel()
            for first, second in ((ia, ib), (ib, ia)):
                for c in range(2):
                    for d in range(2):
                        rows_at.append(c * n + first)
                        cols_at.append(d * n + second)
            self.family_entries.append((start, 4 * ia.size))
            start += 8 * ia.size
        row, col = np.concatenate(rows_at), np.concatenate(cols_at)
        self.nonzeros = row.size                          # A's non-zeros: 4 n + 8 per spring
        # Stored by diagonals (SciPy's DIA format): every entry lies on a diagonal col - row =
        # offset, and the grid's springs put all of them on a few (3 + 6 per family: 27 for the
        # default cloth); data[k, col] holds the entry of diagonal k in column col, zero where
        # the diagonal has no spring. Its product runs down whole diagonals, contiguous in
        # memory: 1.6x faster than CSR's row by row at 64x64 (no column index per entry).
        # (storage="csr": the usual row storage, for the bench's comparison.)
        sparse = scipy_sparse()
        if storage == "dia":
            offsets, diagonal = np.unique(col - row, return_inverse=True)
            data = np.zeros((offsets.size, 2 * n))
            self.matrix = (sparse.dia_matrix((data, offsets), shape=(2 * n, 2 * n))
                           if sparse is not None else
                           DiagonalMatrix(data, offsets, (2 * n, 2 * n)))
            self.slots = diagonal.ravel() * (2 * n) + col     # canonical entry -> data index
        else:
            # CSR sorts its entries by row and column: build it with each entry's canonical
            # index (+1: no explicit zero) as its value to find where each one went
            order = sparse.csr_matrix((np.arange(1.0, row.size + 1), (row, col)),
                                      shape=(2 * n, 2 * n))
            order.sort_indices()
            self.slots = np.empty(row.size, dtype=np.intp)
            self.slots[order.data.astype(np.intp) - 1] = np.arange(row.size)
            order.data[:] = 0.0
            self.matrix = order
        self.diagonal_blocks = np.zeros((2, 2, rows, cols))

    def key_matches(self, families: list[Family]) -> bool:
        """True if this pattern is the one for these families (same objects, same order)."""
        return len(families) == len(self.families) and all(
            f is g for f, g in zip(families, self.families))

    def refresh(self, mass: np.ndarray, blocks: Blocks) -> None:
        """Write one step's A into the matrix: mass (n,) on the diagonal (times the 2x2 identity)
        and, for every family's springs, +B on both ends' diagonal blocks and -B off them."""
        D = self.diagonal_blocks
        D[...] = 0.0
        D[0, 0] = D[1, 1] = mass.reshape(self.rows, self.cols)
        data = self.matrix.data.reshape(-1)           # a view: written in place
        for (fam, B), (start, count) in zip(blocks, self.family_entries):
            D[(slice(None), slice(None)) + fam.a] += B        # the loop it replaces: for each
            D[(slice(None), slice(None)) + fam.b] += B        # spring, B into both ends' blocks
            off = -B.ravel()
            data[self.slots[start:start + count]] = off                  # (a, b) blocks
            data[self.slots[start + count:start + 2 * count]] = off      # (b, a): B is symmetric
        data[self.slots[:4 * self.n]] = D.reshape(-1)

    def product(self, w: np.ndarray) -> np.ndarray:
        """A w for a component-major w of shape (2, n)."""
        return (self.matrix @ w.reshape(-1)).reshape(w.shape)

    def block_jacobi(self):
        """The preconditioner r -> z = (each particle's 2x2 diagonal block of A)^-1 r, from the
        blocks of the last refresh: [[p, q], [q, s]]^-1 = [[s, -q], [-q, p]] / (p s - q^2)."""
        D = self.diagonal_blocks.reshape(2, 2, self.n)
        p, q, s = D[0, 0], D[0, 1], D[1, 1]
        det = p * s - q * q                       # > 0: the block is positive definite
        ip, iq, is_ = s / det, -q / det, p / det

        def precondition(r: np.ndarray) -> np.ndarray:
            return np.stack((ip * r[0] + iq * r[1], iq * r[0] + is_ * r[1]))
        return precondition

    def factorize(self, free: np.ndarray):
        """A factored by SuperLU for the free particles (free: (n,) bool): a fixed particle's
        rows and columns become those of the identity, so its dv comes out 0 (Baraff & Witkin's
        filter, as a matrix: F A F + (I - F), F = diag(free)). Returns (solve: b -> x on (2, n)
        arrays, non-zeros of L and U), or (None, None) if A is singular."""
        sparse = scipy_sparse()
        if sparse is None:
            raise ImportError(NO_SCIPY)
        from scipy.sparse.linalg import splu
        keep = np.tile(np.asarray(free, float), 2)
        F = sparse.diags(keep)
        filtered = (F @ self.matrix @ F + sparse.diags(1.0 - keep)).tocsc()
        try:
            lu = splu(filtered, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                      options={"SymmetricMode": True})
        except RuntimeError:                     # "Factor is exactly singular"
            return None, None

        def solve(b: np.ndarray) -> np.ndarray:
            return lu.solve(b.reshape(-1)).reshape(b.shape)
        return solve, int(lu.L.nnz + lu.U.nnz)


__all__ = ["ClothMatrix"]
