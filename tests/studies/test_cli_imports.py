"""The command line starts lightly (issue 33): its parsers import none of the libraries the
commands compute with, and ``flexfem analyze FILE --model beam`` runs without the continuum's
mesher, plotting or the topology optimisation. Structural: what a new process has imported
at its end (sys.modules), no timing."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

BODIES = Path(__file__).parents[2] / "examples" / "bodies"
# what the beam model's analysis never needs
NOT_FOR_THE_BEAM = ("gmsh", "matplotlib", "flexfem.topopt")
# ... nor the continuum's assembly and meshes (the results the beam shares with it live in
# numpy-only modules: fem/compliance_result.py, fem/frequency_response.py,
# fem/state_buckling.py)
CONTINUUM = ("skfem", "meshio", "flexfem.fem.model")

RUNNER = """
import json, sys
from flexfem.studies.cli import {call}
status = {run}
wanted = json.loads(sys.argv[1])
found = sorted(m for m in sys.modules if any(m == w or m.startswith(w + ".") for w in wanted))
print("IMPORTED " + json.dumps([status, sorted({{w for w in wanted for m in found
                                                 if m == w or m.startswith(w + ".")}})]))
"""


def imported(call: str, run: str, wanted, *argv) -> tuple:
    """(exit status, the names of ``wanted`` imported) of ``run`` in a new process."""
    code = RUNNER.format(call=call, run=run)
    out = subprocess.run([sys.executable, "-c", code, json.dumps(list(wanted)), *map(str, argv)],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    line = next(x for x in out.stdout.splitlines() if x.startswith("IMPORTED "))
    status, names = json.loads(line[len("IMPORTED "):])
    return status, names, out.stdout


def test_the_parsers_import_no_library_the_commands_compute_with():
    heavy = ("numpy", "scipy", "skfem", "gmsh", "matplotlib", "meshio", "flexfem.topopt",
             "flexfem.reduced")
    status, names, _ = imported("build_parser", "build_parser() and 0", heavy)
    assert (status, names) == (0, [])


@pytest.mark.parametrize("name", ["guide.toml", "bridge.toml"])
def test_a_beam_analysis_imports_neither_gmsh_nor_matplotlib_nor_topopt(name):
    status, names, stdout = imported(
        "main", "main(['analyze', sys.argv[2], '--model', 'beam', '--json'])",
        NOT_FOR_THE_BEAM, BODIES / name)
    assert status == 0 and names == []
    assert json.loads(stdout.splitlines()[0])["solver"] == "beam"


@pytest.mark.parametrize("name", ["guide.toml", "notch.toml"])
def test_a_beam_analysis_imports_no_continuum_assembly(name):
    status, names, _ = imported(
        "main", "main(['analyze', sys.argv[2], '--model', 'beam', '--json'])", CONTINUUM,
        BODIES / name)
    assert status == 0 and names == []


def test_the_continuum_still_finds_what_it_imports_on_first_use():
    """The same process after a beam analysis solves the continuum too (fem's names and the
    continuum's dispatch are imported when first used)."""
    status, names, stdout = imported(
        "main", "main(['analyze', sys.argv[2], '--model', 'beam', '--json']) or "
                "main(['analyze', sys.argv[2], '--json'])", ("skfem", "gmsh"),
        BODIES / "guide.toml")
    assert status == 0 and names == ["gmsh", "skfem"]
    beam, continuum = (json.loads(line) for line in stdout.splitlines()[:2])
    k_beam, k_continuum = (r["stiffness"]["stage"]["x"] for r in (beam, continuum))
    assert continuum["solver"] != "beam" and k_beam == pytest.approx(k_continuum, rel=0.1)
