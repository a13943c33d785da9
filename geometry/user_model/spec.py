"""A model file (TOML) -> :class:`ModelSpec`: a user's flexure given by a geometry file and
what to do with it. Every error is a ValueError naming the model file and, where the key can
be found, its line."""
from dataclasses import dataclass, field
from pathlib import Path
import tomllib

from ...fem.materials import Material
from ..mechanism import Mechanism
from ..spatial.detect import is_spatial
from .beam_tables import BeamSpec, beam_options, parse_beams
from .geo_guard import check_inside
from .mechanism_tables import (body_loads, body_supports, check_held_bodies, mechanism_parts,
                               parse_mechanism)
from .names import check_override_key, nearest, unknown_name
from .outputs_table import parse_outputs
from .points_table import parse_points
from .quantities import with_si_units
from .geometry import CAD_SUFFIXES, GEO_SUFFIXES, SUFFIXES, inspect_geometry
from .group_checks import check_groups
from .material_table import check_density, parse_material
from .tables import (Analysis, LoadSpec, Locator, MeshOptions, SectionSpec, SupportSpec,
                     is_number, parse_analysis, parse_loads, parse_mesh, parse_section,
                     parse_selects, parse_supports)

TOP_KEYS = ("geometry", "dim", "description", "parameters", "material", "section", "mesh",
            "supports", "loads", "select", "analysis", "beam", "rigid", "beam_model", "body",
            "flexure", "outputs", "points")
OVERRIDE_TABLES = ("material", "section", "mesh", "analysis", "beam_model")


@dataclass(frozen=True)
class ModelSpec:
    """A validated model file. path: the model file; geometry: the geometry file (absolute,
    resolved from the model file's folder); parameters: {DefineConstant name: value (SI)}
    overriding the .geo; groups: {group name: dimension} offered by the geometry;
    constants: the .geo's DefineConstant values after the overrides; beams: the declared
    beam model (BeamSpec, [[beam]] and [[rigid]]) or None; allow_code: the user trusts the
    file (its .geo may run code and read outside its folder); mechanism: the bodies and
    flexures of a file that describes its mechanism so (then ``geometry`` is the model file
    itself, and both the continuum and the beam model are derived from it); points: the
    [points] {name: (body, coordinates (m))} observed with their bodies; outputs: the
    [outputs] metrics (outputs_table.Output)."""

    path: Path
    geometry: Path
    dim: int
    material: Material
    section: SectionSpec
    parameters: dict = field(default_factory=dict)
    mesh: MeshOptions = MeshOptions()
    supports: tuple = ()
    loads: tuple = ()
    selects: tuple = ()
    analysis: Analysis = Analysis()
    groups: dict = field(default_factory=dict)
    constants: dict = field(default_factory=dict)
    description: str = ""
    beams: BeamSpec | None = None
    allow_code: bool = False
    mechanism: Mechanism | None = None
    outputs: tuple = ()
    points: dict = field(default_factory=dict)
    spatial: object = None  # a SpatialMechanism (geometry/spatial) of 3-D bodies

    @property
    def source(self) -> str:
        """The model file's path, for messages."""
        return str(self.path)

    @property
    def thickness(self) -> float:
        """Out-of-plane thickness (m) of a 2-D section; 1 for a solid."""
        return self.section.thickness


#: What a model file's required tables hold, for the message when one is missing.
REQUIRED = {
    "material": 'name = "structural_steel" (a library material) or E, nu and rho (SI)',
    "section": "thickness = the out-of-plane depth (m) of a planar model",
}

def _read(path: Path) -> tuple[str, dict]:
    if not path.is_file():
        raise ValueError(f"{path}: the model file does not exist")
    text = path.read_text()
    try:
        return text, tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path}: not valid TOML: {error}") from None


def _apply_overrides(raw: dict, overrides: dict | None, path: Path) -> dict:
    """NAME=value goes to [parameters]; TABLE.KEY=value (material, section, mesh, analysis,
    beam_model) to that table; a TABLE.KEY that is no key of its table is refused with the
    known keys (names.py)."""
    raw = {k: (dict(v) if isinstance(v, dict) else v) for k, v in raw.items()}
    for name, value in (overrides or {}).items():
        table, dot, key = str(name).rpartition(".")
        if dot:
            check_override_key(name, path)
        raw.setdefault(table or "parameters", {})[key] = value
    return raw


def parameter_names(raw: dict) -> set:
    """The [parameters] names a model file declares itself (before any override)."""
    table = raw.get("parameters", {})
    return set(table) if isinstance(table, dict) else set()


