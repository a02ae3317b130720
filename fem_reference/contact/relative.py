"""The relative compliance of the two blocks at the condensed contact DOFs, held as the
blocks' own compliances.

Body a is the mirror image of body b (its normal DOFs point the other way, ``Rz = −1``
there), each block has the compliance ``C₁(ν)`` of unit modulus, so

    C_rel = Rz C₁(ν_a) Rz / E_a + C₁(ν_b) / E_b.

Formed whole, C_rel is one more dense matrix of the condensed surface's size beside the
blocks' (and, while formed by whole-array operations, three more); the semi-smooth solve
needs only its products and its rows (:class:`fem_reference.contact.compliance.NodalCompliance`),
so it is held as the blocks' compliances and formed whole only where a solve needs it
(the augmented solve's stiffness, :meth:`RelativeCompliance.dense`).  Its rows are the
same numbers as the whole matrix's, entry by entry.
"""

from __future__ import annotations

import numpy as np


class RelativeCompliance:
    """``C_rel`` of the module doc from the blocks' ``C_a = C₁(ν_a)``, ``C_b = C₁(ν_b)``
    (exactly symmetric, the same array where ν_a = ν_b), the signs ``Rz`` and the moduli."""

    def __init__(self, C_a: np.ndarray, C_b: np.ndarray, Rz: np.ndarray, E_a: float,
                 E_b: float):
        self.C_a, self.C_b, self.Rz, self.E_a, self.E_b = C_a, C_b, Rz, E_a, E_b

    @property
    def shape(self) -> tuple[int, int]:
        return self.C_b.shape

    def rows(self, K: np.ndarray) -> np.ndarray:
        """``C_rel[K]`` (C order), entry by entry the numbers of :meth:`dense`."""
        Rz = self.Rz
        R_a = _rows(self.C_a, K)
        R_b = R_a if self.C_b is self.C_a else _rows(self.C_b, K)
        return (Rz[K, None] * R_a * Rz[None, :]) / self.E_a + R_b / self.E_b

    def dense(self) -> np.ndarray:
        """``C_rel`` whole."""
        return self.rows(np.arange(self.shape[0]))

    def __matmul__(self, v: np.ndarray) -> np.ndarray:
        """``C_rel v`` (v (m,) or (m, k)): the blocks' products, one pass over the matrix
        where both bodies share it (as rows times the exactly symmetric matrix: OpenBLAS
        multiplies a Fortran-ordered matrix by a few rows faster than by a few columns)."""
        V = v.reshape(v.shape[0], -1)
        Rz = self.Rz[:, None]
        if self.C_a is self.C_b and isinstance(self.C_b, np.ndarray):  # (Vᵀ C)ᵀ = C V
            k = V.shape[1]
            both = (np.vstack([(Rz * V).T, V.T]) @ self.C_b).T
            out = Rz * both[:, :k] / self.E_a + both[:, k:] / self.E_b
        else:
            out = Rz * (self.C_a @ (Rz * V)) / self.E_a + (self.C_b @ V) / self.E_b
        return out.reshape(v.shape)


def _rows(C, K: np.ndarray) -> np.ndarray:
    """``C[K]`` of the exactly symmetric ``C``, read as columns where C is Fortran-ordered
    (contiguous there); a compliance held otherwise forms its own rows
    (:class:`fem_reference.model.parity.ParityCompliance`)."""
    if not isinstance(C, np.ndarray):
        return C.rows(K)
    if C.flags.f_contiguous and not C.flags.c_contiguous:
        return np.ascontiguousarray(C[:, K].T)
    return C[K]
