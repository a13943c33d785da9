"""The example studies in examples/ load, and every design they declare is a valid design."""
from pathlib import Path

import pytest
from flexfem.studies.dbma.analysis import params_from_dict
from flexfem.studies.engine.sweep import design_points, load_study

EXAMPLES = sorted((Path(__file__).resolve().parents[2] / "examples").glob("*.toml"))
DESIGN_CHECKS = {"dbma": params_from_dict}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_study_declares_valid_designs(path):
    study = load_study(path)
    designs = design_points(study)
    assert len(designs) > 1
    check = DESIGN_CHECKS[study.mechanism]
    for design in designs:
        check(design)  # raises ValueError on an unknown or out-of-bounds parameter
