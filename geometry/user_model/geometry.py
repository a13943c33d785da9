"""Geometry files of a model file -> FEMesh with named groups.

``.geo``: gmsh's own script; its ``DefineConstant[]`` values are overridden from
``[parameters]`` (``gmsh.parser.setNumber`` before ``gmsh.merge``: the override wins over the
default, with or without a ONELAB ``Name``) and its Physical groups name the groups.
``.step``/``.stp``/``.brep``: imported by OpenCASCADE (STEP converted to metres), groups made
by the model file's ``[[select]]`` rules. ``.msh``: a finished mesh with Physical groups.
"""
from dataclasses import dataclass
from pathlib import Path
import re
from typing import TYPE_CHECKING

from ...fem import gmsh_session
from ...fem.budget import NODES_PER_ELEMENT, TETRAHEDRA_PER_CUBE, TRIANGLE, BudgetError, \
    check_budget, default_max_dofs, memory_bytes
from ..mechanism import mesh_mechanism
from .bounded import run_bounded
from .estimate import check_outlines, estimate_geometry_mesh
from .geo_guard import check_geo, check_geometry_file
from .msh_header import check_msh_counts
from .selection import compile_rule, entity_values

if TYPE_CHECKING:  # the mesh (scikit-fem): imported by _mesh when it meshes or reads one
    from ...fem import FEMesh

GEO_SUFFIXES = (".geo",)
CAD_SUFFIXES = (".step", ".stp", ".brep")
MESH_SUFFIXES = (".msh",)
SUFFIXES = GEO_SUFFIXES + CAD_SUFFIXES + MESH_SUFFIXES
_ENTITY_WORDS = {0: "point", 1: "curve", 2: "surface", 3: "volume"}


@dataclass(frozen=True)
class GeometryInfo:
    """What a geometry file offers: groups {name: dimension}, for a .geo its DefineConstant
    names with their values (SI), and its dimension (highest entity dimension)."""

    groups: dict
    constants: dict
    dim: int = 0


def _split_top(text: str) -> list[str]:
    """Split at commas outside brackets and strings."""
    parts, depth, quote, start = [], 0, False, 0
    for i, c in enumerate(text):
        if c == '"':
            quote = not quote
        elif not quote and c in "[{(":
            depth += 1
        elif not quote and c in "]})":
            depth -= 1
        elif not quote and depth == 0 and c == ",":
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return parts


def define_constant_names(path: Path) -> list[str]:
    """Names declared in the ``DefineConstant[...]`` blocks of a .geo file (main file only)."""
    text = re.sub(r"//[^\n]*|/\*.*?\*/", "", path.read_text(errors="replace"), flags=re.S)
    names = []
    for m in re.finditer(r"DefineConstant\s*\[", text):
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {"[": 1, "]": -1}.get(text[i], 0)
            i += 1
        for item in _split_top(text[m.end():i - 1]):
            name = re.match(r"\s*([A-Za-z_]\w*)\s*=", item)
            if name:
                names.append(name.group(1))
    return names


def suffix_is_mesh(path: Path) -> bool:
    """Whether ``path`` names a finished mesh (.msh)."""
    return Path(path).suffix.lower() in MESH_SUFFIXES


def _gmsh_error(path: Path, error: Exception) -> ValueError:
    reason = str(error).strip() or "gmsh gave no reason (check that the file is complete)"
    return ValueError(f"{path}: gmsh cannot read this geometry file: {reason}")


#: Limits of the child process that reads (parses) a geometry file: CPU seconds, and the
#: share of the available memory it may take.
READ_CPU_SECONDS = 60


def _read_limits() -> dict:
    return {"memory_bytes": int(memory_bytes(default_max_dofs(3), 3)),
            "cpu_seconds": READ_CPU_SECONDS, "wall_seconds": 2 * READ_CPU_SECONDS + 10}


def _mesh_limits(dim: int, max_dofs: int) -> dict:
    """The meshing child's limits from the DOF budget: the memory the budget's solve would
    take, and a CPU time that grows with it (gmsh makes ~1e5 elements a second)."""
    cpu = 60 + max_dofs / 10_000
    return {"memory_bytes": int(memory_bytes(max_dofs, dim)), "cpu_seconds": cpu,
            "wall_seconds": 2 * cpu + 10}


def _load_geo(gmsh, path: Path, parameters: dict, root=None, allow_code=False) -> None:
    """Merge the .geo ``path`` with its DefineConstant overrides, after :func:`check_geo`
    (only what a geometry needs, reads only inside ``root``, unless ``allow_code``)."""
    check_geo(path, root, allow_code)
    for name, value in parameters.items():
        gmsh.parser.setNumber(name, [float(value)])
    try:
        gmsh.merge(str(path))
    except Exception as error:  # gmsh raises plain Exception with its message
        raise _gmsh_error(path, error) from None


