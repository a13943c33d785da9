"""Supports and loads, addressed by group name, and how they become DOFs and load vectors."""
import math
from dataclasses import dataclass

import numpy as np

from .checks import InputError, is_real

_AXES = ("x", "y", "z")


def _finite_vector(value, name: str) -> tuple:
    """A tuple of 2 or 3 finite floats; a string ("12" is not (1, 2)), a mapping, a bool
    component or a number written as a string are refused."""
    try:
        if isinstance(value, (str, bytes, dict)) or not all(is_real(c) for c in value):
            raise TypeError
        v = tuple(float(c) for c in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} must be a sequence of 2 (2-D) or 3 (3-D) numbers, "
                         "e.g. (0.0, -10.0)") from None
    if not all(math.isfinite(c) for c in v):
        raise ValueError(f"{name} = {value} must be finite")
    return v


def _check_group(owner: str, group) -> None:
    if not (isinstance(group, str) and group):
        raise InputError("group", group, "a group's name (a string)", owner)


@dataclass(frozen=True)
class Fixed:
    """All displacement components of group ``group`` held at zero."""

    group: str

    def __post_init__(self):
        _check_group("Fixed", self.group)


@dataclass(frozen=True)
class Prescribed:
    """Displacement components (m) prescribed on ``group``; None leaves a component free.
    A component may be a number or a function of the coordinates, ``f(p) -> values`` with
    ``p`` a (dim, n) array of points (m)."""

    group: str
    x: object = None
    y: object = None
    z: object = None

    def __post_init__(self):
        _check_group("Prescribed", self.group)
        if self.x is None and self.y is None and self.z is None:
            raise ValueError(f"Prescribed({self.group!r}) prescribes no component; give x, y or z")
        for axis in _AXES:
            value = getattr(self, axis)
            if value is None or callable(value):
                continue
            if not (is_real(value) and math.isfinite(value)):
                raise ValueError(f"Prescribed({self.group!r}).{axis} = {value!r} must be a finite "
                                 "number (m) or a function of the coordinates")

    def components(self) -> dict:
        return {i: getattr(self, a) for i, a in enumerate(_AXES) if getattr(self, a) is not None}


@dataclass(frozen=True)
class Force:
    """Total force ``vector`` (N) spread uniformly over boundary group ``group``."""

    group: str
    vector: tuple

    def __post_init__(self):
        _check_group("Force", self.group)
        object.__setattr__(self, "vector", _finite_vector(self.vector, f"Force({self.group!r}).vector"))


@dataclass(frozen=True)
class Traction:
    """Surface traction ``vector`` (Pa) on boundary group ``group``: a constant vector or a
    function of position ``f(x) -> values``, ``x`` a (dim, n) array of points (m), values
    (dim, n) (Pa)."""

    group: str
    vector: object

    def __post_init__(self):
        _check_group("Traction", self.group)
        if not callable(self.vector):
            object.__setattr__(self, "vector",
                               _finite_vector(self.vector, f"Traction({self.group!r}).vector"))


@dataclass(frozen=True)
class Pressure:
    """Pressure ``p`` (Pa) on boundary group ``group``, positive pushing into the body (the
    sign of CalculiX's *DLOAD P): traction -p n, n the outward unit normal. ``p`` is a number
    or a function of position ``f(x) -> values``, ``x`` a (dim, n) array of points (m).
    ``follower``: in solve_nonlinear, act on the deformed surface (normal and area follow the
    deformation) rather than as a dead load on the undeformed one; linear solves ignore it."""

    group: str
    p: object
    follower: bool = True

    def __post_init__(self):
        _check_group("Pressure", self.group)
        if not callable(self.p) and not (is_real(self.p) and math.isfinite(self.p)):
            raise ValueError(f"Pressure({self.group!r}).p = {self.p!r} must be a finite number "
                             "(Pa) or a function of the coordinates")


