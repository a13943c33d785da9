"""The eight-bar flexure suspension (eight-bar thesis, Chapter 5): every pivot of the rigid
eight-bar (:mod:`flexfem.geometry.eightbar.rigid`) replaced by a beam flexure.

Flexure placement (our choice; the thesis only says "beam flexure at the joint position", base
flexures "relatively thicker and shorter", the others "long thin"): each flexure is centred on
its joint. The base flexures O, C lie along the crank / rocker, anchored to the ground by a
square pad whose far face is "fixed"; the flexures A, B lie along the coupler bar (horizontal
in the drawn pose) and P along the coupler stem (vertical, in line with the end-effector's
leg), so the crank and rocker reach the coupler through a hub just beyond the flexure. See
:mod:`flexfem.geometry.flexure_linkage` for the construction and docs/eightbar.md for the
dimensions.

Default dimensions (m), chosen for aluminium 6061-T6 so that pure bending at the rigid-body
joint rotations over the 33.1 mm travel (base 0.10 rad, A/B 0.18 rad, P 0.08 rad at the ends)
keeps sigma = E w theta / (2 L) at or below yield / 2.4: base flexures 12 x 0.4, others
20 x 0.3, links 5 wide, 6 thick.
"""
import math
from dataclasses import dataclass, field, fields, replace

import numpy as np

from ...data import load_toml
from ...fem import checks
from ...fem.materials import material as material_named
from .. import bounds
from ..flexure_drawing import mesh_layout
from ..flexure_linkage import (
    FlexureLayout,
    flexure_layout,
    polygon_distance,
)
from ..flexure_roots import check_root_fillet_radius
from ..flexure_solid import mesh_layout_solid
from ..linkage import trace_from_reference
from ..linkage_clearance import segment_distance
from .rigid import (
    BASE_JOINTS,
    EightBarParams,
    build_eightbar,
    eightbar_joints,
    eightbar_points,
)

THESIS_TRAVEL = load_toml("eightbar_thesis.toml")["design_targets"]["travel_mm"] * 1e-3  # m, Ch. 5
# m, our choice (docs/eightbar.md, "Flexure suspension (FEM)"): see the module docstring
DEFAULT_ROOT_FILLET_RADIUS = 0.3e-3
# the 3-D mesh's defaults (docs/eightbar.md, "The suspension in 3-D"): element length / size
# across a flexure, element layers through the thickness
SOLID_ASPECT, SOLID_LAYERS = 4.0, 2


def _thesis_rigid() -> EightBarParams:
    return replace(EightBarParams(), travel=THESIS_TRAVEL)


_LENGTHS = ("link_width", "base_flexure_length", "base_flexure_width", "flexure_length",
            "flexure_width", "thickness")


@dataclass(frozen=True)
class EightBarFlexureParams:
    """The flexure suspension. rigid : the rigid-body linkage (its ``travel`` is the stroke
    checked for clearance and traced); link_width W, base_flexure_length / _width (joints
    O, C to the ground), flexure_length / _width (joints A, B, P), thickness (out of plane),
    all m; material : a name in the fem material library."""

    rigid: EightBarParams = field(default_factory=_thesis_rigid)
    link_width: float = 5e-3
    base_flexure_length: float = 12e-3
    base_flexure_width: float = 0.4e-3
    flexure_length: float = 20e-3
    flexure_width: float = 0.3e-3
    thickness: float = 6e-3
    material: str = "aluminium_6061_t6"
    root_fillet_radius: float = DEFAULT_ROOT_FILLET_RADIUS

    def __post_init__(self):
        if not isinstance(self.rigid, EightBarParams):
            raise ValueError(f"rigid = {self.rigid!r} must be an EightBarParams")
        bounds.span("EightBarFlexureParams", bounds.lengths("EightBarFlexureParams", self, _LENGTHS)
                    | {"rigid.ground_spacing": self.rigid.ground_spacing})
        material_named(self.material)  # raises ValueError naming the known materials
        for name in ("base_flexure_width", "flexure_width"):
            if not getattr(self, name) < self.link_width:
                raise ValueError(f"{name} = {getattr(self, name)} m, must be < link_width = "
                                 f"{self.link_width} m (a flexure wider than the links it joins)")
        for name in ("base_flexure_length", "flexure_length"):
            if not getattr(self, name) > getattr(self, name.replace("length", "width")):
                raise ValueError(f"{name} = {getattr(self, name)} m, must be > its width (a beam "
                                 "flexure is long and thin)")
        layout = eightbar_layout(self)  # raises if a flexure is too long for its link segment
        object.__setattr__(self, "root_fillet_radius", check_root_fillet_radius(
            self.root_fillet_radius, layout.parts, self.link_width))
        touching = flexure_contacts(self)
        if touching:
            first = touching[0]
            raise ValueError(
                f"flexure_{first['flexure']} touches link {first['link']!r} at displacement "
                f"{first['displacement_m'] * 1e3:.3g} mm of the travel (near "
                f"({first['location'][0]:.4g}, {first['location'][1]:.4g}) m); shorten the "
                f"flexures or reduce the travel ({len(touching)} contacts in all)")

    def flexure_size(self, joint: str) -> tuple:
        """(length, width) in m of the flexure at ``joint``."""
        if joint in BASE_JOINTS:
            return self.base_flexure_length, self.base_flexure_width
        return self.flexure_length, self.flexure_width

    def scaled(self, factor: float, material: str | None = None) -> "EightBarFlexureParams":
        """Every length times ``factor`` (e.g. 1e-3 for the micrometre version), and the
        material swapped if given."""
        checks.positive("factor", factor)
        rigid = replace(self.rigid, **{f.name: getattr(self.rigid, f.name) * factor
                                       for f in fields(self.rigid)})
        return replace(self, rigid=rigid, material=material or self.material,
                       root_fillet_radius=self.root_fillet_radius * factor,
                       **{name: getattr(self, name) * factor for name in _LENGTHS})


