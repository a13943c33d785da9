"""CalculiX cross-check: write a flexfem model as a CalculiX deck, run ``ccx``, read its results.

The deck holds the same nodes and elements as the flexfem model (see
:mod:`flexfem.fem.abaqus`: node ``k + 1`` is scalar DOF ``k`` of the flexfem basis), the
material, a solid section, the supports as ``*BOUNDARY`` on their NSETs and the loads as
``*CLOAD`` of flexfem's consistent nodal force vector, so that both programs solve the same
discrete problem where their elements agree (C3D4/C3D10 vs P1/P2 tetrahedra, C3D8 vs the
trilinear hexahedron with full integration). Results are read from the ``.dat`` file.
"""
import os
import re
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .abaqus import abaqus_mesh, inp_lines, set_name
from .boundary import Fixed, Prescribed, load_vector
from .modal import solve_modes
from .model import Model, PlaneStrain, PlaneStress
from .static import solve_static

_FLOAT = r"[-+]?\d\.\d+E[-+]\d+"


@dataclass(frozen=True)
class CalculixRun:
    """One ``ccx`` run: the ``.dat`` text, wall time (s), peak resident memory of the ccx
    process (bytes) and its console output."""

    dat: str
    wall_s: float
    peak_rss_bytes: int
    stdout: str


def ccx_path() -> str | None:
    """Path of the ``ccx`` executable, or None when CalculiX is not installed."""
    return shutil.which("ccx")


def _number(x: float) -> str:
    return "%.12e" % x  # at most 19 characters: CalculiX reads 20 per field


def _check_model(model: Model, supports) -> None:
    if isinstance(model.formulation, PlaneStrain):
        raise ValueError("CalculiX decks are written for plane stress and 3-D solids only "
                         "(CalculiX's CPE elements are not wired up)")
    for s in supports:
        constant = isinstance(s, Prescribed) and not any(callable(v) for v in s.components().values())
        if not (isinstance(s, Fixed) or constant):
            raise ValueError(f"support {s!r}: only Fixed supports and Prescribed ones with constant "
                             "values are written to CalculiX decks")


def boundary_lines(model: Model, supports) -> list[str]:
    """*BOUNDARY data lines: every component of a Fixed group, and each prescribed component
    of a Prescribed one with its value (m)."""
    lines = []
    for s in supports:
        if isinstance(s, Fixed):
            lines.append(f"{set_name(s.group)}, 1, {model.dim}")
        else:
            lines += [f"{set_name(s.group)}, {i + 1}, {i + 1}, {_number(float(v))}"
                      for i, v in s.components().items() if i < model.dim]
    return lines


def nodal_forces(model: Model, loads) -> np.ndarray:
    """(n_nodes, dim) nodal forces (N) of flexfem's consistent load vector at the CalculiX
    nodes (scalar DOF k = node k + 1; vector DOF dim * k + i is component i)."""
    f = load_vector(model, loads).reshape(-1, model.dim)
    n_nodes = abaqus_mesh(model.mesh, model.order).points.shape[0]
    if np.any(f[n_nodes:]):
        raise ValueError("the load acts on face or centre nodes of scikit-fem's Q2/hexahedral "
                         "element that CalculiX's CPS8/C3D20 lack; use order=1 or a simplex mesh")
    return f[:n_nodes]


def deck_lines(model: Model, supports, loads=(), n_modes: int | None = None) -> list[str]:
    """A complete CalculiX input deck: the mesh and sets, *MATERIAL (*ELASTIC in Pa, *DENSITY
    in kg/m^3), *SOLID SECTION (with the thickness in m for plane stress), *BOUNDARY on each
    fixed group, and one step: *STATIC with *CLOAD of the nodal forces and *NODE PRINT U, or,
    with ``n_modes``, *FREQUENCY for the ``n_modes`` lowest modes."""
    _check_model(model, supports)
    am = abaqus_mesh(model.mesh, model.order)
    mat = model.material
    lines = inp_lines(am, heading=f"flexfem model: {am.element_type}, {mat.name}")
    lines += ["*MATERIAL, NAME=MAT", "*ELASTIC", f"{_number(mat.E)}, {_number(mat.nu)}",
              *(("*DENSITY", _number(mat.rho)) if mat.rho is not None else ()),
              "*SOLID SECTION, ELSET=EALL, MATERIAL=MAT"]
    if isinstance(model.formulation, PlaneStress):
        lines.append(_number(model.formulation.thickness))
    lines.append("*BOUNDARY")
    lines += boundary_lines(model, supports)
    lines.append("*STEP")
    if n_modes is not None:
        if not (isinstance(n_modes, (int, np.integer)) and n_modes >= 1):
            raise ValueError(f"n_modes = {n_modes} must be a positive integer")
        lines += ["*FREQUENCY", str(int(n_modes))]
    else:
        lines.append("*STATIC")
        forces = nodal_forces(model, loads)
        node, comp = np.nonzero(forces)
        if len(node):
            lines.append("*CLOAD")
            lines += [f"{n + 1}, {c + 1}, {_number(forces[n, c])}" for n, c in zip(node, comp)]
        lines += ["*NODE PRINT, NSET=NALL", "U"]
    lines.append("*END STEP")
    return lines


