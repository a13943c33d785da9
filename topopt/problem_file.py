"""A problem file (TOML) to a :class:`Problem`: data only, every key checked, a bad one a
ValueError that names it. The tables are described in docs/topopt.md."""
from pathlib import Path
import tomllib

from .grid import Grid
from .interpolation import Interpolation
from .large_displacement import Nonlinear
from .problem import (Constraint, Load, Optimizer, Passive, Problem, Response, Spring,
                      Support)
from .projection import Projection
from .regions import parse_region
from .robust import Robust, radius_for

TABLES = {
    "domain": {"nelx", "nely", "size", "thickness", "symmetry"},
    "material": {"E", "nu", "Emin", "rho"},
    "interpolation": {"kind", "penal"},
    "filter": {"kind", "radius"},
    "objective": {"kind", "spring", "sense", "case", "weights", "pnorm", "relaxation", "modes"},
    "optimizer": {"kind", "move", "max_iterations", "tolerance", "initial"},
    "projection": {"beta", "eta", "beta_max", "every"},
    "shape": {"rho", "yield_strength", "min_member"},
    "nonlinear": {"steps", "max_iterations", "tolerance"},
    "robust": {"min_hinge", "eta"},
}
LISTS = {
    "support": {"where", "fix"},
    "load": {"where", "force", "case"},
    "spring": {"name", "where", "dof", "stiffness"},
    "constraint": {"kind", "spring", "max", "min", "case", "weights", "pnorm", "relaxation",
                   "modes"},
    "passive": {"where", "value"},
}


def _table(data: dict, name: str, allowed: set, required=()) -> dict:
    if not isinstance(data, dict):
        raise ValueError(f"{name}: must be a table, not {data!r}")
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise ValueError(f"{name}: unknown key {unknown[0]!r} (known: {sorted(allowed)})")
    for key in required:
        if key not in data:
            raise ValueError(f"{name}.{key}: missing")
    return data