def _hosts() -> dict:
    hosts = {}
    for s in ("L", "R"):
        hosts.update({f"O_{s}": f"crank_{s}", f"C_{s}": f"rocker_{s}", f"A_{s}": f"coupler_{s}",
                      f"B_{s}": f"coupler_{s}", f"P_{s}": f"coupler_{s}"})
    return hosts


HOSTS = _hosts()
JOINT_NAMES = tuple(HOSTS)


def eightbar_layout(params: EightBarFlexureParams) -> FlexureLayout:
    """The flexure part's rectangles in the drawn (middle) pose, m. Boundary edges: "fixed"
    (the anchors' far faces) and "end_effector" (the bottom face of the end-effector bar)."""
    geo = eightbar_joints(params.rigid, 0.0)
    pts = eightbar_points(params.rigid)
    W = params.link_width
    (xl, ye), (xr, _) = pts["E_L"], pts["E_R"]
    bottom = ((xl - W / 2, ye - W / 2), (xr + W / 2, ye - W / 2))
    sizes = {j["name"]: params.flexure_size(j["name"]) for j in geo["joints"]}
    return flexure_layout(geo["polylines"], geo["joints"], HOSTS, sizes, W,
                          edges={"end_effector": bottom})


def end_effector_point(params: EightBarFlexureParams) -> np.ndarray:
    """Centroid (m) of the "end_effector" face (the bottom face of the end-effector bar)."""
    (a, b) = eightbar_layout(params).edges["end_effector"]
    return (np.asarray(a) + np.asarray(b)) / 2


def _transforms(linkage, q) -> dict:
    return {link.name: linkage.link_transform(q, link.name) for link in linkage.links}


def flexure_contacts(params: EightBarFlexureParams, n: int = 5) -> list:
    """Flexures that touch a link they are not attached to, at ``n`` poses over the travel.

    Each flexure is split at its centre into the half fixed to its host and the half fixed to
    the other link; each half moves rigidly with its link (the bend is a kink at the joint).
    Returns [{"flexure", "link", "displacement_m", "location" (x, y) m}], empty if clear."""
    layout = eightbar_layout(params)
    linkage = build_eightbar(params.rigid)
    x0 = eightbar_points(params.rigid)["E"][0]
    half = params.rigid.travel / 2
    trace = trace_from_reference(linkage, x0 - half, x0 + half, n)
    halves = []
    for fj in layout.joints:
        a, b = fj.ends()
        part = layout.flexure(fj.name)
        halves.append((fj.name, fj.host, replace(part, p0=a, p1=fj.position)))
        halves.append((fj.name, fj.other, replace(part, p0=fj.position, p1=b)))
    solids = [(p.link, p) for p in layout.parts if p.kind != "flexure"]
    contacts, seen = [], set()
    for q, s in zip(trace.poses, trace.inputs[:, 0] - x0):
        T = _transforms(linkage, q)
        placed = [(link, p, p.corners(T[link])) for link, p in solids]
        placed += [(link, replace(p, name=f"flexure_{name}"), p.corners(T[link]))
                   for name, link, p in halves]
        for name, owner, part in halves:
            poly = part.corners(T[owner])
            for link, other, corners in placed:
                if link == owner or other.name == f"flexure_{name}":
                    continue
                centre_gap = _segment_gap(poly, corners) - (part.width + other.width) / 2
                if centre_gap > 0:
                    continue
                d, where = polygon_distance(poly, corners)
                if d <= 0 and (name, link) not in seen:
                    seen.add((name, link))
                    contacts.append({"flexure": name, "link": link, "displacement_m": float(s),
                                     "location": tuple(float(c) for c in where)})
    return contacts