def evaluate_on_points(function, x: np.ndarray, rows: int, name: str) -> np.ndarray:
    """Values of a load ``function`` at quadrature points ``x`` ((dim, ...), m), called on the
    flattened (dim, n) points; returns (rows, ...) (``rows`` = 0: one number per point)."""
    flat = x.reshape(x.shape[0], -1)
    shape = ((rows,) if rows else ()) + (flat.shape[1],)
    try:
        values = np.broadcast_to(np.asarray(function(flat), dtype=float), shape)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name}: the function must return an array of shape {shape} for a "
                         f"(dim, n) array of points, here n = {flat.shape[1]} ({error})") from None
    if not np.all(np.isfinite(values)):
        bad = np.flatnonzero(~np.all(np.isfinite(values.reshape(-1, flat.shape[1])), axis=0))[0]
        raise ValueError(f"{name}: the function returns a non-finite value at "
                         f"{flat[:, bad].tolist()} m")
    return values.reshape(shape[:-1] + x.shape[1:])


@dataclass(frozen=True)
class PointForce:
    """Force ``vector`` (N) at the mesh vertex nearest ``point`` (m)."""

    point: tuple
    vector: tuple

    def __post_init__(self):
        object.__setattr__(self, "point", _finite_vector(self.point, "PointForce.point"))
        object.__setattr__(self, "vector", _finite_vector(self.vector, "PointForce.vector"))


@dataclass(frozen=True)
class BodyForce:
    """Body force density ``vector`` (N/m^3) on the whole body or on subdomain ``group``."""

    vector: tuple
    group: str | None = None

    def __post_init__(self):
        object.__setattr__(self, "vector", _finite_vector(self.vector, "BodyForce.vector"))


@dataclass(frozen=True)
class Gravity:
    """Self-weight: body force rho * ``acceleration`` (m/s^2) on the whole body or on
    subdomain ``group``."""

    acceleration: tuple = (0.0, -9.81)
    group: str | None = None

    def __post_init__(self):
        object.__setattr__(self, "acceleration", _finite_vector(self.acceleration, "Gravity.acceleration"))


def _check_dim(vector, dim, what):
    if len(vector) != dim:
        raise ValueError(f"{what} has {len(vector)} components; the model is {dim}-D: give {dim}")


def facet_basis(model, group):
    import skfem  # the continuum's assembly: imported where a continuum is loaded

    facets = model.mesh.facets(group)
    if len(facets) == 0:
        raise ValueError(f"group {group!r} has no facets: a load on it would act on no nodes")
    return skfem.FacetBasis(model.cell_mesh, model.basis.elem, facets=facets,
                            intorder=2 * model.order)


def component_indices(model) -> list[np.ndarray]:
    """DOF indices of each displacement component (x, y[, z])."""
    return model.basis.split_indices()


def group_dofs(model, group: str) -> dict[int, np.ndarray]:
    """DOFs of a boundary group or subdomain per component: {0: x DOFs, 1: y DOFs, ...}."""
    mesh = model.mesh
    if group in mesh.boundaries:
        dofs = model.basis.get_dofs(facets=mesh.facets(group))
    elif group not in mesh.subdomains:
        raise ValueError(f"no group {group!r}; boundary groups: {sorted(mesh.boundaries)}, "
                         f"subdomains: {sorted(mesh.subdomains)}")
    else:
        dofs = model.basis.get_dofs(elements=mesh.elements(group))
    return {i: dofs.all(f"u^{i + 1}") for i in range(model.dim)}


def constrained_dofs(model, supports) -> tuple[np.ndarray, np.ndarray, dict]:
    """(DOF indices, prescribed values (m), {group: its DOFs}) of the supports; where supports
    share a DOF, the first listed wins."""
    taken = np.zeros(model.n_dofs, dtype=bool)
    values = np.zeros(model.n_dofs)
    owned = {}
    for support in supports:
        comps = {i: 0.0 for i in range(model.dim)} if isinstance(support, Fixed) else support.components()
        if max(comps) >= model.dim:
            raise ValueError(f"{support} prescribes z in a 2-D model")
        dofs = group_dofs(model, support.group)
        mine = []
        for i, value in comps.items():
            if len(dofs[i]) == 0:
                raise ValueError(f"support on {support.group!r} acts on no nodes")
            new = dofs[i][~taken[dofs[i]]]
            if callable(value):
                values[new] = _evaluate_prescribed(value, model.basis.doflocs[:, new],
                                                   f"Prescribed({support.group!r}).{_AXES[i]}")
            else:
                values[new] = value
            taken[new] = True
            mine.append(new)
        owned[support.group] = np.sort(np.concatenate(mine))
    D = np.flatnonzero(taken)
    return D, values[D], owned