def _load_cad(gmsh, path: Path, selects) -> dict:
    """Import a STEP/BREP file and make a physical group per distinct select ``group``;
    returns {group: dim}. A rule that matches nothing raises ValueError."""
    gmsh.option.setString("Geometry.OCCTargetUnit", "M")
    try:
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
    except Exception as error:
        raise _gmsh_error(path, error) from None
    if not gmsh.model.getEntities():
        raise ValueError(f"{path}: the file holds no shapes")
    chosen = {}
    for rule in selects:
        predicate = compile_rule(rule.where)
        tags = [tag for _, tag in gmsh.model.getEntities(rule.dim)
                if predicate(entity_values(gmsh, rule.dim, tag))]
        if not tags:
            raise ValueError(f"{rule.source}: [[select]] group {rule.group!r} (where "
                             f"{rule.where!r}) matches no {_ENTITY_WORDS[rule.dim]} of {path}")
        dims = chosen.setdefault(rule.group, (rule.dim, []))
        if dims[0] != rule.dim:
            raise ValueError(f"{rule.source}: [[select]] group {rule.group!r} mixes dimensions "
                             f"{dims[0]} and {rule.dim}")
        dims[1].extend(tags)
    top = max(d for d, _ in gmsh.model.getEntities())
    chosen.setdefault("body", (top, [tag for _, tag in gmsh.model.getEntities(top)]))
    for name, (dim, tags) in chosen.items():
        gmsh.model.addPhysicalGroup(dim, sorted(set(tags)), name=name)
    return {name: dim for name, (dim, _) in chosen.items()}


def _physical_groups(gmsh) -> dict:
    return {gmsh.model.getPhysicalName(d, t) or f"group{t}": d
            for d, t in gmsh.model.getPhysicalGroups()}


def inspect_geometry(path: Path, parameters: dict | None = None, selects=(), root=None,
                     allow_code: bool = False) -> GeometryInfo:
    """Read ``path`` (no meshing) and list its groups and DefineConstant values. The file is
    checked first (its content must be what its name says; a .geo passes :func:`check_geo`
    and reads only inside ``root``, default its folder), then read by gmsh in a bounded child
    process (bounded.py)."""
    path = Path(path)
    if path.suffix.lower() not in SUFFIXES:
        raise ValueError(f"{path}: unknown geometry file type {path.suffix!r}; use one of "
                         f"{', '.join(SUFFIXES)}")
    if not path.is_file():
        raise ValueError(f"{path}: the geometry file does not exist")
    check_geometry_file(path, root, allow_code)
    if suffix_is_mesh(path):
        check_msh_counts(path)
    if path.suffix.lower() in CAD_SUFFIXES:
        # a STEP/BREP file is data for OpenCASCADE, no script: read in this process (a
        # forked child can wait forever on OpenCASCADE's thread pool, copied without its
        # threads from a parent that used it)
        return _inspect(path, parameters, selects, root, allow_code)
    return run_bounded(_inspect, path, parameters, selects, root, allow_code,
                       what=f"reading {path.name}", **_read_limits())


def _inspect(path: Path, parameters, selects, root, allow_code) -> GeometryInfo:
    suffix = path.suffix.lower()
    with gmsh_session("inspect") as gmsh:
        if suffix in GEO_SUFFIXES:
            names = define_constant_names(path)
            _load_geo(gmsh, path, {k: v for k, v in (parameters or {}).items() if k in names},
                      root, allow_code)
            constants = {n: float(gmsh.parser.getNumber(n)[0]) for n in names
                         if len(gmsh.parser.getNumber(n)) == 1}
            return GeometryInfo(_physical_groups(gmsh), constants, gmsh.model.getDimension())
        if suffix in CAD_SUFFIXES:
            groups = _load_cad(gmsh, path, selects)
            return GeometryInfo(groups, {}, gmsh.model.getDimension())
        try:
            gmsh.open(str(path))
        except Exception as error:
            raise _gmsh_error(path, error) from None
        return GeometryInfo(_physical_groups(gmsh), {}, gmsh.model.getDimension())