def _segment_gap(P, Q) -> float:
    """Distance (m) between the centre-lines of two rectangles given by their corners."""
    return segment_distance((P[0] + P[3]) / 2, (P[1] + P[2]) / 2, (Q[0] + Q[3]) / 2, (Q[1] + Q[2]) / 2)


def check_mesh_options(n_across, size_factor) -> None:
    checks.count("n_across", n_across, least=3)
    checks.in_range("size_factor", size_factor, (0.1, 10))


def mesh_eightbar_flexure(params: EightBarFlexureParams, n_across: int = 3,
                          size_factor: float = 1.0, aspect: float = 4.0, dim: int = 2,
                          layers: int | None = None):
    """Mesh the flexure suspension: triangles (use order=2), ``max(n_across, 3 / size_factor)``
    elements across every flexure, element length ``aspect * size_factor`` times the width
    across it (at most 20), links graded to W / 2 * size_factor. ``dim=3``: the solid of
    thickness t (tetrahedra, mid-plane z = 0), sized by :func:`solid_mesh_options` (``aspect``
    unused). Returns (FEMesh, sizes dict {"flexure_size", "coarse_size"(, "layer_size")}, m).
    Subdomains:
    each link, "flexure_<joint>", "links", "flexures", "anchors", "body"; boundaries: "fixed",
    "end_effector"."""
    check_mesh_options(n_across, size_factor)
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    if dim == 3:
        options = solid_mesh_options(params, n_across, size_factor, layers)
        return mesh_layout_solid(eightbar_layout(params), params.thickness, name="eightbar_solid",
                                 root_fillet_radius=params.root_fillet_radius, **options)
    n = max(int(n_across), int(math.ceil(3 / size_factor)))
    return mesh_layout(eightbar_layout(params), n_across=n,
                       aspect=min(20.0, max(0.5, aspect * size_factor)),
                       coarse=params.link_width / 2 * size_factor, name="eightbar_flexure",
                       root_fillet_radius=params.root_fillet_radius)


def solid_mesh_options(params: EightBarFlexureParams, n_across: int = 3,
                       size_factor: float = 1.0, layers: int | None = None) -> dict:
    """In-plane sizes and layers of the 3-D mesh: n_across elements across a flexure, element
    length SOLID_ASPECT * size_factor times the size across (at most 20), links graded to
    W * size_factor (twice the 2-D mesh's: the solid's DOFs grow as (2 layers + 1) times the
    plane's), ``layers`` (default max(2, SOLID_LAYERS / size_factor)) through t."""
    check_mesh_options(n_across, size_factor)
    if layers is None:
        layers = max(2, int(round(SOLID_LAYERS / size_factor)))
    return {"n_across": int(n_across), "layers": layers,
            "aspect": min(20.0, max(0.5, SOLID_ASPECT * size_factor)),
            "coarse": params.link_width * size_factor}


def joint_rotation_rates(params: EightBarFlexureParams, step: float | None = None) -> dict:
    """d(phi_j)/dx (rad/m) at the drawn pose: the relative rotation of each joint's two links
    per unit end-effector displacement, by central differences on the rigid linkage."""
    linkage = build_eightbar(params.rigid)
    x0 = eightbar_points(params.rigid)["E"][0]
    h = step or 1e-4 * params.rigid.ground_spacing
    tr = trace_from_reference(linkage, x0 - h, x0 + h, 3)
    theta = {name: tr.poses[:, 3 * i + 2] for i, name in enumerate(linkage.moving_links)}
    theta["ground"] = np.zeros(3)
    rates = {}
    for j in linkage.joints:
        a, b = j.links
        phi = theta[a] - theta[b]
        rates[j.point] = float((phi[2] - phi[0]) / (2 * h))
    return rates


def joint_rotations(params: EightBarFlexureParams, displacement: float) -> dict:
    """Relative rotation (rad) of each joint at end-effector displacement ``displacement`` (m)."""
    linkage = build_eightbar(params.rigid)
    x0 = eightbar_points(params.rigid)["E"][0]
    tr = trace_from_reference(linkage, x0, x0 + displacement, 3)
    theta = {name: tr.poses[-1, 3 * i + 2] for i, name in enumerate(linkage.moving_links)}
    theta["ground"] = 0.0
    return {j.point: float(theta[j.links[0]] - theta[j.links[1]]) for j in linkage.joints}


