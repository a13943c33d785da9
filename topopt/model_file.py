"""A density design as a flexfem model file: the outline's polygons as a gmsh .geo with a
Physical Curve where each support, load and spring was, and the .toml that ``flexfem
analyze`` (and every study of a model file) reads (docs/model_files.md)."""
from pathlib import Path

import numpy as np

from .outline import Outline

REACH = 0.51  # a group's curves lie within this many longer element sides of its nodes


def groups_of(problem) -> list:
    """(group name, region, kind) of every support ('support<k>'), load ('load<k>') and
    spring (its name)."""
    out = [(f"support{k}", s.where, "support") for k, s in enumerate(problem.supports)]
    out += [(name, ld.where, "load") for name, ld in problem.load_groups()]
    return out + [(s.name, s.where, "spring") for s in problem.springs]


def _zones(problem) -> dict:
    """{group: (shapely zone, axis)}: the union of disks of REACH elements about its nodes;
    axis 0 (1) where the nodes line an edge x = const (y = const), else None."""
    from shapely import MultiPoint

    g = problem.grid
    r = REACH * max(g.dx, g.dy)
    out = {}
    for name, where, _ in groups_of(problem):
        xy = g.nodes[where.nodes(g)]
        out[name] = (MultiPoint(xy).buffer(r, 32), edge_axis(xy, r))
    return out


def edge_axis(xy: np.ndarray, scale: float):
    """0 (1) where the points ``xy`` (n, 2; m) line an edge x = const (y = const), to
    1e-9 of ``scale`` (m); else None."""
    line = [a for a in (0, 1) if len(xy) > 1 and np.ptp(xy[:, a]) <= 1e-9 * scale]
    return line[0] if line else None


def along_edge(t, axis: int):
    """Whether direction(s) ``t`` ((2,) or (2, n)) lie within 60 degrees of an edge normal to
    ``axis`` (0: an edge x = const): the outline's chamfer at a boundary element's corner
    (45 degrees) belongs to the edge, the faces that meet it at a corner (90) do not."""
    t = np.asarray(t, dtype=float)
    return np.abs(t[axis]) <= np.sin(np.radians(60.0)) * np.hypot(t[0], t[1])


def _member(a, b, zone, axis) -> bool:
    """Whether the line a-b belongs to a group: its midpoint in the zone and, where the
    group lines an edge, along it (:func:`along_edge`)."""
    from shapely import Point

    return zone.contains(Point(np.mean([a, b], axis=0))) and (
        axis is None or bool(along_edge(np.subtract(b, a), axis)))


def _split_ring(coords, zones: dict) -> list:
    """The ring's vertices (closed, last = first dropped) with a vertex added wherever an
    edge crosses a zone's boundary, so that every edge lies inside or outside each zone."""
    from shapely import LineString, Point, union_all

    cuts = union_all([z.boundary for z, _ in zones.values()]) if zones else None
    ring = np.asarray(coords)[:-1]
    out = []
    for a, b in zip(ring, np.roll(ring, -1, axis=0)):
        out.append(tuple(a))
        if cuts is None:
            continue
        hit = LineString([a, b]).intersection(cuts)
        points = [p for p in getattr(hit, "geoms", [hit]) if isinstance(p, Point)]
        t = sorted(np.hypot(p.x - a[0], p.y - a[1]) for p in points)
        length = np.hypot(*(b - a))
        for s in t:
            if 1e-9 * length < s < (1 - 1e-9) * length:
                out.append(tuple(a + (b - a) * s / length))
    return out


