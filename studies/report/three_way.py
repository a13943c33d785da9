"""Three-way tables of a mechanism's models: closed form (PRBM), beam model and continuum FEM,
and their report rows (beam judged against the continuum).

    rows = [Metric("k_x", "N/m", prbm, beam, continuum, STIFFNESS_TOL), ...]
    three_way_rows(rows)        # JSON-able dicts for the CSV
    beam_comparisons(rows)      # Comparison rows: the beam model, the continuum as reference
    key_table(rows, title)      # the report's small printed table
"""
from dataclasses import dataclass
import math

from .comparison import Comparison, rel_diff
from .format import number

STIFFNESS_TOL = 0.03  # stiffnesses and frequencies: beam within 3 % of the continuum
STRESS_TOL = 0.10     # peak stresses: within 10 %


@dataclass(frozen=True)
class Metric:
    """One quantity by the three models (nan where a model has none); tolerance: of the beam
    model against the continuum (relative, None: not judged)."""

    quantity: str
    unit: str
    prbm: float
    beam: float
    continuum: float
    tolerance: float | None = STIFFNESS_TOL
    note: str = ""


def three_way_rows(metrics) -> list:
    """[{quantity, unit, prbm, beam, continuum, beam_error, prbm_error}] (errors relative to
    the continuum)."""
    return [{"quantity": m.quantity, "unit": m.unit, "prbm": m.prbm, "beam": m.beam,
             "continuum": m.continuum, "beam_error": rel_diff(m.beam, m.continuum),
             "prbm_error": rel_diff(m.prbm, m.continuum), "note": m.note} for m in metrics]


def beam_comparisons(metrics, source: str = "continuum FEM (2-D, same design)") -> list:
    """Comparison rows of the beam model against the continuum FEM (kind "derived")."""
    return [Comparison(f"{m.quantity} (beam model)", m.beam, m.continuum, m.unit, source,
                       kind="derived", tolerance=m.tolerance, note=m.note).to_row()
            for m in metrics if math.isfinite(m.beam) and math.isfinite(m.continuum)]


def key_table(metrics, title: str) -> dict:
    """The report's printed table: quantity, PRBM, beam, continuum (with their units, scaled
    for reading), beam and PRBM errors against the continuum (%)."""
    pct = lambda v, ref: 100 * rel_diff(v, ref)
    return {"title": title,
            "columns": ["quantity", "PRBM / closed form", "beam model", "continuum FEM",
                        "beam error (%)", "PRBM error (%)"],
            "rows": [[m.quantity, number(m.prbm, m.unit), number(m.beam, m.unit),
                      number(m.continuum, m.unit), pct(m.beam, m.continuum),
                      pct(m.prbm, m.continuum)] for m in metrics]}
