"""`flexfem dbma mesh` writes the model `analyze` solves: quadratic elements by default, and
with --deck a complete CalculiX deck that CalculiX solves to flexfem's own numbers."""
import json
import shutil
import subprocess

import pytest

from flexfem.studies.cli import main


def test_the_mesh_is_written_in_the_order_analyze_solves(tmp_path, capsys):
    assert main(["dbma", "mesh", str(tmp_path / "d.inp"), "--dim", "2", "--size-factor", "4",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["order"] == 2
    assert "*ELEMENT, TYPE=CPS6" in (tmp_path / "d.inp").read_text()
    assert main(["dbma", "mesh", str(tmp_path / "d1.inp"), "--dim", "2", "--size-factor", "4",
                 "--order", "1"]) == 0
    assert "*ELEMENT, TYPE=CPS3" in (tmp_path / "d1.inp").read_text()
    assert "order 1 (linear)" in capsys.readouterr().out


def test_a_deck_must_be_an_inp_file(tmp_path, capsys):
    assert main(["dbma", "mesh", str(tmp_path / "d.vtu"), "--deck", "static"]) == 2
    assert "--deck writes a CalculiX deck" in capsys.readouterr().err


@pytest.mark.slow
def test_calculix_solves_the_modal_deck_to_flexfems_frequencies(tmp_path, capsys):
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX (Debian package calculix-ccx) is not installed")
    options = ["--dim", "3", "--size-factor", "2"]
    assert main(["dbma", "mesh", str(tmp_path / "modal.inp"), "--deck", "modal"] + options) == 0
    subprocess.run(["ccx", "-i", "modal"], cwd=tmp_path, capture_output=True, timeout=600,
                   check=True)
    dat = (tmp_path / "modal.dat").read_text().splitlines()
    start = next(k for k, line in enumerate(dat) if "E I G E N V A L U E   O U T P U T" in line)
    ccx = [float(line.split()[3]) for line in dat[start + 6:start + 12]]
    capsys.readouterr()
    assert main(["dbma", "analyze", "--json"] + options) == 0
    flexfem = json.loads(capsys.readouterr().out)["frequencies_hz"]
    # the same mesh, elements, supports and material: the two solvers agree to round-off
    assert ccx == pytest.approx(flexfem, rel=1e-5)