def run_ccx(lines: list[str], workdir=None, job: str = "job", threads: int = 1) -> CalculixRun:
    """Write ``lines`` to ``job.inp`` in ``workdir`` (a temporary folder by default), run
    ``ccx -i job`` with ``threads`` OpenMP/solver threads and return its results."""
    exe = ccx_path()
    if exe is None:
        raise FileNotFoundError("CalculiX (ccx) is not on PATH; install it, e.g. "
                                "apt-get install calculix-ccx")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(workdir or tmp)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / f"{job}.inp").write_text("\n".join(lines) + "\n")
        env = {**os.environ, "OMP_NUM_THREADS": str(threads),
               "CCX_NPROC_EQUATION_SOLVER": str(threads)}
        start = time.perf_counter()
        proc = subprocess.Popen([exe, "-i", job], cwd=folder, env=env, text=True,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        stdout = proc.stdout.read()
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        wall = time.perf_counter() - start
        dat = folder / f"{job}.dat"
        if proc.returncode != 0 or "*ERROR" in stdout or not dat.exists():
            errors = [l.strip() for l in stdout.splitlines() if "ERROR" in l][:5]
            raise RuntimeError(f"ccx failed (exit {proc.returncode}): {errors}")
        return CalculixRun(dat.read_text(), wall, usage.ru_maxrss * 1024, stdout)


def parse_displacements(dat: str) -> tuple[np.ndarray, np.ndarray]:
    """(node ids, (n, 3) displacements) of the last ``displacements`` block of a .dat file."""
    blocks = dat.split(" displacements (vx,vy,vz)")
    if len(blocks) < 2:
        raise ValueError("no displacement block in the .dat file (is *NODE PRINT U missing?)")
    rows = re.findall(rf"^\s*(\d+)\s+({_FLOAT})\s+({_FLOAT})\s+({_FLOAT})\s*$",
                      blocks[-1], flags=re.M)
    data = np.array(rows, dtype=float)
    return data[:, 0].astype(int), data[:, 1:]


def parse_frequencies(dat: str) -> np.ndarray:
    """Natural frequencies (Hz, the CYCLES/TIME column) of the eigenvalue output of a .dat."""
    if "E I G E N V A L U E" not in dat:
        raise ValueError("no eigenvalue output in the .dat file")
    section = dat.split("E I G E N V A L U E   O U T P U T")[1].split("P A R T I C I P")[0]
    rows = re.findall(rf"^\s*\d+\s+({_FLOAT})\s+({_FLOAT})\s+({_FLOAT})", section, flags=re.M)
    return np.array([float(r[2]) for r in rows])


def calculix_static(model: Model, supports, loads, threads: int = 1, workdir=None):
    """Run the static problem in CalculiX. Returns ((n_nodes, dim) displacement (m) at the
    CalculiX nodes, i.e. at flexfem's scalar DOF locations, and the :class:`CalculixRun`)."""
    run = run_ccx(deck_lines(model, supports, loads), workdir, threads=threads)
    ids, u = parse_displacements(run.dat)
    out = np.zeros((ids.max(), 3))
    out[ids - 1] = u
    return out[:, :model.dim], run


def calculix_frequencies(model: Model, n: int, supports, threads: int = 1, workdir=None):
    """Run a CalculiX *FREQUENCY step. Returns ((n,) natural frequencies in Hz, the run)."""
    run = run_ccx(deck_lines(model, supports, n_modes=n), workdir, threads=threads)
    return parse_frequencies(run.dat)[:n], run


def flexfem_nodal_displacement(model: Model, u: np.ndarray) -> np.ndarray:
    """(n_nodes, dim) flexfem displacement at the CalculiX nodes (vector DOF dim * k + i)."""
    n_nodes = abaqus_mesh(model.mesh, model.order).points.shape[0]
    return u.reshape(-1, model.dim)[:n_nodes]


def compare_with_calculix(model: Model, supports, loads, n_modes: int = 6,
                          threads: int = 1) -> dict:
    """Solve ``model`` in flexfem and CalculiX and compare: the largest displacement magnitude
    (m) at the common nodes and the ``n_modes`` lowest frequencies (Hz). Returns
    ``{"comparisons": [{"quantity", "flexfem", "calculix", "rel_diff", "note"}, ...],
    "element": ..., "n_dofs": ...}``; JSON-able."""

    u = flexfem_nodal_displacement(model, solve_static(model, supports, loads).u)
    u_ccx, _ = calculix_static(model, supports, loads, threads=threads)
    f = solve_modes(model, n_modes, supports).frequencies_hz
    f_ccx, _ = calculix_frequencies(model, n_modes, supports, threads=threads)
    element = abaqus_mesh(model.mesh, model.order).element_type
    rows = [("max displacement (m)", float(np.linalg.norm(u, axis=1).max()),
             float(np.linalg.norm(u_ccx, axis=1).max()))]
    rows += [(f"f{k + 1} (Hz)", float(a), float(b)) for k, (a, b) in enumerate(zip(f, f_ccx))]
    note = f"same mesh and nodal forces, CalculiX {element}"
    return {"element": element, "n_dofs": int(model.n_dofs),
            "comparisons": [{"quantity": q, "flexfem": a, "calculix": b,
                             "rel_diff": (a - b) / b if b else float("nan"), "note": note}
                            for q, a, b in rows]}