def geo_text(problem, outline: Outline, size: float) -> tuple:
    """(the .geo's text, {group: number of curves}); ``size``: element size (m)."""
    zones = _zones(problem)
    lines = [f"// A density design's outline (flexfem.topopt), m\nlc = {float(size)!r};"]
    members = {name: [] for name in zones}
    point_id = line_id = loop_id = 0
    surfaces = []
    for part in outline.parts:
        loops = []
        for ring in [part.exterior, *part.interiors]:
            verts = _split_ring(ring.coords, zones)
            first = point_id + 1
            for x, y in verts:
                point_id += 1
                lines.append(f"Point({point_id}) = {{{float(x)!r}, {float(y)!r}, 0, lc}};")
            ids = list(range(first, point_id + 1))
            curves = []
            for a, b in zip(ids, ids[1:] + ids[:1]):
                line_id += 1
                lines.append(f"Line({line_id}) = {{{a}, {b}}};")
                curves.append(line_id)
                for name, (zone, axis) in zones.items():
                    if _member(verts[a - first], verts[b - first], zone, axis):
                        members[name].append(line_id)
            loop_id += 1
            lines.append(f"Curve Loop({loop_id}) = {{{', '.join(map(str, curves))}}};")
            loops.append(loop_id)
        surfaces.append(loop_id)
        lines.append(f"Plane Surface({loop_id}) = {{{', '.join(map(str, loops))}}};")
    for name, ids in members.items():
        if ids:
            lines.append(f'Physical Curve("{name}") = {{{", ".join(map(str, ids))}}};')
    lines.append(f'Physical Surface("body") = {{{", ".join(map(str, surfaces))}}};')
    return "\n".join(lines) + "\n", {k: len(v) for k, v in members.items()}


def _toml_text(problem, geo_name: str, material: dict, case: int = 1) -> str:
    cases = f", load case {case}" if problem.n_cases > 1 else ""
    out = [f'# A density design of flexfem.topopt{cases}; flexfem analyze THIS.toml\n'
           f'geometry = "{geo_name}"\ndim = 2\n\n[material]\n'
           + "".join(f"{k} = {float(v)!r}\n" for k, v in material.items())
           + f'\n[section]\nkind = "plane_stress"\n'
           f'thickness = {problem.thickness!r}\n\n[mesh]\norder = 2\n']
    for k, s in enumerate(problem.supports):
        fixed = "".join(f"{a} = 0.0\n" for a in s.fix) if len(s.fix) < 2 else ""
        out.append(f'[[supports]]\ngroup = "support{k}"\n{fixed}')
    for name, ld in problem.load_groups(case):
        out.append(f'[[loads]]\ngroup = "{name}"\nforce = [{ld.force[0]!r}, {ld.force[1]!r}]\n')
    for s in problem.springs:
        out.append(f'[[loads]]          # no force: its mean displacement is reported\n'
                   f'group = "{s.name}"\nforce = [0.0, 0.0]\n')
    springs = ", ".join(f"{s.name} {s.stiffness!r} N/m along {s.dof}" for s in problem.springs)
    return "\n".join(out) + (f"\n# the design's springs (not in the model file): {springs}\n"
                             if springs else "")


def write_model(problem, outline: Outline, folder, *, rho: float, yield_strength: float,
                name: str = "design", E: float | None = None, size: float | None = None) -> Path:
    """Write ``folder/name.geo`` and ``folder/name.toml``; returns the .toml's path. ``rho``
    (kg/m^3), ``yield_strength`` (Pa) and ``E`` (Pa, default the problem's) are the model
    file's material, SI as ``flexfem analyze`` requires (E >= 1 kPa); ``size`` (m, default
    half an element): the mesh. The loads are those of load case 1; with several load cases
    ``folder/name_case<c>.toml`` holds case c's (c >= 2), on the same .geo. The springs are
    not in the file (the format has none): each becomes a force-free load group whose mean
    displacement ``flexfem analyze`` reports."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    g = problem.grid
    text, counts = geo_text(problem, outline, size or min(g.dx, g.dy) / 2)
    missing = [k for k, n in counts.items() if n == 0]
    if missing:
        raise ValueError(f"the outline does not reach {missing}: no model file written")
    (folder / f"{name}.geo").write_text(text)
    E = problem.interpolation.E0 if E is None else E
    path = folder / f"{name}.toml"
    material = {"E": E, "nu": problem.nu, "rho": rho, "yield_strength": yield_strength}
    path.write_text(_toml_text(problem, f"{name}.geo", material))
    for case in range(2, problem.n_cases + 1):
        (folder / f"{name}_case{case}.toml").write_text(
            _toml_text(problem, f"{name}.geo", material, case))
    return path