def _refine(gmsh, refinements, coarse: float) -> None:
    """Background field: element size ``size`` within ``distance`` of each group, growing
    linearly to ``coarse`` over another ``distance``."""
    groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
    thresholds = []
    for r in refinements:
        dim, tag = groups[r.group]
        entities = [int(e) for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag)]
        distance = gmsh.model.mesh.field.add("Distance")
        key = {0: "PointsList", 1: "CurvesList", 2: "SurfacesList", 3: "VolumesList"}[dim]
        gmsh.model.mesh.field.setNumbers(distance, key, entities)
        gmsh.model.mesh.field.setNumber(distance, "Sampling", 50)
        threshold = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(threshold, "InField", distance)
        gmsh.model.mesh.field.setNumber(threshold, "SizeMin", r.size)
        gmsh.model.mesh.field.setNumber(threshold, "SizeMax", max(coarse, r.size))
        gmsh.model.mesh.field.setNumber(threshold, "DistMin", r.distance)
        gmsh.model.mesh.field.setNumber(threshold, "DistMax", 2 * r.distance)
        thresholds.append(threshold)
    field = gmsh.model.mesh.field.add("Min")
    gmsh.model.mesh.field.setNumbers(field, "FieldsList", thresholds)
    gmsh.model.mesh.field.setAsBackgroundMesh(field)


def mesh_geometry(spec, size_factor: float = 1.0, max_dofs: int | None = None) -> "FEMesh":
    """Mesh the model file's geometry (m) with its named groups. ``size_factor`` multiplies
    every element size (a .msh cannot be remeshed: only 1 is accepted). A mesh whose estimate
    (estimate.py) is above ``max_dofs`` (None: half the available memory) is refused before
    gmsh meshes it (BudgetError). A geometry file is meshed in a bounded child process
    (bounded.py) that also stops, with a BudgetError, as soon as the nodes gmsh has made
    (curves first, then surfaces, then volumes) pass the budget."""
    if not size_factor > 0:
        raise ValueError(f"size_factor = {size_factor!r} must be > 0")
    if getattr(spec, "spatial", None) is not None:
        from ..spatial.continuum import mesh_spatial

        return mesh_spatial(spec.spatial, size_factor, spec.mesh.size, spec.mesh.order,
                            max_dofs)
    if spec.mechanism is not None:
        mesh = mesh_mechanism(spec.mechanism, spec.dim, size_factor, spec.mesh.size,
                              order=spec.mesh.order, max_dofs=max_dofs)
        return with_faces(mesh, spec)
    if spec.geometry.suffix.lower() in MESH_SUFFIXES and size_factor != 1.0:
        raise ValueError(f"{spec.geometry}: a .msh mesh cannot be remeshed with size_factor "
                         f"= {size_factor}; give a .geo or CAD file")
    check_budget({"elements": 0, "nodes": 0, "dofs": 0}, spec.dim, max_dofs)  # max_dofs valid
    limit = default_max_dofs(spec.dim) if max_dofs is None else max_dofs
    check_geometry_file(spec.geometry, spec.path.parent, spec.allow_code)
    if suffix_is_mesh(spec.geometry):
        check_msh_counts(spec.geometry)
    if spec.geometry.suffix.lower() in CAD_SUFFIXES:  # see _inspect's call above
        return _mesh(spec, size_factor, max_dofs, limit)
    return run_bounded(_mesh, spec, size_factor, max_dofs, limit,
                       what=f"meshing {spec.geometry.name}", **_mesh_limits(spec.dim, limit))


def with_faces(mesh: "FEMesh", spec) -> "FEMesh":
    """``mesh`` of a mechanism with a boundary group for each face of a body the model file
    names (``stage.top``: geometry/mechanism/faces.py)."""
    from ..mechanism.faces import face_facets, parse_face

    bodies = [b.name for b in spec.mechanism.bodies]
    for name in spec.groups:
        face = parse_face(name, bodies, spec.dim)
        if face is not None and name not in mesh.boundaries:
            mesh.boundaries[name] = face_facets(mesh, spec.mechanism, name, *face)
    return mesh


def _with_refinements(gmsh, estimate: dict, spec, factor: float) -> dict:
    """``estimate`` plus the elements of each [mesh] refine band: the group's measure (a
    curve's length, a surface's area; a point counts as a disc/ball of the band) times the
    band's width 2 ``distance``, at the refined ``size``."""
    groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
    dim, extra = spec.dim, 0.0
    for r in spec.mesh.refine:
        d, tag = groups[r.group]
        h = r.size * factor
        if not h > 1e-12:
            raise ValueError(f"{spec.source}: [mesh] refine size {r.size!r} cannot be meshed")
        band = 2 * r.distance
        measure = 0.0
        for e in gmsh.model.getEntitiesForPhysicalGroup(d, tag):
            measure += 1.0 if d == 0 else _entity_measure(gmsh, d, int(e))
        region = measure * band ** (dim - d) if d < dim else measure
        cell = TRIANGLE * h * h if dim == 2 else h ** 3 / TETRAHEDRA_PER_CUBE
        extra += region / cell
    if not extra:
        return estimate
    elements = estimate["elements"] + extra
    nodes = NODES_PER_ELEMENT[(dim, spec.mesh.order)] * elements
    return {"elements": int(min(elements, 1e18)), "nodes": int(min(nodes, 1e18)),
            "dofs": int(min(dim * nodes, 1e18))}