def _number(value, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{key} = {value!r}: must be a number")
    return float(value)


def _rows(data: dict, name: str) -> list:
    rows = data.get(name, [])
    if not isinstance(rows, list):
        raise ValueError(f"{name}: give [[{name}]] tables")
    return [_table(r, f"{name}[{k}]", LISTS[name]) for k, r in enumerate(rows)]


def _grid(d: dict) -> Grid:
    for key in ("nelx", "nely"):
        if not isinstance(d.get(key), int) or isinstance(d.get(key), bool):
            raise ValueError(f"domain.{key} = {d.get(key)!r}: must be an integer >= 1")
    size = d.get("size", [d["nelx"], d["nely"]])
    if not isinstance(size, list) or len(size) != 2:
        raise ValueError(f"domain.size = {size!r}: give [lx, ly] (m)")
    return Grid(d["nelx"], d["nely"], _number(size[0], "domain.size"),
                _number(size[1], "domain.size"))


def _support(k, r) -> Support:
    fix = r.get("fix", ["x", "y"])
    if not isinstance(fix, list) or not fix or not set(fix) <= {"x", "y"}:
        raise ValueError(f"support[{k}].fix = {fix!r}: give a list of 'x', 'y'")
    return Support(parse_region(r.get("where"), f"support[{k}].where"), tuple(fix))


def _integer(value, key: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ValueError(f"{key} = {value!r}: must be an integer >= 1")
    return value


def _load(k, r) -> Load:
    force = r.get("force")
    if not isinstance(force, list) or len(force) != 2:
        raise ValueError(f"load[{k}].force = {force!r}: give [fx, fy] (N)")
    return Load(parse_region(r.get("where"), f"load[{k}].where"),
                tuple(_number(f, f"load[{k}].force") for f in force),
                _integer(r.get("case", 1), f"load[{k}].case"))


# the keys of [objective] and [[constraint]] that only some kinds take
KIND_KEYS = {"spring": ("displacement",), "case": ("displacement",),
             "weights": ("compliance",), "pnorm": ("stress",), "relaxation": ("stress",),
             "modes": ("frequency",)}


def _response(r: dict, name: str) -> Response:
    """The Response of an [objective] or [[constraint]] table named ``name``."""
    kind = r.get("kind")
    for key, kinds in KIND_KEYS.items():
        if key in r and kind not in kinds:
            raise ValueError(f"{name}.{key}: applies to kind {' or '.join(map(repr, kinds))}, "
                             f"not {kind!r}")
    weights = r.get("weights", [])
    if not isinstance(weights, list):
        raise ValueError(f"{name}.weights = {weights!r}: give a list, one per load case")
    return Response(kind, r.get("spring", ""), _integer(r.get("case", 1), f"{name}.case"),
                    tuple(_number(w, f"{name}.weights") for w in weights),
                    _number(r.get("pnorm", 8.0), f"{name}.pnorm"),
                    _number(r.get("relaxation", 0.5), f"{name}.relaxation"),
                    r.get("modes", 1))


def _spring(k, r) -> Spring:
    return Spring(str(r.get("name", f"spring{k}")),
                  parse_region(r.get("where"), f"spring[{k}].where"), r.get("dof"),
                  _number(r.get("stiffness"), f"spring[{k}].stiffness"))


def _constraint(k, r) -> Constraint:
    bounds = {b: _number(r[b], f"constraint[{k}].{b}") for b in ("max", "min") if b in r}
    return Constraint(_response(r, f"constraint[{k}]"), bounds.get("max"), bounds.get("min"))


def _passive(k, r) -> Passive:
    if r.get("value") not in ("solid", "void"):
        raise ValueError(f"passive[{k}].value = {r.get('value')!r}: choose 'solid' or 'void'")
    return Passive(parse_region(r.get("where"), f"passive[{k}].where"), r["value"])


def _optimizer(o: dict) -> Optimizer:
    iters = o.get("max_iterations", 200)
    if not isinstance(iters, int) or isinstance(iters, bool):
        raise ValueError(f"optimizer.max_iterations = {iters!r}: must be an integer >= 0")
    return Optimizer(o.get("kind", "oc"), _number(o.get("move", 0.2), "optimizer.move"), iters,
                     _number(o.get("tolerance", 0.01), "optimizer.tolerance"))


def _projection(data: dict, t: dict) -> Projection | None:
    if "projection" not in data:
        return None
    d = t["projection"]
    every = d.get("every", 50)
    if isinstance(every, bool) or not isinstance(every, int):
        raise ValueError(f"projection.every = {every!r}: must be an integer >= 1")
    return Projection(*(_number(d.get(k, v), f"projection.{k}")
                        for k, v in (("beta", 1.0), ("eta", 0.5), ("beta_max", 32.0))), every)


def _nonlinear(data: dict, t: dict) -> Nonlinear | None:
    if "nonlinear" not in data:
        return None
    d, default = t["nonlinear"], Nonlinear()
    return Nonlinear(d.get("steps", default.steps),
                     d.get("max_iterations", default.max_iterations),
                     _number(d.get("tolerance", default.tolerance), "nonlinear.tolerance"))


def _robust(data: dict, t: dict) -> Robust | None:
    """[robust]: ``min_hinge`` (m, the blueprint's minimum solid and void size) and ``eta``
    (the dilated threshold, default 0.25)."""
    if "robust" not in data:
        return None
    d = t["robust"]
    if "min_hinge" in d and "radius" in t["filter"]:
        raise ValueError("filter.radius: give robust.min_hinge or filter.radius, not both "
                         "(the radius is derived from min_hinge)")
    return Robust(_number(d.get("eta", 0.25), "robust.eta"),
                  _number(d.get("min_hinge", 0.0), "robust.min_hinge"))


def _radius(f: dict, robust: Robust | None, grid: Grid) -> float:
    """The filter's radius (elements): derived from robust.min_hinge where given."""
    if robust is not None and robust.min_size > 0:
        return radius_for(robust.min_size, grid.dx, robust.eta)
    return _number(f.get("radius", 1.5), "filter.radius")


def problem_from_dict(data: dict) -> Problem:
    """The Problem a parsed problem file describes."""
    unknown = sorted(set(data) - set(TABLES) - set(LISTS))
    if unknown:
        raise ValueError(f"unknown table {unknown[0]!r} (known: {sorted({*TABLES, *LISTS})})")
    t = {name: _table(data.get(name, {}), name, keys) for name, keys in TABLES.items()}
    _table(t["domain"], "domain", TABLES["domain"], ("nelx", "nely"))
    _table(t["objective"], "objective", TABLES["objective"], ("kind",))
    m, i, f, o = t["material"], t["interpolation"], t["filter"], t["optimizer"]
    E = _number(m.get("E", 1.0), "material.E")
    symmetry = t["domain"].get("symmetry", [])
    if not isinstance(symmetry, list):
        raise ValueError(f"domain.symmetry = {symmetry!r}: give a list of 'x', 'y'")
    grid, robust = _grid(t["domain"]), _robust(data, t)
    return Problem(
        grid=grid,
        objective=_response(t["objective"], "objective"),
        sense=t["objective"].get("sense", "max" if t["objective"].get("kind") == "frequency"
                                 else "min"),
        nu=_number(m.get("nu", 0.3), "material.nu"),
        thickness=_number(t["domain"].get("thickness", 1.0), "domain.thickness"),
        mass_density=_number(m.get("rho", 1.0), "material.rho"),
        interpolation=Interpolation(i.get("kind", "simp"),
                                    _number(i.get("penal", 3.0), "interpolation.penal"), E,
                                    _number(m.get("Emin", 1e-9 * E), "material.Emin")),
        filter_kind=f.get("kind", "sensitivity"),
        radius=_radius(f, robust, grid),
        supports=tuple(_support(k, r) for k, r in enumerate(_rows(data, "support"))),
        loads=tuple(_load(k, r) for k, r in enumerate(_rows(data, "load"))),
        springs=tuple(_spring(k, r) for k, r in enumerate(_rows(data, "spring"))),
        constraints=tuple(_constraint(k, r) for k, r in enumerate(_rows(data, "constraint"))),
        passive=tuple(_passive(k, r) for k, r in enumerate(_rows(data, "passive"))),
        symmetry=tuple(symmetry),
        optimizer=_optimizer(o),
        initial=_number(o["initial"], "optimizer.initial") if "initial" in o else None,
        projection=_projection(data, t),
        nonlinear=_nonlinear(data, t),
        robust=robust)


def read_problem_file(path) -> dict:
    """The parsed TOML of a problem file."""
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path.name}: not valid TOML: {error}") from None


def load_problem(path) -> Problem:
    """Read and check a problem file (its errors name it)."""
    try:
        return problem_from_dict(read_problem_file(path))
    except ValueError as error:
        if not str(error).startswith(Path(path).name):
            error.args = (f"{Path(path).name}: {error}",)
        raise
