"""Time flexfem against CalculiX on the same quadratic meshes: assembly, static solve and the
first 6 modes of a cantilever, with peak memory. Not a test: prints a table (and JSON lines).

    .venv/bin/python benchmarks/bench_fem.py                 # all rows (~15 min on 2 cores)
    .venv/bin/python benchmarks/bench_fem.py --sizes small   # smallest 2-D and 3-D rows
    .venv/bin/python benchmarks/bench_fem.py --case 3d-300k --program calculix  # one JSON line
    python3 benchmarks/bench_fem.py --install default        # what a plain `pip install .` gives
    .venv/bin/python benchmarks/bench_fem.py --suite solids --sizes small  # large solids, small
    .venv/bin/python benchmarks/bench_fem.py --suite solids --timeout 3600 --mem-gb 22 \
        --programs direct direct-ooc pmg calculix     # the 1M and 2M rows: ~1 h

``--suite solids``: the large 3-D P2 solids (a 1 x 0.042 x 1 m plate of 1M and of 2M DOFs, a
1 m cube of 1M DOFs; ``--sizes small``: a 36k-DOF plate and a 47k-DOF cube), static only, each
by the direct solver (in core or out of core, as fem/budget.py's plan of PARDISO's analysis
says: the JSON line records the plan, the factor's size and the backend), the iterative path
(p-multigrid CG) and CalculiX where its memory, estimated from its measured peak on the 3-D
cantilever against flexfem's, fits ``--mem-gb``; each in a process of its own: time, peak
memory, the ratios.

``--install default`` measures flexfem as a plain ``pip install .`` (no extras) installs it: it
builds a fresh virtual environment (``--venv``, default /tmp/flexfem-default-venv) from this
checkout, runs flexfem's cases with that environment's Python, and runs the 3-D rows of about
30k and 100k DOFs unless ``--rows`` says otherwise. Every flexfem line names the linear solver
that the results recorded (``solver``: mkl-pardiso, cholmod, superlu or amg-cg).

Each program measures the static and the modal case of a row in two processes of their own
(CalculiX: one ``ccx`` run per deck; flexfem: one subprocess per case, the modal one on a fresh
model), and the row's peak resident memory is the larger of the two (both are in the JSON
lines): flexfem's from ``getrusage(RUSAGE_SELF)`` of its process, CalculiX's from ``wait4`` of
the ccx process. CalculiX's times include reading its deck (it cannot be split), not writing
it; flexfem's include reading the same mesh from a .vtu file written beforehand by another
process, as the deck is (``read_mesh_s``, added to the static and modal totals of the table),
not the import of flexfem (``import_s``, reported apart).
"""
import argparse
import importlib.util
import json
import os
from pathlib import Path
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

LENGTH, HEIGHT = 1.0, 0.1  # m: cantilever 10:1 (3-D: square section HEIGHT x HEIGHT)
TIP_FORCE = 100.0          # N, -y on the tip face
N_MODES = 6
ROWS = {"2d-50k": (2, 50_000), "2d-200k": (2, 200_000), "2d-1M": (2, 1_000_000),
        "3d-30k": (3, 30_000), "3d-100k": (3, 100_000), "3d-300k": (3, 300_000)}
SMALL = ["2d-50k", "3d-100k"]
DEFAULT_INSTALL_ROWS = ["3d-30k", "3d-100k"]
REPO = Path(__file__).resolve().parents[1]
#: --suite solids: benchmarks/bench_iterative.py's meshes
SOLID_ROWS = ["plate-1M", "plate-2M", "block-1M"]
SMALL_SOLIDS = ["plate-36k", "block-47k"]
#: CalculiX's measured peak (GiB) on the 3-D cantilever of 350 727 DOFs (the 3d-300k row of
#: docs/performance.md: 5983 MiB, 1.78 x flexfem's 3366): a solid row's CalculiX estimate is
#: that multiple of PARDISO's planned factor + 1 GiB, else the peak grown as DOFs^(4/3)
CCX_PEAK_GIB, CCX_PEAK_DOFS, CCX_PER_FLEXFEM = 5983 / 1024, 350_727, 5983 / 3366


