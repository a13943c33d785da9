"""The spatial beam model against the continuum of the same file (issue 35): within 3 % in
the compliant directions (the static stiffness along the load) and 10 % in the support
directions (the compliance diagonal of the moving body's rigid face; in the compliant
direction that face, which holds the leaves' roots, is a few per cent stiffer than the
static solve's body, so that direction is compared by the static load), for the leaf
guide and the cross-spring pivot at the default mesh (the beam 0.983-1.015 of the continuum;
the leaf guide's k_z and k_rx 0.957: the continuum's rigid face hides the roots' axial
compliance the beam model has), and for the four-wire guide (its wires' cells curved onto
their cylinders: every stiffness of the compliance diagonal within 3 %)."""
from pathlib import Path

import numpy as np
import pytest

from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model.analysis import analyze_model

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"


@pytest.mark.slow
@pytest.mark.parametrize("name, body, compliant, within_3", [
    ("leaf_guide", "stage", [1], []), ("cross_pivot", "rotor", [5], []),
    ("wire_guide", "stage", [0, 1, 5], range(6))])
def test_beam_within_3_percent_compliant_10_support(name, body, compliant, within_3):
    runs = {}
    for model in ("beam", "continuum"):
        spec = load_spec(EXAMPLES / f"{name}.toml", {"analysis.compliance": body,
                                                     "analysis.modes": 1})
        runs[model] = analyze_model(spec, model=model)
    (axis, k_beam), = runs["beam"]["stiffness"][body].items()
    assert k_beam == pytest.approx(runs["continuum"]["stiffness"][body][axis], rel=0.03)
    diagonal = {m: 1 / np.diag(np.array(r["compliance"]["matrix"])) for m, r in runs.items()}
    ratio = diagonal["beam"] / diagonal["continuum"]
    support = [i for i in range(6) if i not in compliant]
    assert np.all(np.abs(ratio[support] - 1) < 0.10), ratio
    assert np.all(np.abs(ratio[list(within_3)] - 1) < 0.03), ratio
    assert runs["beam"]["compliance"]["centre_of_compliance_m"] == pytest.approx(
        runs["continuum"]["compliance"]["centre_of_compliance_m"], abs=1e-4)
