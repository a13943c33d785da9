"""``flexfem reproduce``: regenerate every comparison with the source documents into one report.

Each section is one mechanism's ``reproduce(out_dir, quick) -> summary`` function, found in the
registry (studies/mechanisms.py), in registry order. A
section that fails is recorded with its error and the others still run; each section's
summary is written to ``<out>/<section>/summary.json`` as soon as it finishes, so an
interrupted run keeps the finished sections and a re-run with ``--resume`` skips them.
"""
from dataclasses import dataclass
import json
import os
from pathlib import Path
import platform
import sys
import time
import traceback

from ..mechanisms import RegisteredMechanism, ReportSection, report_sections
from .render import write_report
from ..engine.serialize import jsonable

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


def run_section(folder: Path, mechanism: RegisteredMechanism, section: ReportSection,
                settings: Settings) -> dict:
    """Run one section into ``folder``; never raises: a failure becomes ``{"error": ...}``."""
    done = folder / "summary.json"
    if settings.resume and done.exists():
        return json.loads(done.read_text())
    folder.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    try:
        reproduce = mechanism.load(section.target)
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
    every = report_sections()
    chosen = [(m, s) for m, s in every if sections is None or s.folder in sections]
    if sections is not None and len(chosen) != len(set(sections)):
        known = [s.folder for _, s in every]
        raise ValueError(f"unknown section(s) {sorted(set(sections) - set(known))}; known: {known}")
    start = time.perf_counter()
    results = []
    for mechanism, section in chosen:
        if progress:
            progress(f"{section.folder} ...")
        summary = run_section(out / section.folder, mechanism, section, settings)
        if progress:
            status = "failed: " + summary["error"] if "error" in summary else "done"
            progress(f"{section.folder} {status} ({summary['wall_time_s']:.1f} s)")
        results.append({"section": section.folder, "title": section.title,
                        "mechanism": mechanism.name, "document": mechanism.document, **summary})
    report = {"settings": {"quick": quick, "full": full}, "environment": environment(),
              "wall_time_s": time.perf_counter() - start, "sections": results}
    write_report(out, report)
    return report