def cantilever_mesh(dim: int, target_dofs: int):
    """Structured triangle (2-D) or tetrahedron (3-D, 6 per cube) mesh of the cantilever whose
    P2 vector basis has about ``target_dofs`` DOFs; groups 'fixed' (x = 0) and 'tip' (x = L)."""
    import skfem
    from flexfem.fem import FEMesh, facets_where

    # P2 nodes per direction 2 n_cells + 1; cells along x = 10 x cells across
    n_nodes = target_dofs / dim
    ny = max(1, int(round((n_nodes / 10) ** (1 / dim) / 2)))
    nx = 10 * ny
    if dim == 2:
        mesh = skfem.MeshTri.init_tensor(np.linspace(0, LENGTH, nx + 1),
                                         np.linspace(0, HEIGHT, ny + 1))
    else:
        y = np.linspace(0, HEIGHT, ny + 1)
        mesh = skfem.MeshTet.init_tensor(np.linspace(0, LENGTH, nx + 1), y, y)
    groups = {"fixed": facets_where(mesh, lambda x: np.isclose(x[0], 0.0)),
              "tip": facets_where(mesh, lambda x: np.isclose(x[0], LENGTH))}
    return FEMesh(mesh, groups, {"body": np.arange(mesh.t.shape[1])})


def cantilever_model(dim: int, target_dofs: int, mesh=None):
    from flexfem.fem import Material, Model, PlaneStress, Solid3D

    steel = Material("steel", E=200e9, nu=0.3, rho=7800.0)
    form = PlaneStress(0.01) if dim == 2 else Solid3D()
    return Model(mesh or cantilever_mesh(dim, target_dofs), steel, form, order=2)


def _loads(dim):
    from flexfem.fem import Fixed, Force
    vector = (0.0, -TIP_FORCE) if dim == 2 else (0.0, -TIP_FORCE, 0.0)
    return [Fixed("fixed")], [Force("tip", vector)]


def write_cantilever_mesh(row: str, path: Path) -> Path:
    """The row's mesh as a .vtu file, written by the driving process as CalculiX's deck is:
    the measured process only reads it."""
    from flexfem.fem import write_mesh
    return write_mesh(cantilever_mesh(*ROWS[row]), path)