def model_parameter_names(path, allow_code: bool = False) -> list[str]:
    """The names an override of model file ``path`` may set besides 'table.key': a bodies
    and flexures file's [parameters], a .geo's DefineConstants (gmsh reads them), none for
    a STEP or a mesh. ValueError (naming the file) for a file that cannot be read."""
    path = Path(path)
    _, raw = _read(path)
    if "body" in raw or "flexure" in raw:
        return sorted(parameter_names(raw))
    return sorted(load_spec(path, allow_code=allow_code).constants)


def _check_declared(overridden: set, declared: set, path: Path) -> None:
    """An override of bodies and flexures names one of the file's own [parameters]: its
    expressions use no other name, so any other would leave the design unchanged."""
    for name in sorted(n for n in overridden if "." not in str(n)):
        if name not in declared:
            raise ValueError(f"{path}: override " + unknown_name(
                name, f"a [parameters] name of {path.name}", declared))


def _parameters(raw, loc: Locator, overridden: set) -> dict:
    if not isinstance(raw, dict):
        raise loc.error(f"[parameters] must be a table of numbers, not {raw!r}", "parameters")
    for name, value in raw.items():
        if not is_number(value):
            how = " (set by an override)" if name in overridden else ""
            raise loc.error(f"[parameters] {name} = {value!r}{how} must be a number (SI)",
                            "parameters", name)
    return {k: float(v) for k, v in raw.items()}


def _geometry_path(raw, loc: Locator, allow_code: bool = False) -> Path:
    value = raw.get("geometry")
    if not isinstance(value, str) or not value:
        raise loc.error('geometry = "FILE" (a .geo, .step/.stp/.brep or .msh file, relative to '
                        "the model file) is required", None, "geometry")
    path = loc.path.parent / value
    try:
        path = check_inside(path, loc.path.parent, allow_code)
    except ValueError as error:
        raise loc.error(f"geometry = {value!r}: {error}", None, "geometry") from None
    if path.suffix.lower() not in SUFFIXES:
        raise loc.error(f"geometry = {value!r}: unknown file type; use one of "
                        f"{', '.join(SUFFIXES)}", None, "geometry")
    if not path.is_file():
        raise loc.error(f"geometry = {value!r}: {path} does not exist", None, "geometry")
    return path


def _dim(raw, loc: Locator) -> int:
    section = raw.get("section")
    default = 3 if isinstance(section, dict) and section.get("kind") == "solid" else 2
    dim = raw.get("dim", default)
    if dim not in (2, 3) or isinstance(dim, bool):
        raise loc.error(f"dim = {dim!r} must be 2 or 3", None, "dim")
    return int(dim)


def _check_parameters(parameters: dict, geometry: Path, constants: dict, loc: Locator,
                      overridden: set) -> None:
    if parameters and geometry.suffix.lower() not in GEO_SUFFIXES:
        raise loc.error(f"[parameters] are DefineConstant overrides of a .geo file; "
                        f"{geometry.name} has none", "parameters")
    for name in parameters:
        if name not in constants:
            message = (f"{name!r} is not a DefineConstant of {geometry.name}; its "
                       f"constants: {', '.join(sorted(constants)) or 'none'}"
                       f"{nearest(name, constants)}")
            if name in overridden:
                raise ValueError(f"{loc.path}: override {message}")
            raise loc.error(f"[parameters] {message}", "parameters", name)