def _evaluate_prescribed(function, points, name: str) -> np.ndarray:
    """Values (m) of a function-valued Prescribed component at ``points`` ((dim, n), m)."""
    n = points.shape[1]
    try:
        values = np.broadcast_to(np.asarray(function(points), dtype=float), (n,))
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name}: the function must return one number per point for a "
                         f"(dim, n) array of points, here n = {n} ({error})") from None
    if not np.all(np.isfinite(values)):
        bad = points[:, np.flatnonzero(~np.isfinite(values))[0]]
        raise ValueError(f"{name}: the function returns a non-finite value at {bad.tolist()} m")
    return values


def nearest_vertex(model, point, what: str = "PointForce.point") -> int:
    """Index of the mesh vertex nearest ``point`` (m); a point farther from it than the
    largest element edge there lies off the body and raises ValueError."""
    mesh = model.mesh.mesh
    if len(point) != model.dim:
        raise ValueError(f"{what} = {point} has {len(point)} coordinates; the model is "
                         f"{model.dim}-D: give {model.dim}")
    x = np.reshape(point, (-1, 1))
    distance = np.sqrt(np.sum((mesh.p - x) ** 2, axis=0))
    node = int(np.argmin(distance))
    around = mesh.t[:, np.any(mesh.t == node, axis=0)]
    reach = max(np.linalg.norm(mesh.p[:, around[i]] - mesh.p[:, [node]], axis=0).max()
                for i in range(around.shape[0]))
    if distance[node] > reach:
        raise ValueError(f"{what} = {tuple(point)} m is {distance[node]:.3g} m from the nearest "
                         f"mesh vertex {mesh.p[:, node].tolist()}: it is not on the body (which "
                         f"spans {mesh.p.min(axis=1).tolist()} to {mesh.p.max(axis=1).tolist()} m)")
    return node


def _traction_form(model, load):
    """Traction (Pa) of a Traction or Pressure at the quadrature points of a FacetBasis, as a
    function of the form's ``w``."""
    name = f"{type(load).__name__}({load.group!r})"
    if isinstance(load, Pressure):
        if callable(load.p):
            return lambda w: -evaluate_on_points(load.p, w.x, 0, f"{name}.p") * w.n
        return lambda w: -load.p * w.n
    if callable(load.vector):
        return lambda w: evaluate_on_points(load.vector, w.x, model.dim, f"{name}.vector")
    _check_dim(load.vector, model.dim, "Traction")
    tr = np.array(load.vector).reshape(-1, 1, 1)
    return lambda w: tr + 0 * w.x


def _surface_load(model, load) -> np.ndarray:
    """Nodal forces (N) of a Force, Traction or Pressure on the undeformed surface."""
    import skfem
    from skfem.helpers import dot

    fb = facet_basis(model, load.group)
    t = model.thickness
    if isinstance(load, Force):
        _check_dim(load.vector, model.dim, "Force")
        measure = skfem.Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(fb)
        tr = (np.array(load.vector) / (measure * t)).reshape(-1, 1, 1)
        traction = lambda w: tr + 0 * w.x  # noqa: E731
    else:
        traction = _traction_form(model, load)
    return t * skfem.LinearForm(lambda v, w: dot(traction(w), v)).assemble(fb)


def load_vector(model, loads) -> np.ndarray:
    """Assembled nodal force vector (N) of ``loads``."""
    import skfem
    from skfem.helpers import dot

    f = np.zeros(model.n_dofs)
    t = model.thickness
    for load in loads:
        if isinstance(load, (Force, Traction, Pressure)):
            f += _surface_load(model, load)
        elif isinstance(load, PointForce):
            _check_dim(load.vector, model.dim, "PointForce.vector")
            node = nearest_vertex(model, load.point)
            for i, dofs in enumerate(model.basis.nodal_dofs):
                f[dofs[node]] += load.vector[i]
        elif isinstance(load, (BodyForce, Gravity)):
            if isinstance(load, Gravity):
                vector = model.material.density * np.array(load.acceleration)
            else:
                vector = np.array(load.vector)
            _check_dim(vector, model.dim, type(load).__name__)
            b = vector.reshape(-1, 1, 1)
            basis = model.basis
            if load.group is not None:
                basis = model.basis.with_elements(model.mesh.elements(load.group))
            f += t * skfem.LinearForm(lambda v, w: dot(b + 0 * w.x, v)).assemble(basis)
        else:
            raise ValueError(f"unknown load {load!r}")
    return f