def run_flexfem(row: str, part: str = "static", mesh_path: Path | None = None) -> dict:
    """One of flexfem's two cases, as CalculiX runs its static and its frequency deck in
    two processes: ``part`` 'static' (mesh read, K assembly, static solve with stress
    recovery) or 'modes' (mesh read, M assembly, ``solve_modes`` on the fresh model: its K
    assembly is inside ``modes_s``), on the mesh file ``mesh_path`` (written here first when
    None). Times (s); the import of flexfem.fem apart."""
    t = time.perf_counter()
    from flexfem.fem import read_mesh, solve_modes, solve_static
    import_s = time.perf_counter() - t

    dim, target = ROWS[row]
    with tempfile.TemporaryDirectory() as folder:
        path = mesh_path or write_cantilever_mesh(row, Path(folder) / "cantilever.vtu")
        t = time.perf_counter()
        mesh = read_mesh(path)
        read_s = time.perf_counter() - t
    model = cantilever_model(dim, target, mesh)
    supports, loads = _loads(dim)
    out = {"row": row, "program": "flexfem", "part": part, "n_dofs": int(model.n_dofs),
           "import_s": import_s, "read_mesh_s": read_s,
           "pypardiso": importlib.util.find_spec("pypardiso") is not None,
           "mkl": importlib.util.find_spec("mkl") is not None or any(
               Path(sys.prefix, "lib").glob("libmkl_rt.*"))}
    if part == "static":
        t = time.perf_counter()
        model.stiffness_upper  # what solve_static reads
        out["assemble_K_s"] = time.perf_counter() - t
        t = time.perf_counter()
        try:
            result = solve_static(model, supports, loads, solver="direct")
            out["static_s"] = time.perf_counter() - t
            out["tip_uy_m"] = float(result.mean_displacement("tip")[1])
            out["solver"] = result.solver
        except Exception as error:  # residual check refused it, or PARDISO ran out of memory
            # the time until the refusal: factorization, solve and residual check, no stress
            # recovery (AMG-CG, the other solver, does not converge on the slender 2d-1M row)
            out["static_error"] = (f"after {time.perf_counter() - t:.1f} s: "
                                   f"{type(error).__name__} {error}")
    else:
        t = time.perf_counter()
        model.mass_upper
        out["assemble_M_s"] = time.perf_counter() - t
        t = time.perf_counter()
        try:
            modes = solve_modes(model, N_MODES, supports)
            out["modes_s"] = time.perf_counter() - t
            out["f1_hz"] = float(modes.frequencies_hz[0])
            out["modes_solver"] = modes.solver
        except Exception as error:  # e.g. PARDISO out of memory under --mem-gb
            out["modes_error"] = (f"after {time.perf_counter() - t:.0f} s: "
                                  f"{type(error).__name__} {error}")
    out["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return out


def merge_flexfem(static: dict, modes: dict) -> dict:
    """One row of flexfem from its static and its modal process: the peak memory is the
    larger of the two, as for CalculiX's two runs."""
    out = dict(static)
    for key in ("modes_s", "f1_hz", "modes_solver", "modes_error", "assemble_M_s"):
        if key in modes:
            out[key] = modes[key]
    if "error" in modes:
        out["modes_error"] = modes["error"]
    out["modes_read_mesh_s"] = modes.get("read_mesh_s")
    out["peak_rss_static_mb"] = static.get("peak_rss_mb")
    out["peak_rss_modes_mb"] = modes.get("peak_rss_mb")
    out["peak_rss_mb"] = max(v for v in (static.get("peak_rss_mb"), modes.get("peak_rss_mb"),
                                         0.0) if v is not None) or None
    out["load_avg"] = static.get("load_avg", []) + modes.get("load_avg", [])
    out.pop("part", None)
    return out


def run_calculix(row: str, threads: int) -> dict:
    """Wall times (s) and peak memory of ccx for the static and the frequency deck."""
    from flexfem.fem.calculix import deck_lines, parse_frequencies, run_ccx

    dim, target = ROWS[row]
    model = cantilever_model(dim, target)
    supports, loads = _loads(dim)
    out = {"row": row, "program": "calculix", "n_dofs": int(model.n_dofs)}
    static = run_ccx(deck_lines(model, supports, loads), threads=threads)
    out["static_s"], rss = static.wall_s, static.peak_rss_bytes
    out["peak_rss_mb"] = rss / 2**20
    t = time.perf_counter()
    try:
        freq = run_ccx(deck_lines(model, supports, n_modes=N_MODES), threads=threads)
    except RuntimeError as error:  # e.g. out of memory under --mem-gb: keep the static row
        out["modes_error"] = f"after {time.perf_counter() - t:.0f} s: {error}"
        return out
    out["modes_s"] = freq.wall_s
    out["f1_hz"] = float(parse_frequencies(freq.dat)[0])
    out["peak_rss_static_mb"] = rss / 2**20
    out["peak_rss_modes_mb"] = freq.peak_rss_bytes / 2**20
    out["peak_rss_mb"] = max(rss, freq.peak_rss_bytes) / 2**20
    return out


def solid_dofs(row: str) -> int:
    """The DOFs of a solid row's structured P2 mesh (3 a node)."""
    from bench_iterative import PLATES
    nx, ny, nz, _ = PLATES[row]
    return 3 * (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1)


def ccx_estimate_gib(n_dofs: int, factor_gib: float | None = None) -> float:
    """CalculiX's peak memory (GiB) expected of a static solve of ``n_dofs`` 3-D DOFs, from
    PARDISO's planned in-core factor (GiB) of the same matrix where known."""
    if factor_gib is not None:
        return CCX_PER_FLEXFEM * factor_gib + 1.0
    return CCX_PEAK_GIB * (n_dofs / CCX_PEAK_DOFS) ** (4 / 3)


def run_solid(row: str, program: str, threads: int) -> dict:
    """One static solve of a solid row in this process: 'direct' or 'pmg' (flexfem, through
    bench_iterative.run_case) or 'calculix' (ccx on flexfem's deck of the same mesh)."""
    from bench_iterative import plate_problem, run_case
    if program != "calculix":
        return {"row": row, "program": program, **run_case(row, program)}
    from flexfem.fem.calculix import deck_lines, parse_displacements, run_ccx
    model, supports, loads = plate_problem(row)
    out = {"row": row, "program": program, "n_dofs": int(model.n_dofs)}
    run = run_ccx(deck_lines(model, supports, loads), threads=threads)
    out.update(solve_s=run.wall_s, peak_rss_mb=run.peak_rss_bytes / 2**20,
               u_max_m=float(np.abs(parse_displacements(run.dat)[1]).max()))
    return out


def _solid_s(r: dict) -> float | None:
    """A solid run's time (s): flexfem's mesh + assembly + solve, ccx's wall time (its deck
    read and assembly included); None where it did not solve."""
    if r.get("solve_s") is None:
        return None
    return r["solve_s"] + r.get("mesh_s", 0.0) + r.get("assemble_s", 0.0)


def _solid_gb(r: dict) -> float | None:
    return r["peak_rss_mb"] / 1024 if r.get("solve_s") is not None else None


def _ratio(a, b) -> str:
    return _fmt(a / b if a is not None and b else None, ".2f")


def solid_table(results: list[dict]) -> str:
    """Markdown table of the solid rows: direct, p-multigrid CG and CalculiX side by side
    (time s: mesh + assembly + solve; peak GB), with the ratios to the direct solver, and
    PARDISO out of core forced where it ran."""
    head = ("| row | DOFs | direct backend | direct s | direct GB | pmg-cg s | pmg-cg GB | CG its "
            "| ccx s | ccx GB | pmg/direct time | pmg/direct memory | ccx/direct time | "
            "ccx/direct memory | forced out of core s | GB | direct's plan |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for row in dict.fromkeys(r["row"] for r in results):
        by = {r["program"]: r for r in results if r["row"] == row}
        d, p, c, o = (by.get(k, {}) for k in ("direct", "pmg", "calculix", "direct-ooc"))

        its = re.search(r"(\d+) CG iterations", p.get("why", ""))
        dt, pt, ct = _solid_s(d), _solid_s(p), _solid_s(c)
        gb, ratio = _solid_gb, _ratio
        lines.append(
            f"| {row} | {d.get('n_dofs', p.get('n_dofs', '-'))} | {d.get('solver', '-')} | "
            f"{_cell(dt, d.get('error'))} | {_fmt(gb(d), '.2f')} | {_cell(pt, p.get('error'))} | "
            f"{_fmt(gb(p), '.2f')} | {its.group(1) if its else '-'} | "
            f"{_cell(ct, c.get('error'))} | {_fmt(gb(c), '.2f')} | {ratio(pt, dt)} | "
            f"{ratio(gb(p), gb(d))} | {ratio(ct, dt)} | {ratio(gb(c), gb(d))} | "
            f"{_cell(_solid_s(o), o.get('error'))} | {_fmt(gb(o), '.2f')} | "
            f"{d.get('plan', '-')}: {d.get('error') or c.get('error') or ''} |")
    return "\n".join(lines)


def run_solids(rows: list[str], args, python: str) -> list[dict]:
    """Every program on every solid row, each in a process of its own; prints JSON lines."""
    results = []
    for row in rows:
        for program in args.programs:
            planned = [r["factor_gib"] for r in results if r["row"] == row and "factor_gib" in r]
            need = ccx_estimate_gib(solid_dofs(row), planned[0] if planned else None)
            if program == "calculix" and need > args.mem_gb:
                out = {"row": row, "program": program,
                       "error": f"not run: ~{need:.0f} GiB estimated, above --mem-gb"}
            elif program == "calculix" and row in args.skip_ccx:
                out = {"row": row, "program": program, "error": "not run"}
            elif program == "direct-ooc" and any(r.get("solver") == "mkl-pardiso-ooc"
                                                 for r in results if r["row"] == row):
                out = {"row": row, "program": program,
                       "error": "not run: the direct run was out of core already"}
            else:
                out = _in_subprocess(row, program, args.threads, args.timeout, args.mem_gb,
                                     python)
            print(json.dumps(out), flush=True)
            results.append(out)
    return results


def default_install(venv: Path) -> str:
    """Python of a virtual environment with flexfem installed from this checkout by a plain
    ``pip install .`` (no extras), made once at ``venv`` and reused."""
    python = venv / ("Scripts/python.exe" if os.name == "nt" else "bin/python")
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "-q", str(REPO)], check=True)
    return str(python)


