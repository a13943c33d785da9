"""``flexfem reproduce``: regenerate every comparison with the source documents into one report.

Each section is one mechanism study's ``reproduce(out_dir, quick) -> summary`` function. A
section that fails is recorded with its error and the others still run; each section's
summary is written to ``<out>/<section>/summary.json`` as soon as it finishes, so an
interrupted run keeps the finished sections and a re-run with ``--resume`` skips them.
"""
from dataclasses import dataclass
import importlib
import json
import os
from pathlib import Path
import platform
import sys
import time
import traceback

from .report import write_report
from .serialize import jsonable

# (section folder, title, "module:function") in report order
SECTIONS = [
    ("dbma_analytical", "DBMA: pseudo-rigid-body and enhanced analytical models",
     "flexfem.studies.dbma_figures:reproduce_analytical"),
    ("dbma_fem", "DBMA: FEM amplification ratio, stress, modes and convergence",
     "flexfem.studies.dbma_fem:reproduce"),
    ("dbma_optimize", "DBMA: FEM-decided hinge design search (beyond the sources)",
     "flexfem.studies.dbma_optimize:reproduce"),
    ("eightbar_rigid", "Eight-bar and straight-line linkages: rigid-body paths and synthesis",
     "flexfem.studies.eightbar_path:reproduce"),
    ("eightbar_fem", "Eight-bar flexure suspension: FEM, stress and large-deflection path",
     "flexfem.studies.eightbar_fem:reproduce"),
    ("balancing", "Five-bar robot: optimum static balancing and flexure pivots",
     "flexfem.studies.balancing:reproduce"),
    ("studies_engine", "Study engine: sweep and Richardson convergence checked on a closed form",
     "flexfem.studies.sweep:reproduce"),
]


@dataclass(frozen=True)
class Settings:
    """quick: smoke-run sizes (< 2 min); full: the finest meshes; resume: keep sections whose
    summary.json already exists in the output folder."""

    quick: bool = False
    full: bool = False
    resume: bool = False

    def __post_init__(self):
        if self.quick and self.full:
            raise ValueError("choose at most one of quick and full")


def _load(target: str):
    module_name, function_name = target.split(":")
    return getattr(importlib.import_module(module_name), function_name)


def run_section(folder: Path, target: str, settings: Settings) -> dict:
    """Run one section into ``folder``; never raises: a failure becomes ``{"error": ...}``."""
    done = folder / "summary.json"
    if settings.resume and done.exists():
        return json.loads(done.read_text())
    folder.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    try:
        reproduce = _load(target)
        kwargs = {"quick": settings.quick}
        if settings.full:
            kwargs["full"] = True
        try:
            summary = reproduce(folder, **kwargs)
        except TypeError as error:
            if "full" not in str(error):
                raise
            summary = reproduce(folder, quick=settings.quick)
        summary = dict(summary)
    except Exception as error:  # a failing section must not lose the others
        summary = {"error": f"{type(error).__name__}: {error}",
                   "traceback": traceback.format_exc(limit=6)}
    summary["wall_time_s"] = time.perf_counter() - start
    done.write_text(json.dumps(jsonable(summary), indent=1))
    return summary


def flexfem_version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("flexfem")
    except PackageNotFoundError:
        return "unknown"


def environment() -> dict:
    """Versions and machine facts recorded in the report."""
    from importlib.metadata import PackageNotFoundError, version
    versions = {}
    for package in ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "matplotlib", "pyamg", "pypardiso"):
        try:
            versions[package] = version(package)
        except PackageNotFoundError:
            versions[package] = None
    return {"flexfem": flexfem_version(), "python": sys.version.split()[0],
            "platform": platform.platform(), "cpus": os.cpu_count(), "packages": versions}


def reproduce(out_dir, quick: bool = False, full: bool = False, resume: bool = False,
              sections=None, progress=None) -> dict:
    """Run every section (or the named ``sections``) into ``out_dir``; write report.md and
    index.html there. Returns the summary: per-section comparisons, files and errors."""
    settings = Settings(quick=quick, full=full, resume=resume)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    chosen = [s for s in SECTIONS if sections is None or s[0] in sections]
    if sections is not None and len(chosen) != len(set(sections)):
        known = [s[0] for s in SECTIONS]
        raise ValueError(f"unknown section(s) {sorted(set(sections) - set(known))}; known: {known}")
    start = time.perf_counter()
    results = []
    for folder, title, target in chosen:
        if progress:
            progress(f"{folder} ...")
        summary = run_section(out / folder, target, settings)
        if progress:
            status = "failed: " + summary["error"] if "error" in summary else "done"
            progress(f"{folder} {status} ({summary['wall_time_s']:.1f} s)")
        results.append({"section": folder, "title": title, **summary})
    report = {"settings": {"quick": quick, "full": full}, "environment": environment(),
              "wall_time_s": time.perf_counter() - start, "sections": results}
    write_report(out, report)
    return report