def _entity_measure(gmsh, dim: int, tag: int) -> float:
    try:
        return float(gmsh.model.occ.getMass(dim, tag))
    except Exception:  # noqa: BLE001 - a built-in kernel entity: its bounding box
        box = gmsh.model.getBoundingBox(dim, tag)
        sides = sorted((max(box[3 + k] - box[k], 0.0) for k in range(3)), reverse=True)
        return float(sum(sides[:1])) if dim == 1 else float(sides[0] * sides[1])


def _check_nodes(gmsh, spec, limit: int, stage: str, what: str) -> None:
    """BudgetError when the nodes gmsh has made so far (order 1) already mean more DOFs
    than ``limit`` at the model's element order."""
    nodes = len(gmsh.model.mesh.getNodes()[0])
    per_node = NODES_PER_ELEMENT[(spec.dim, spec.mesh.order)] / NODES_PER_ELEMENT[(spec.dim, 1)]
    dofs = int(spec.dim * nodes * per_node)
    if dofs > limit:
        raise BudgetError(f"{what}: gmsh made {nodes:,} nodes on the {stage} alone, about "
                          f"{dofs:,} DOFs at order {spec.mesh.order}, above the budget of "
                          f"{limit:,} DOFs; check the .geo's element sizes (Transfinite, "
                          "MeshSize, Field) or raise the budget with --max-dofs N")


def _mesh(spec, size_factor: float, max_dofs, limit: int) -> "FEMesh":
    from ...fem import mesh_from_gmsh, read_mesh  # scikit-fem: imported where a mesh is made

    suffix = spec.geometry.suffix.lower()
    if suffix in MESH_SUFFIXES:
        return _check_dim(read_mesh(spec.geometry), spec)
    with gmsh_session("model") as gmsh:
        if suffix in GEO_SUFFIXES:
            _load_geo(gmsh, spec.geometry, spec.parameters, spec.path.parent, spec.allow_code)
        else:
            _load_cad(gmsh, spec.geometry, spec.selects)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        factor = size_factor * gmsh.option.getNumber("Mesh.MeshSizeFactor")  # the .geo's too
        gmsh.option.setNumber("Mesh.MeshSizeFactor", factor)
        xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
        coarse = spec.mesh.size or 0.1 * ((xmax - xmin) ** 2 + (ymax - ymin) ** 2
                                          + (zmax - zmin) ** 2) ** 0.5
        if spec.mesh.size:
            gmsh.option.setNumber("Mesh.MeshSizeMax", min(
                spec.mesh.size, gmsh.option.getNumber("Mesh.MeshSizeMax")))
        size_max = gmsh.option.getNumber("Mesh.MeshSizeMax")
        if spec.mesh.refine:
            _refine(gmsh, spec.mesh.refine, coarse)
        off_plane = max(abs(zmin), abs(zmax))  # OpenCASCADE pads boxes by 1e-7 m
        if spec.dim == 2 and off_plane > 1e-6 * (1 + max(xmax - xmin, ymax - ymin)):
            raise ValueError(f"{spec.geometry}: a 2-D model must lie in the plane z = 0; it "
                             f"spans z = {zmin:.4g} to {zmax:.4g} m")
        if gmsh.model.getDimension() != spec.dim:
            raise ValueError(f"{spec.source}: dim = {spec.dim} but {spec.geometry} is "
                             f"{gmsh.model.getDimension()}-D")
        what = f"the mesh of {spec.geometry.name} at size_factor {size_factor:g}"
        estimate = estimate_geometry_mesh(gmsh, spec.dim, spec.mesh.order, factor, size_max,
                                          what)
        estimate = _with_refinements(gmsh, estimate, spec, factor)
        check_budget(estimate, spec.dim, max_dofs, what=what)
        check_outlines(gmsh, what)
        stages = {1: "curves", 2: "surfaces", 3: "volumes"}
        try:
            for stage in range(1, spec.dim + 1):
                gmsh.model.mesh.generate(stage)
                _check_nodes(gmsh, spec, limit, stages[stage], what)
        except BudgetError:
            raise
        except Exception as error:
            reason = str(error) or gmsh.logger.getLastError() or "gmsh gave no reason"
            raise ValueError(f"{spec.geometry}: gmsh could not mesh it: {reason}") from None
        return _check_dim(mesh_from_gmsh(gmsh), spec)


def _check_dim(mesh: "FEMesh", spec) -> "FEMesh":
    if mesh.dim != spec.dim:
        raise ValueError(f"{spec.source}: dim = {spec.dim} but the mesh of {spec.geometry} is "
                         f"{mesh.dim}-D")
    return mesh