def _mechanism_spec(path: Path, raw: dict, loc: Locator, overridden: set, dim: int | None,
                    allow_code: bool) -> ModelSpec:
    """A model file of ``[[body]]`` and ``[[flexure]]`` tables: its continuum (2-D, or with
    ``dim`` 3 extruded by the [section] thickness) and its planar beam model, one
    description."""
    for key in ("geometry", "select", "beam", "rigid"):
        if key in raw:
            raise loc.error(f"{'[[' + key + ']]' if key != 'geometry' else 'geometry'} with "
                            "[[body]]/[[flexure]]: the bodies and flexures describe the whole "
                            "mechanism, its continuum and its beam model; give one or the other",
                            None if key == "geometry" else key, key if key == "geometry" else None)
    dim = dim or raw.get("dim", 2)
    if dim not in (2, 3) or isinstance(dim, bool):
        raise loc.error(f"dim = {dim!r} must be 2 or 3", None, "dim")
    for table in ("material", "section"):
        if table not in raw:
            raise loc.error(f"[{table}] is required: {REQUIRED[table]}", None)
    section_raw = dict(raw["section"]) if isinstance(raw["section"], dict) else raw["section"]
    if isinstance(section_raw, dict):
        section_raw.setdefault("kind", "plane_stress")
    section = parse_section(section_raw, 2, loc)
    if section.kind != "plane_stress":
        raise loc.error(f"[section] kind = {section.kind!r}: bodies and flexures are plane "
                        "stress (their beam model's depth contracts freely); drop kind and "
                        "give thickness = the out-of-plane depth (m)", "section", "kind")
    if "thickness" not in section_raw:
        raise loc.error("[section] of bodies and flexures: thickness = the out-of-plane depth "
                        "(m; kind plane_stress, the default)", "section")
    parts = mechanism_parts(raw, loc, section if dim == 2 else SectionSpec("solid"),
                            body_supports, body_loads, dim, "every flexure of bodies and "
                            "flexures is refined already (its thickness sets its element size)")
    parameters = _parameters(raw.get("parameters", {}), loc, overridden)
    held = {s.group for s in parts["supports"]}  # a held face holds its body
    check_held_bodies(raw, parts["supports"], loc)
    mechanism = parse_mechanism(raw, parameters, section.thickness, loc,
                                held | {g.rpartition(".")[0] for g in held if "." in g})
    if parts["mesh"].size is not None:  # a size the mesh cannot honour: refused, not raised
        from ..mechanism.draw import check_body_size

        try:
            check_body_size(mechanism, parts["mesh"].size)
        except ValueError as error:
            raise loc.error(str(error).removeprefix(f"{mechanism.source}: "), "mesh",
                            "size") from None
    groups = {b.name: dim - 1 for b in mechanism.bodies} | {"solid": dim}
    from ..mechanism.faces import face_names, named_faces, with_face_points

    bodies = [b.name for b in mechanism.bodies]
    taken = set(groups) | set(face_names(bodies, dim))
    points = {name: (body, at if len(at) == dim else (*at, mechanism.depth / 2)) for name, (
        body, at) in parse_points(raw.get("points"), parameters, bodies, dim, taken, loc).items()}
    outputs = parse_outputs(raw.get("outputs"), parameters, taken | set(points), dim, loc)
    faces = named_faces(parts, outputs, bodies, dim)
    groups |= {name: dim - 1 for name in faces}
    check_groups(parts, groups, path, dim, loc)
    from ..mechanism.beams import beam_spec  # it builds on beam_tables: imported when used

    options = beam_options(raw.get("beam_model", {}), loc)
    beams = with_face_points(beam_spec(mechanism, **options), mechanism, faces)
    return ModelSpec(path=path, geometry=path, dim=dim, parameters=parameters, groups=groups,
                     constants=dict(parameters), description=str(raw.get("description", "")),
                     beams=beams, allow_code=allow_code, mechanism=mechanism, selects=(),
                     outputs=outputs, points=points, **parts)


def _spatial_spec(path: Path, raw: dict, loc: Locator, overridden: set, dim: int | None,
                  allow_code: bool) -> ModelSpec:
    """A model file of 3-D bodies and flexures (geometry/spatial): its continuum, dim 3."""
    from ..spatial.model_file import spatial_spec

    parameters = _parameters(raw.get("parameters", {}), loc, overridden)
    parts, groups = spatial_spec(raw, parameters, loc, dim)
    check_groups(parts, groups, path, 3, loc)
    return ModelSpec(path=path, geometry=path, dim=3, parameters=parameters, groups=groups,
                     constants=dict(parameters), allow_code=allow_code,
                     description=str(raw.get("description", "")), **parts)


def mechanism_spec(mechanism: Mechanism, material: Material, supports, loads,
                   analysis: Analysis = Analysis(), dim: int = 2, order: int = 2,
                   mesh_size: float | None = None) -> ModelSpec:
    """A ModelSpec of a Mechanism built in Python (the model file's [[body]]/[[flexure]]
    route without a file): ``supports`` ["group", ...] held, ``loads`` {"group": (Fx, Fy)}
    total forces (N), ``analysis`` as a model file's; ``dim`` 3 extrudes the continuum.
    analyze_model(spec, model="beam" | "continuum") then analyses either model."""
    from ..mechanism.beams import beam_spec

    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    mechanism.check(set(supports))
    groups = {b.name: dim - 1 for b in mechanism.bodies} | {"solid": dim}
    for name in list(supports) + list(loads):
        if name not in groups:
            raise ValueError(f"group {name!r} is no body of the mechanism; bodies: "
                             f"{', '.join(b.name for b in mechanism.bodies)}")
    section = SectionSpec("plane_stress", mechanism.depth) if dim == 2 else SectionSpec("solid")
    forces = tuple(LoadSpec(g, "force", tuple(float(v) for v in f) + (0.0,) * (dim - 2))
                   for g, f in loads.items())
    path = Path(mechanism.source or "<mechanism>")
    return ModelSpec(path=path, geometry=path, dim=dim, material=material, section=section,
                     mesh=MeshOptions(order, mesh_size), supports=tuple(
                         SupportSpec(g, None) for g in supports), loads=forces,
                     analysis=analysis, groups=groups, beams=beam_spec(mechanism),
                     mechanism=mechanism)


