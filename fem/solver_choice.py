"""Which linear solver ``solver="auto"`` runs: the direct factorization wherever its factor
fits the memory, the iterative path ('amg') beyond: p-multigrid CG on quadratic elements
(fem/pmultigrid.py), AMG-CG on linear ones (docs/performance.md, "The iterative path for the
largest meshes")."""
from .budget import available_memory_bytes
from .linsolve import factor_bytes

# Up to these sizes (free DOFs) "auto" takes the direct solver without asking; above them it
# asks PARDISO's analysis how much memory the factor takes (direct factorization fill grows
# much faster in 3-D).
AMG_THRESHOLD = {2: 2_000_000, 3: 400_000}


def solver_choice(n_unknowns: int, dim: int, solver: str = "auto", matrix=None,
                  kind: str = "spd") -> tuple[str, str]:
    """('direct' or 'amg', why) for ``solver='auto'``; a named solver is checked and kept.
    Up to AMG_THRESHOLD unknowns the direct solver; above it, with the ``matrix`` (a callable
    giving it, built only then), the direct solver still wherever PARDISO's analysis says
    its factor fits half the memory available (fem/budget.py), the iterative path beyond."""
    if solver not in ("auto", "direct", "amg"):
        raise ValueError(f"solver = {solver!r}; choose 'auto', 'direct' or 'amg'")
    if solver != "auto":
        return solver, "asked for"
    if n_unknowns <= AMG_THRESHOLD[dim]:
        return "direct", f"{n_unknowns:,} unknowns, at most {AMG_THRESHOLD[dim]:,}"
    need = factor_bytes(matrix(), kind) if matrix is not None else None
    budget = 0.5 * available_memory_bytes()
    if need is None:
        return "amg", f"{n_unknowns:,} unknowns, above {AMG_THRESHOLD[dim]:,}"
    verdict = "fits" if need <= budget else "is above"
    why = (f"the direct factor's {need / 2**30:.2f} GiB (PARDISO's analysis) {verdict} half "
           f"the available memory, {budget / 2**30:.2f} GiB")
    return ("direct" if need <= budget else "amg"), why


def choose_solver(n_unknowns: int, dim: int, solver: str = "auto", matrix=None) -> str:
    """The solver of :func:`solver_choice`, without the reason."""
    return solver_choice(n_unknowns, dim, solver, matrix)[0]