def flexure_rotational_stiffness(params: EightBarFlexureParams, joint: str) -> float:
    """E I / L (N m/rad) of the flexure at ``joint``, I = t w^3 / 12: a beam whose ends turn
    about its middle carries a pure moment M = E I phi / L (no shear)."""
    L, w = params.flexure_size(joint)
    E = material_named(params.material).E
    return E * params.thickness * w ** 3 / 12 / L


def prbm_stiffness(params: EightBarFlexureParams) -> dict:
    """Pseudo-rigid-body stiffness along the motion, k_x = sum_j (E I / L)_j (dphi_j/dx)^2
    (N/m), with each joint's share. Neglects the links' compliance and the flexures' axial and
    transverse compliance."""
    rates = joint_rotation_rates(params)
    share = {j: flexure_rotational_stiffness(params, j) * r ** 2 for j, r in rates.items()}
    return {"k_x": float(sum(share.values())), "joints": share, "rates": rates}


def prbm_peak_stress(params: EightBarFlexureParams, displacement: float) -> dict:
    """Bending stress sigma = E w phi / (2 L) (Pa) of each flexure at end-effector displacement
    ``displacement`` (m), from the rigid-body joint rotations phi."""
    E = material_named(params.material).E
    phi = joint_rotations(params, displacement)
    return {j: E * params.flexure_size(j)[1] * abs(p) / (2 * params.flexure_size(j)[0])
            for j, p in phi.items()}


def prbm_flexure_loads(params: EightBarFlexureParams, displacement: float) -> dict:
    """Loads in each flexure of the pseudo-rigid-body model at end-effector displacement
    ``displacement`` (m) from the middle, linear (small rotations, drawn pose): rigid links,
    pivots at the flexure centres with springs k_j = E I / L, the end-effector pushed along x.

    The equilibrium of the seven moving links (3 equations each) gives the 10 joint forces and
    the drive force (21 unknowns). A flexure carries its spring moment M_j = k_j phi_j plus the
    joint force's component across it, the shear V, whose moment grows to V L / 2 at each end;
    the component along it, N, is axial. Returns {joint: {"moment_nm", "shear_n", "axial_n",
    "end_moment_nm" = |M| + |V| L / 2, "bending_stress_pa" = 6 |M| / (t w^2),
    "root_stress_pa" = 6 end_moment / (t w^2) + |N| / (t w)}} and "drive_force_n" (N)."""
    linkage = build_eightbar(params.rigid)
    geo = eightbar_joints(params.rigid, 0.0)
    layout = eightbar_layout(params)
    axis = {fj.name: np.asarray(fj.direction) for fj in layout.joints}
    position = {j["name"]: np.asarray(j["position"]) for j in geo["joints"]}
    phi = {j: r * displacement for j, r in joint_rotation_rates(params).items()}
    moving = list(linkage.moving_links)
    row = {name: 3 * i for i, name in enumerate(moving)}
    joints = list(linkage.joints)
    n = 2 * len(joints) + 1
    A, b = np.zeros((3 * len(moving), n)), np.zeros(3 * len(moving))
    for k, j in enumerate(joints):
        p = position[j.point]
        M = flexure_rotational_stiffness(params, j.point) * phi[j.point]
        for link, sign in zip(j.links, (1.0, -1.0)):  # force f on links[0], -f on links[1]
            if link not in row:
                continue
            i = row[link]
            A[i, 2 * k], A[i + 1, 2 * k + 1] = sign, sign
            A[i + 2, 2 * k], A[i + 2, 2 * k + 1] = -sign * p[1], sign * p[0]
            b[i + 2] -= -sign * M  # spring moment -k phi on links[0], +k phi on links[1]
    e = end_effector_point(params)
    ee = next(name for name in moving if "end_effector" in name)
    A[row[ee], -1], A[row[ee] + 2, -1] = 1.0, -e[1]  # drive force (F, 0) at the face
    sol = np.linalg.solve(A, b)
    t, out = params.thickness, {}
    for k, j in enumerate(joints):
        f = sol[2 * k: 2 * k + 2]
        d = axis[j.point]
        L, w = params.flexure_size(j.point)
        M = flexure_rotational_stiffness(params, j.point) * phi[j.point]
        V, N = float(f @ np.array([-d[1], d[0]])), float(f @ d)
        end = abs(M) + abs(V) * L / 2
        out[j.point] = {"moment_nm": float(M), "shear_n": V, "axial_n": N, "end_moment_nm": end,
                        "bending_stress_pa": 6 * abs(M) / (t * w ** 2),
                        "root_stress_pa": 6 * end / (t * w ** 2) + abs(N) / (t * w)}
    return {"joints": out, "drive_force_n": float(sol[-1])}
