"""The stroke limits' stress basis is honest: a peak at a sharp re-entrant corner, found from
the mesh (the outline's interior angle at the peak, with no fillet spreading it), is called
singular and never converging: the cross pivot's fused crossing and the remote-centre
pivot's roots are; a filleted leaf's root and a notch are not."""
from pathlib import Path

import numpy as np
import pytest
import skfem
from flexfem.geometry.user_model import load_spec
from flexfem.studies.user_model.analysis import analyze_model, build
from flexfem.studies.user_model.corners import interior_angles, sharp_corner
from flexfem.studies.user_model.stroke import stroke_limits

BODIES = Path(__file__).parents[3] / "examples" / "bodies"


def _filleted_guide(tmp_path, fillet=0.0005) -> Path:
    path = tmp_path / "guide.toml"
    path.write_text((BODIES / "guide.toml").read_text().replace(
        'thickness = "t"', f'thickness = "t"\nfillet = {fillet}'))
    return path


def test_interior_angles_of_an_l_shape():
    """An L of three unit squares: 90 deg at its five convex corners, 270 deg at the
    re-entrant one, 180 deg along its edges, 360 deg inside."""
    mesh = skfem.MeshTri.init_tensor(np.linspace(0, 2, 9), np.linspace(0, 2, 9))
    mesh = mesh.remove_elements(np.nonzero((mesh.p[:, mesh.t].mean(axis=1) > 1).all(axis=0))[0])
    angles = interior_angles(mesh)
    at = {tuple(np.round(mesh.p[:, i], 9)): a for i, a in enumerate(angles)}
    assert at[(1.0, 1.0)] == pytest.approx(270.0)
    for corner in [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 2.0), (0.0, 2.0)]:
        assert at[corner] == pytest.approx(90.0)
    assert at[(0.5, 0.0)] == pytest.approx(180.0) and at[(0.5, 0.5)] == pytest.approx(360.0)
    found = sharp_corner(mesh, [1.1, 1.05])
    assert found["point"] == pytest.approx([1.0, 1.0]) and found["angle_deg"] == pytest.approx(270)
    assert sharp_corner(mesh, [0.0, 0.5]) is None  # a convex corner is no singularity


@pytest.mark.parametrize("name", ["cross_pivot", "remote_centre"])
def test_a_fused_crossing_and_square_roots_are_singular(name):
    spec = load_spec(BODIES / f"{name}.toml")
    out = analyze_model(spec)
    basis = out["stroke_stress_basis"]
    assert "sharp re-entrant corner" in basis and "singular" in basis
    assert "converg" not in basis  # never called converging
    assert basis.startswith("nominal beam stress")  # sized by the beam model instead
    fe, _ = build(spec)
    corner = sharp_corner(fe.mesh.mesh, out["max_von_mises_location"])
    assert corner["angle_deg"] == pytest.approx(270.0, abs=1e-6)
    assert np.linalg.norm(np.subtract(corner["point"], out["max_von_mises_location"])) < 1e-3


def test_the_cross_pivot_without_a_beam_model_says_its_limits_are_not_material_limits():
    """Where nothing can stand in for the singular peak (a drawing), the limits are still
    given but flagged: they shrink as the mesh is refined."""
    spec = load_spec(BODIES / "cross_pivot.toml")
    out = analyze_model(spec)
    fe, _ = build(spec)
    corner = sharp_corner(fe.mesh.mesh, out["max_von_mises_location"])
    limits = stroke_limits(spec, {**out, "max_von_mises_location": [1.0, 1.0]}, None, corner)
    assert limits["stroke_stress_singular"] is True
    assert "singular" in limits["stroke_stress_basis"]
    assert "converg" not in limits["stroke_stress_basis"]


def test_a_filleted_root_and_a_notch_converge(tmp_path):
    for path in (_filleted_guide(tmp_path), BODIES / "notch.toml"):
        spec = load_spec(path)
        out = analyze_model(spec)
        assert out["stroke_stress_singular"] is False
        assert "converges under refinement" in out["stroke_stress_basis"]
        assert "nominal" not in out["stroke_stress_basis"]
        fe, _ = build(spec)
        assert sharp_corner(fe.mesh.mesh, out["max_von_mises_location"]) is None
