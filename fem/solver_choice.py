"""Which linear solver ``solver="auto"`` runs, by memory: the direct factorization in core
wherever its factor fits half the available memory, PARDISO out of core (the factor in files)
where only its working set does, the iterative path ('amg') beyond: p-multigrid CG on
quadratic elements (fem/pmultigrid.py), AMG-CG on linear ones (docs/large_models.md)."""
from .budget import factor_plan
from .linsolve import factor_memory

# Up to these sizes (free DOFs) "auto" takes the direct solver without asking; above them it
# asks PARDISO's analysis how much memory the factor takes (direct factorization fill grows
# much faster in 3-D).
AMG_THRESHOLD = {2: 2_000_000, 3: 400_000}


def solver_choice(n_unknowns: int, dim: int, solver: str = "auto", matrix=None,
                  kind: str = "spd", available: float | None = None) -> tuple[str, str]:
    """('direct' or 'amg', why) for ``solver='auto'``; a named solver is checked and kept.
    Up to AMG_THRESHOLD unknowns the direct solver; above it, with the ``matrix`` (a callable
    giving it, built only then), fem/budget.py's ``factor_plan`` of PARDISO's analysis:
    'direct' in core or out of core (the factorization itself goes out of core by the same
    rule, fem/linsolve.py), 'amg' where neither fits. ``available``: the memory (bytes) to
    plan for (None: fem/budget.py's ``available_memory_bytes``)."""
    if solver not in ("auto", "direct", "amg"):
        raise ValueError(f"solver = {solver!r}; choose 'auto', 'direct' or 'amg'")
    if solver != "auto":
        return solver, "asked for"
    if n_unknowns <= AMG_THRESHOLD[dim]:
        return "direct", f"{n_unknowns:,} unknowns, at most {AMG_THRESHOLD[dim]:,}"
    need = factor_memory(matrix(), kind) if matrix is not None else None
    if need is None:
        return "amg", f"{n_unknowns:,} unknowns, above {AMG_THRESHOLD[dim]:,}"
    plan, why = factor_plan(*need, available)
    return ("amg" if plan == "iterative" else "direct"), why


def choose_solver(n_unknowns: int, dim: int, solver: str = "auto", matrix=None) -> str:
    """The solver of :func:`solver_choice`, without the reason."""
    return solver_choice(n_unknowns, dim, solver, matrix)[0]
