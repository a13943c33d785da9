"""The size factor of ``flexfem analyze``: the one given (``--size-factor``), else 1; for a
solid of bodies and flexures (``--dim 3``) whose default mesh is estimated above the DOF
budget, the smallest factor whose estimate fits, never so coarse that a flexure's elements
are larger than its thickness (:data:`COARSEST_THROUGH_THICKNESS`)."""
import math

from ...fem.budget import BudgetError, default_max_dofs
from ...geometry.mechanism.description import Leaf, flexure_label
from ...geometry.mechanism.draw import element_sizes, estimate_mesh

#: The largest element size in a flexure, over its thickness (the neck of a notch): 1, at
#: least one quadratic element through the thickness, its mid-side nodes two node intervals,
#: which represent the linear bending stress across it. A leaf's own size is half its
#: thickness (two elements at factor 1), a notch's a quarter of its neck: the coarsest
#: factor is 2 for a leaf and 4 for a notch.
COARSEST_THROUGH_THICKNESS = 1.0
#: The chosen factor is rounded up to this step (and checked again).
STEP = 0.1


def coarsest_factor(spec) -> tuple[float, str]:
    """(the largest size factor the flexures allow, the flexure that sets it, in words)."""
    mechanism = spec.mechanism
    sizes, _ = element_sizes(mechanism, spec.mesh.size)
    limits = [COARSEST_THROUGH_THICKNESS * f.thickness / h
              for f, h in zip(mechanism.flexures, sizes)]
    k = min(range(len(limits)), key=limits.__getitem__)
    f = mechanism.flexures[k]
    what = "thickness" if isinstance(f, Leaf) else "neck"
    return limits[k], f"{flexure_label(f, k)} ({what} {f.thickness:g} m)"


def _dofs(spec, factor: float) -> int:
    return estimate_mesh(spec.mechanism, spec.dim, factor, spec.mesh.size,
                         spec.mesh.order)["dofs"]


def choose_size_factor(spec, size_factor: float | None = None,
                       max_dofs: int | None = None) -> tuple[float, str]:
    """(size factor, how it was chosen): ``size_factor`` where given ("given"); 1 where the
    model is not a solid of bodies and flexures or its default mesh fits ("default");
    else the smallest factor (a multiple of :data:`STEP`) whose estimate fits the budget
    (``max_dofs``, None: half the available memory), from the estimate's ~F^-3 scaling and
    checked again. BudgetError where even :func:`coarsest_factor` does not fit."""
    if size_factor is not None:
        return size_factor, "given"
    if spec.mechanism is None or spec.dim != 3:
        return 1.0, "default"
    limit = default_max_dofs(3) if max_dofs is None else max_dofs
    source = "half the available memory" if max_dofs is None else "max_dofs"
    dofs = _dofs(spec, 1.0)
    if dofs <= limit:
        return 1.0, "default"
    coarsest, by = coarsest_factor(spec)
    factor = 1.0
    for _ in range(20):
        factor = math.ceil(factor * (dofs / limit) ** (1 / 3) / STEP - 1e-9) * STEP
        factor = round(max(factor, 1.0 + STEP), 6)
        dofs = _dofs(spec, factor)
        if dofs <= limit or factor > coarsest:
            break
    if factor > coarsest or dofs > limit:
        factor, dofs = coarsest, _dofs(spec, coarsest)
        if dofs > limit:
            raise BudgetError(
                f"{spec.source}: the 3-D mesh does not fit the budget of {limit:,} DOFs "
                f"({source}) even at size_factor {coarsest:.3g} (about {dofs:,} DOFs), the "
                f"coarsest that keeps a quadratic element through the thickness of {by}; "
                "raise the budget (--max-dofs N, FLEXFEM_MEMORY_GIB) or analyse it in 2-D")
    return factor, (f"size_factor {factor:.3g} chosen to fit the budget of {limit:,} DOFs "
                    f"({source}; about {dofs:,} DOFs at it, {_dofs(spec, 1.0):,} at "
                    "size_factor 1)")


def with_mesh_size(sets: dict, mesh_size) -> dict:
    """The ``--set`` overrides with ``--mesh-size`` as ``mesh.size`` (both: refused)."""
    if mesh_size is None:
        return sets
    if "mesh.size" in sets:
        raise ValueError("give the bodies' element size once: --mesh-size or --set mesh.size")
    return {**sets, "mesh.size": mesh_size}

