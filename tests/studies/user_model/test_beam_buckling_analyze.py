"""flexfem analyze --model beam gives [analysis] buckling through the beam models' geometric
stiffness: the parallel guide under a compressive stage load, beside the continuum's."""
import json
from pathlib import Path

from flexfem.studies.cli import main

GUIDE = Path(__file__).parents[3] / "examples" / "bodies" / "guide.toml"


def test_the_beam_models_buckling_beside_the_continuums(tmp_path, capsys):
    model = tmp_path / "guide.toml"
    text = GUIDE.read_text()
    assert "force = [1.0, 0.0]" in text
    model.write_text(text.replace("force = [1.0, 0.0]", "force = [0.0, -1.0]"))
    factors = {}
    for which in ("beam", "continuum"):
        assert main(["analyze", str(model), "--model", which, "--set", "analysis.buckling=2",
                     "--json"]) == 0
        factors[which] = json.loads(capsys.readouterr().out)["buckling"]["load_factors"]
    # two leaves in compression, clamped at both ends with a sidesway stage: the first factor
    # is the sway mode, the second the symmetric one (about 4x: 4 pi^2 EI/L^2 vs pi^2 EI/L^2)
    for beam, solid in zip(factors["beam"], factors["continuum"]):
        assert abs(beam / solid - 1) < 0.03
    assert 3.5 < factors["beam"][1] / factors["beam"][0] < 4.5