def _in_subprocess(row: str, program: str, threads: int, timeout_s: float, mem_gb: float,
                   python: str = sys.executable, part: str = "static",
                   mesh_path: Path | None = None) -> dict:
    cmd = [python, __file__, "--case", row, "--program", program, "--threads", str(threads),
           "--mem-gb", str(mem_gb), "--part", part]
    cmd += ["--mesh", str(mesh_path)] if mesh_path else []
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True, start_new_session=True)
    try:
        stdout, _ = proc.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)  # the case and the ccx it started
        proc.communicate()
        return {"row": row, "program": program, "error": f"timeout after {timeout_s:.0f} s"}
    if proc.returncode != 0:
        return {"row": row, "program": program, "error": f"exit {proc.returncode}"}
    return json.loads(stdout.strip().splitlines()[-1])


def _fmt(v, spec=".1f"):
    return "-" if v is None else format(v, spec)


def _cell(value, error, spec=".1f"):
    return _fmt(value, spec) if value is not None else ("failed" if error else "-")


def table(rows: list[dict]) -> str:
    """Markdown table: one line per row, flexfem beside CalculiX with the ratios; failures and
    fallbacks in the notes column (details in the JSON lines)."""
    head = ("| mesh | DOFs | flexfem assembly K+M (s) | flexfem static (s) | ccx static (s) | "
            "ratio static | flexfem 6 modes (s) | ccx 6 modes (s) | ratio modes | "
            "flexfem peak MB | ccx peak MB | f1 flexfem / ccx (Hz) | flexfem solver | "
            "flexfem import (s) | notes |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for f, c in rows:
        asm = f.get("assemble_K_s", np.nan) + f.get("assemble_M_s", np.nan)
        # static: mesh read + K assembly + solve; modes: mesh read + M assembly + eigen solve
        # with its K assembly (ccx's own times include reading its deck and its assembly)
        read = f.get("read_mesh_s", np.nan)
        fs = read + f.get("assemble_K_s", np.nan) + f.get("static_s", np.nan)
        if "static_error" in f:  # time until the solve was refused
            fs = read + f.get("assemble_K_s", np.nan) + float(f["static_error"].split()[1])
        # the modal process: its mesh read, M assembly and solve_modes (K assembly inside)
        fm = (f.get("modes_read_mesh_s") or np.nan) + f.get("assemble_M_s", np.nan) \
            + f.get("modes_s", np.nan)
        cs, cm = c.get("static_s"), c.get("modes_s")
        notes = [f"{p}: {e}" for p, e in (("flexfem", f.get("error")), ("ccx", c.get("error")),
                                           ("flexfem static", f.get("static_error")),
                                           ("flexfem modes", f.get("modes_error")),
                                           ("ccx modes", c.get("modes_error"))) if e]
        lines.append(
            f"| {f['row']} | {f.get('n_dofs', '-')} | {asm:.1f} | {fs:.1f} | "
            f"{_cell(cs, c.get('error'))} | {_fmt(fs / cs if cs else None, '.2f')} | "
            f"{_cell(fm if 'modes_s' in f else None, f.get('modes_error'))} | "
            f"{_cell(cm, c.get('error') or c.get('modes_error'))} | "
            f"{_fmt(fm / cm if cm else None, '.2f')} | {_fmt(f.get('peak_rss_mb'), '.0f')} | "
            f"{_fmt(c.get('peak_rss_mb'), '.0f')} | {_fmt(f.get('f1_hz'), '.3f')} / "
            f"{_fmt(c.get('f1_hz'), '.3f')} | {f.get('solver', '-')} | "
            f"{_fmt(f.get('import_s'), '.1f')} | {'; '.join(notes)[:120]} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", choices=["small", "all"], default="all")
    parser.add_argument("--rows", nargs="*", choices=list(ROWS) + SOLID_ROWS + SMALL_SOLIDS,
                        help="run only these rows (of the suite)")
    parser.add_argument("--threads", type=int, default=2, help="ccx OpenMP/solver threads")
    parser.add_argument("--timeout", type=float, default=600.0, help="per program and row, s")
    parser.add_argument("--skip-ccx", nargs="*", default=[],
                        choices=list(ROWS) + SOLID_ROWS + SMALL_SOLIDS,
                        help="rows where CalculiX is not run")
    parser.add_argument("--mem-gb", type=float, default=16.0,
                        help="address-space limit of each measured process (and its ccx), GiB: "
                             "a row that needs more fails instead of exhausting the machine")
    parser.add_argument("--install", choices=["current", "default"], default="current",
                        help="'default': measure flexfem as a plain `pip install .` gives it, "
                             "in a fresh virtual environment (--venv)")
    parser.add_argument("--venv", type=Path, default=Path("/tmp/flexfem-default-venv"),
                        help="where --install default builds its environment")
    parser.add_argument("--suite", choices=["cantilever", "solids"], default="cantilever",
                        help="'solids': the large 3-D P2 plates and block, static only")
    parser.add_argument("--programs", nargs="+", default=["direct", "pmg", "calculix"],
                        choices=["direct", "direct-ooc", "pmg", "calculix"],
                        help="--suite solids: what runs on each row ('direct-ooc': PARDISO "
                             "out of core forced)")
    parser.add_argument("--case", help=argparse.SUPPRESS)
    parser.add_argument("--program", help=argparse.SUPPRESS)
    parser.add_argument("--part", default="static", help=argparse.SUPPRESS)
    parser.add_argument("--mesh", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.case:  # one measurement, in this (sub)process
        limit = int(args.mem_gb * 2**30)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        if args.program == "mesh":
            write_cantilever_mesh(args.case, args.mesh)
            print(json.dumps({"row": args.case, "mesh": str(args.mesh)}))
            return 0
        if args.case in SOLID_ROWS + SMALL_SOLIDS:
            def fn(r):
                return run_solid(r, args.program, args.threads)
        elif args.program == "flexfem":
            def fn(r):
                return run_flexfem(r, args.part, args.mesh)
        else:
            def fn(r):
                return run_calculix(r, args.threads)
        before = os.getloadavg()[0]
        out = fn(args.case)
        # 1-minute load average before and after: above the core count, times are inflated
        out["load_avg"] = [round(before, 2), round(os.getloadavg()[0], 2)]
        print(json.dumps(out))
        return 0
    python = sys.executable
    if args.suite == "solids":
        rows = args.rows or (SMALL_SOLIDS if args.sizes == "small" else SOLID_ROWS)
        if set(rows) - set(SOLID_ROWS + SMALL_SOLIDS):
            parser.error(f"--suite solids: rows are {', '.join(SOLID_ROWS + SMALL_SOLIDS)}")
        print(solid_table(run_solids(rows, args, python)))
        return 0
    rows = args.rows or (SMALL if args.sizes == "small" else list(ROWS))
    if set(rows) - set(ROWS):
        parser.error(f"--suite cantilever: rows are {', '.join(ROWS)}")
    if args.install == "default":
        rows = args.rows or DEFAULT_INSTALL_ROWS
        python = default_install(args.venv)
    results = []
    folder = tempfile.TemporaryDirectory()
    for row in rows:
        mesh_path = Path(folder.name) / f"{row}.vtu"
        _in_subprocess(row, "mesh", args.threads, args.timeout, args.mem_gb, python,
                       mesh_path=mesh_path)
        f = merge_flexfem(*(_in_subprocess(row, "flexfem", args.threads, args.timeout,
                                           args.mem_gb, python, part, mesh_path)
                            for part in ("static", "modes")))
        mesh_path.unlink(missing_ok=True)
        f["install"] = args.install
        print(json.dumps(f), flush=True)
        if row in args.skip_ccx:
            c = {"row": row, "program": "calculix", "error": "not run"}
        else:
            # the deck is written by flexfem: the same Python (and flexfem) as its cases
            c = _in_subprocess(row, "calculix", args.threads, args.timeout, args.mem_gb, python)
        print(json.dumps(c), flush=True)
        results.append((f, c))
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
