"""The groups a model file names ([[supports]], [[loads]], [analysis], [mesh] refine),
checked against those its geometry has, each refusal naming the file's line."""
from pathlib import Path

from .geometry import CAD_SUFFIXES
from .tables import Locator


def check_groups(spec_parts: dict, groups: dict, geometry: Path, dim: int, loc: Locator):
    """Every support, load and refinement names a group of the geometry; loads a boundary."""
    listed = ", ".join(sorted(n for n, d in groups.items() if d in (dim - 1, dim)))
    entries = [("supports", i, s.group) for i, s in enumerate(spec_parts["supports"])]
    entries += [("loads", i, load.group) for i, load in enumerate(spec_parts["loads"])]
    for table, i, group in entries:
        if groups.get(group) not in (dim - 1, dim):
            hint = (" (name groups with [[select]] rules)"
                    if geometry.suffix.lower() in CAD_SUFFIXES else "")
            raise loc.error(f"[[{table}]] group {group!r} is not a group of {geometry.name}; "
                            f"groups: {listed or 'none'}{hint}", table, "group", i)
        if table == "loads" and groups[group] != dim - 1:
            raise loc.error(f"[[loads]] group {group!r} is a {dim}-D subdomain of "
                            f"{geometry.name}; a force or traction needs a boundary group "
                            f"(dimension {dim - 1})", table, "group", i)
    analysis = spec_parts["analysis"]
    named = [("compliance", analysis.compliance, dim - 1)]
    if analysis.harmonic:
        named.append(("harmonic", analysis.harmonic.group, None))
    for key, group, needed in named:
        if group is not None and (groups.get(group) not in (dim - 1, dim)
                                  or needed not in (None, groups[group])):
            raise loc.error(f"[analysis] {key} group {group!r} is not a "
                            f"{'boundary ' if needed is not None else ''}group of "
                            f"{geometry.name}; groups: {listed or 'none'}", "analysis", key)
        if group is not None and group in {s.group for s in spec_parts["supports"]}:
            raise loc.error(f"[analysis] {key} group {group!r} is held by a [[supports]]: "
                            "it does not move; name a group that does", "analysis", key)
    for r in spec_parts["mesh"].refine:
        if r.group not in groups:
            raise loc.error(f"[mesh] refine group {r.group!r} is not a group of "
                            f"{geometry.name}; groups: {listed or 'none'}", "mesh", "refine")