def load_spec(path, overrides: dict | None = None, allow_code: bool = False,
              dim: int | None = None, bodies_only: str | None = None) -> ModelSpec:
    """Read and validate the model file ``path``; ``overrides`` {NAME: value} replace
    [parameters] entries (or 'material.E'-style keys) before validation. Files are data:
    the geometry must lie in the model file's folder and a .geo may not reach the OS
    (geo_guard.py) unless ``allow_code``. ``dim``: 3 extrudes a file of bodies and
    flexures to a solid (a geometry file has its own dimension). ``bodies_only``: the name
    of a task that needs bodies and flexures ("export"): any other file is refused before its
    geometry is read."""
    path = Path(path)
    text, raw = _read(path)
    loc = Locator(path, text)
    overridden = set((overrides or {}).keys())
    declared = parameter_names(raw)
    raw = with_si_units(_apply_overrides(raw, overrides, path), path)
    unknown = sorted(set(raw) - set(TOP_KEYS))
    if unknown:
        name = unknown[0]
        is_table = isinstance(raw[name], (dict, list))
        more = f" (and {', '.join(map(repr, unknown[1:]))})" if unknown[1:] else ""
        raise loc.error(f"unknown {'table' if is_table else 'key'} {name!r}{more}; "
                        f"allowed: {', '.join(TOP_KEYS)}",
                        name if is_table else None, None if is_table else name)
    if "body" in raw or "flexure" in raw:
        _check_declared(overridden, declared, path)
        if is_spatial(raw):
            return _spatial_spec(path, raw, loc, overridden, dim, allow_code)
        return _mechanism_spec(path, raw, loc, overridden, dim, allow_code)
    if bodies_only:
        raise ValueError(f"{path}: {bodies_only} needs a model of bodies and flexures "
                         "([[body]], [[flexure]]); a geometry file is already a drawing")
    geometry = _geometry_path(raw, loc, allow_code)
    asked, dim = dim, _dim(raw, loc)
    if asked is not None and asked != dim:
        raise loc.error(f"--dim {asked}: this model's geometry file is {dim}-D; only bodies "
                        "and flexures ([[body]], [[flexure]]) are extruded", None, "dim")
    for table in ("material", "section"):
        if table not in raw:
            raise loc.error(f"[{table}] is required: {REQUIRED[table]}", None)
    parts = {
        "material": parse_material(raw["material"], loc),
        "section": parse_section(raw["section"], dim, loc),
        "mesh": parse_mesh(raw.get("mesh", {}), loc),
        "supports": parse_supports(raw.get("supports", []), dim, loc),
        "loads": parse_loads(raw.get("loads", []), dim, loc),
        "selects": parse_selects(raw.get("select", []), loc),
        "analysis": parse_analysis(raw.get("analysis", {}), loc),
    }
    check_density(parts, loc)
    if parts["selects"] and geometry.suffix.lower() not in CAD_SUFFIXES:
        raise loc.error("[[select]] rules are for CAD files (.step/.stp/.brep); "
                        f"{geometry.name} names its own groups", "select")
    if geometry.suffix.lower() not in GEO_SUFFIXES + CAD_SUFFIXES and (
            parts["mesh"].size or parts["mesh"].refine):
        raise loc.error(f"[mesh] size and refine need a geometry to mesh; {geometry.name} is a "
                        "finished mesh (only order applies)", "mesh")
    if not parts["supports"]:
        raise loc.error("at least one [[supports]] is needed (group = \"NAME\")", None)
    parameters = _parameters(raw.get("parameters", {}), loc, overridden)
    info = inspect_geometry(geometry, parameters, parts["selects"], path.parent, allow_code)
    _check_parameters(parameters, geometry, info.constants, loc, overridden)
    if info.dim != dim:
        raise loc.error(f"dim = {dim} but {geometry.name} is {info.dim}-D", None,
                        "dim" if "dim" in raw else None)
    check_groups(parts, info.groups, geometry, dim, loc)
    if "points" in raw:
        raise loc.error("[points] are points of bodies: a file of [[body]] and [[flexure]] "
                        "names them (a geometry file's groups are observed as they are)",
                        "points")
    observable = {g for g, d in info.groups.items() if d in (dim - 1, dim)}
    outputs = parse_outputs(raw.get("outputs"), {**info.constants, **parameters}, observable,
                            dim, loc)
    beams = parse_beams(raw, {**info.constants, **parameters},
                        parts["section"].thickness if dim == 2 else None, loc)
    if beams is not None and dim != 2:
        raise loc.error("[[beam]]: the beam model is planar (dim = 2)", "beam")
    return ModelSpec(path=path, geometry=geometry, dim=dim, parameters=parameters,
                     groups=info.groups, constants=info.constants,
                     description=str(raw.get("description", "")), beams=beams,
                     allow_code=allow_code, outputs=outputs, **parts)
