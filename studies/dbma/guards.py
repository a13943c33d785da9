"""What a DBMA analysis refuses: before meshing, a design its models cannot take and a mesh
above the machine's budget; after solving, a result outside the models' validity.

Before: h = 0 puts both hinges of an arm on one line; the drawing allows it, but the
amplification of Eq. 7 and of the enhanced model grows as 1/h and the analytical mass model
fails at R = 0, so the analyses need h > 0 (named at once, not after meshing). The mesh's
size is estimated from its size field (geometry/dbma/estimate.py) and checked against the
DOF budget (fem/budget.py). After: every number finite, and R_fem > 0 -- a bow-type
amplifier whose output moves against its input (h too small next to the hinge's own
bending, say h = 1 um with b = 0.6 mm) is outside what its models describe; it is refused
with the numbers rather than printed as an amplification ratio. A formula used beyond its
assumptions is flagged (``validity_notes``): Eq. 7's rigid-lever ratio when h < b (the
hinges' own bending then dominates the lever and Eq. 7 overestimates R many times).
"""
from ...fem.budget import check_budget
from ...geometry.dbma.estimate import estimate_mesh
from ...geometry.dbma.params import DBMAParams
from ..engine.validate import require_finite


def check_analysable(p: DBMAParams) -> None:
    """ValueError naming h when the analyses cannot take it (h = 0)."""
    if not p.h > 0:
        raise ValueError(f"DBMAParams: h = {p.h!r} m must be > 0 for an analysis: the hinge "
                         "offset sets the amplification (R ~ 1/h in Eq. 7 and the enhanced "
                         "model), infinite at h = 0")


def check_mesh_budget(p: DBMAParams, layout, dim: int, size_factor: float,
                      hinge_elements: int | None = None, max_dofs: int | None = None) -> dict:
    """The mesh estimate, after BudgetError if it is above ``max_dofs`` (None: the
    machine's default budget)."""
    estimate = estimate_mesh(p, layout, dim, hinge_elements, size_factor)
    check_budget(estimate, dim, max_dofs,
                 what=f"the DBMA {dim}-D mesh at size_factor {size_factor:g}")
    return estimate


def check_result(out: dict, p: DBMAParams) -> dict:
    """``out`` if its numbers are finite and R_fem > 0, else ValueError with the numbers."""
    require_finite(out, "DBMA")
    if "R_fem" in out and not out["R_fem"] > 0:
        raise ValueError(
            f"R_fem = {out['R_fem']:.3g}: the output moves against the amplifying direction, "
            f"outside the validity of the DBMA's models (h = {p.h:g} m is too small next to "
            f"the hinge thickness b = {p.b:g} m); no amplification ratio to report")
    return out


def validity_notes(p: DBMAParams, out: dict) -> list[str]:
    """Sentences flagging the formulas of ``out`` used beyond their assumptions."""
    notes = []
    if p.h < p.b:
        notes.append(f"h = {p.h:g} m < b = {p.b:g} m: Eq. 7 (R_eq7 = {out.get('R_eq7', 0):.3g}) "
                     "assumes rigid levers; here the hinges' bending dominates, trust R_fem "
                     "and R_enhanced")
    return notes
