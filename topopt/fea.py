"""The grid's stiffness matrix with its sparsity pattern built once: K(E) = sum_e E_e KE
over the free DOFs, plus springs, factorised once per design and shared by all solves."""
import numpy as np
import scipy.sparse as sp

from ..fem.linsolve import direct_backend
from .grid import Grid
from .solver import PatternSolver


class System:
    """K u = f of a grid, DOFs ``fixed`` removed, ``springs`` ({DOF: N/m}) added.

    ``KE`` is the element stiffness for unit modulus (N/m per Pa); ``solve(E, rhs)``
    returns full-length solutions (zeros at fixed DOFs) for every column of ``rhs``.
    """

    def __init__(self, grid: Grid, KE: np.ndarray, fixed: np.ndarray, springs: dict):
        self.grid, self.KE = grid, KE
        self.fixed = np.unique(np.asarray(fixed, dtype=int))
        self.free = np.setdiff1d(np.arange(grid.n_dofs), self.fixed)
        self.upper = direct_backend("spd") == "mkl-pardiso"
        reduced = np.full(grid.n_dofs, -1)
        reduced[self.free] = np.arange(self.free.size)
        edofs = grid.edofs
        rows = reduced[np.repeat(edofs, 8, axis=1)].ravel()
        cols = reduced[np.tile(edofs, (1, 8))].ravel()
        vals = np.tile(KE.ravel(), grid.n_elements)
        elems = np.repeat(np.arange(grid.n_elements), 64)
        local = np.tile(np.arange(64), grid.n_elements)
        keep = (rows >= 0) & (cols >= 0) & ((rows <= cols) if self.upper else True)
        rows, cols, vals, elems = rows[keep], cols[keep], vals[keep], elems[keep]
        n = self.free.size
        keys, slot = np.unique(rows.astype(np.int64) * n + cols, return_inverse=True)
        rows, self._indices = np.divmod(keys, n)
        self._indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=n))])
        self._entries = (slot.ravel(), elems, local[keep], keys.size)
        self._map = self.element_map(KE)
        self.solver = PatternSolver(self._indptr, self._indices, n)
        self._spring = np.zeros(keys.size)
        self.spring_diagonal = np.zeros(grid.n_dofs)   # N/m by DOF
        for dof, k in springs.items():
            self.spring_diagonal[dof] += k
            r = reduced[dof]
            if r >= 0:
                self._spring[np.searchsorted(keys, np.int64(r) * n + r)] += k

    def element_map(self, ME: np.ndarray) -> sp.csr_matrix:
        """The sparse map from element factors to the values of sum_e factor_e ME (8 x 8)
        in the reduced matrix's pattern."""
        slot, elems, local, size = self._entries
        return sp.csr_matrix((ME.ravel()[local], (slot, elems)),
                             shape=(size, self.grid.n_elements))

    def matrix(self, E: np.ndarray, element_map=None) -> sp.csr_matrix:
        """The reduced K(E) (CSR; its upper triangle only where PARDISO factorises it), or
        with ``element_map`` the reduced sum_e E_e ME of its matrix ME (without springs)."""
        data = self._map @ E + self._spring if element_map is None else element_map @ E
        n = self.free.size
        return sp.csr_matrix((data, self._indices, self._indptr), shape=(n, n))

    def factor_elements(self, KE: np.ndarray) -> None:
        """Factorise sum_e KE[e] (n_elements x 8 x 8, N/m: each element its own matrix, e.g.
        a tangent) plus the springs; then ``resolve`` solves with it."""
        slot, elems, local, size = self._entries
        values = KE.reshape(len(KE), 64)[elems, local]
        self.solver.factor(np.bincount(slot, weights=values, minlength=size) + self._spring)

    def solve(self, E: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """Solutions (n_dofs, k) of K(E) u = rhs[:, j], one factorisation for all k."""
        self.solver.factor(self._map @ E + self._spring)
        return self.resolve(rhs)

    def solve_without_springs(self, E: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """Solutions (n_dofs, k) of K(E) u = rhs[:, j] without the springs (the structure's
        own stiffness); the factorisation is then that matrix's until the next ``solve``."""
        self.solver.factor(self._map @ E)
        return self.resolve(rhs)

    def resolve(self, rhs: np.ndarray) -> np.ndarray:
        """Solutions (n_dofs, k) with the last factorisation (of the last ``solve``)."""
        rhs = np.asarray(rhs, dtype=float).reshape(self.grid.n_dofs, -1)
        out = np.zeros_like(rhs)
        out[self.free] = self.solver.solve(rhs[self.free]).reshape(self.free.size, -1)
        return out

    def element_products(self, a: np.ndarray, b: np.ndarray, ME=None) -> np.ndarray:
        """a_e^T KE b_e for every element (the unit-modulus energy products), or with an
        8 x 8 ME a_e^T ME b_e."""
        ae, be = a[self.grid.edofs], b[self.grid.edofs]
        return np.einsum("ei,ij,ej->e", ae, self.KE if ME is None else ME, be)
