"""Spatial beam models: sections, nodes and elements, rigid links, supports and loads.

    model = Beam3DModel(nodes, elements, Section.rect(2e-3, 10e-3), steel)

DOFs per node: (u_x, u_y, u_z) displacement (m) and (r_x, r_y, r_z) rotation (rad, about the
global axes; at large rotations the nodes carry rotation matrices, see nonlinear.py).
Each element's local axes: x along it (node 1 to node 2), z the component of its
``orientation`` vector normal to x (default global z; global x for an element along z),
y = z cross x. A planar model in the x-y plane then has local z = global z and bends in
plane about local z (Iz), as the planar model (fem/beam) does with its I.
"""
from dataclasses import dataclass
import math

import numpy as np

from ..groups import BeamGroup
from ..model import RigidLink, link_masters
from ...checks import positive
from ...materials import Material

def rect_torsion_constant(a, b):
    """Saint-Venant torsion constant J (m^4) of a x b rectangles (arrays broadcast): the
    series solution for rectangular bars (Timoshenko & Goodier, Theory of Elasticity, 3rd
    ed., 1970), 20 odd terms."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    a, b = np.maximum(a, b), np.minimum(a, b)
    n = np.arange(1, 40, 2).reshape((-1,) + (1,) * a.ndim)
    series = np.sum(np.tanh(n * np.pi * a / (2 * b)) / n**5, axis=0)
    J = a * b**3 / 3.0 * (1.0 - 192.0 / np.pi**5 * (b / a) * series)
    return float(J) if J.ndim == 0 else J


def rect_torsion_shear(a, b):
    """Largest shear stress per unit torque (1/m^3) of a x b rectangles under Saint-Venant
    torsion, at the middle of the long sides: tau_max = G theta' t (1 - 8 / pi^2 sum_{n odd}
    1 / (n^2 cosh(n pi a / (2 t)))), t the short side, theta' = T / (G J) (Timoshenko &
    Goodier, Theory of Elasticity, 3rd ed., 1970, Sec. 109), 20 odd terms."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    a, t = np.maximum(a, b), np.minimum(a, b)
    n = np.arange(1, 40, 2).reshape((-1,) + (1,) * a.ndim)
    series = np.sum(1.0 / (n**2 * np.cosh(np.minimum(n * np.pi * a / (2 * t), 700.0))), axis=0)
    return t * (1.0 - 8.0 / np.pi**2 * series) / rect_torsion_constant(a, t)


def rect_depth(t0, t1, tm, xi):
    """Depth (m) at fractions xi (k,) of elements with end depths t0, t1 (n_e,) and mid
    depth tm (n_e,; NaN: linear taper): (n_e, k), the planar model's tapers."""
    x = np.asarray(xi, dtype=float)[None, :]
    t0, t1, tm = t0[:, None], t1[:, None], tm[:, None]
    quadratic = t0 * (1 - x) * (1 - 2 * x) + 4 * tm * x * (1 - x) + t1 * x * (2 * x - 1)
    return np.where(np.isfinite(tm), quadratic, t0 + (t1 - t0) * x)


@dataclass(frozen=True)
class Section:
    """Cross-section of one element: area ``A`` (m^2), second moments ``Iy`` = int z^2 dA
    and ``Iz`` = int y^2 dA (m^4, about the local y and z axes), torsion constant ``J``
    (m^4), optional shear areas ``Ay``, ``Az`` (m^2; None: no shear deformation in that
    direction, Euler-Bernoulli). Prismatic, or a rectangle tapered along local y
    (``Section.rect``; A, Iy, Iz, J are then those at the element's first node). A rectangle
    keeps its depths along local y and z (m; None for a general section: no stress).
    ``factors`` (bending, shear, axial, bending_y) multiply E Iz, G Ay, E A and E Iy in the
    stiffness only (a planar model's notch correction or root extension, carried into 3-D by
    reduced/spatial.py), not the mass; ``mass_factor`` multiplies
    the mass (0: a root extension)."""

    A: float
    Iy: float
    Iz: float
    J: float
    Ay: float | None = None
    Az: float | None = None
    taper: tuple | None = None  # (depth_y at node 1, at node 2, at mid or NaN, depth_z)
    depth_y: float | None = None
    depth_z: float | None = None
    factors: tuple = (1.0, 1.0, 1.0, 1.0)
    mass_factor: float = 1.0

    def __post_init__(self):
        for name in ("A", "Iy", "Iz", "J"):
            positive(name, getattr(self, name))
        if len(self.factors) != 4 or not all(f > 0 for f in self.factors):
            raise ValueError(f"Section: factors = {self.factors!r} must be four positive "
                             "numbers (bending, shear, axial, bending_y)")
        positive("Ay", self.Ay, allow_none=True)
        positive("Az", self.Az, allow_none=True)

    @classmethod
    def rect(cls, width: float, thickness: float, shear: bool = False,
             thickness_end: float | None = None, thickness_mid: float | None = None):
        """Rectangle ``width`` (along local z: the plate's depth, out of a planar mechanism's
        plane) by ``thickness`` (along local y: in the plane), m, in the planar
        :meth:`flexfem.fem.beam.Section.rect`'s order; the thickness tapered linearly to
        ``thickness_end`` at the second node, or quadratically through ``thickness_mid`` too
        (the planar model's tapers); shear areas 5/6 A if ``shear`` (given for the mid-length
        section; the stiffness follows A along the taper). depth_y = thickness, depth_z =
        width."""
        b, h = positive("thickness", thickness), positive("width", width)
        end = positive("thickness_end", thickness_end, allow_none=True)
        mid = positive("thickness_mid", thickness_mid, allow_none=True)
        taper = None
        if end is not None or mid is not None:
            end = b if end is None else end
            taper = (b, end, math.nan if mid is None else mid, h)
        t_mid = b if taper is None else float(rect_depth(*(np.array([v]) for v in taper[:3]),
                                                          [0.5])[0, 0])
        k = 5.0 / 6.0 * t_mid * h if shear else None
        return cls(A=b * h, Iy=b * h**3 / 12.0, Iz=h * b**3 / 12.0,
                   J=float(rect_torsion_constant(b, h)), Ay=k, Az=k, taper=taper,
                   depth_y=b, depth_z=h)

    @property
    def Ip(self) -> float:
        """Polar second moment Iy + Iz (m^4): the section's torsional inertia per rho."""
        return self.Iy + self.Iz


def element_frames(nodes, elements, orientation=None) -> np.ndarray:
    """(n_e, 3, 3) local axes (columns x, y, z) of each element; ``orientation``: one
    vector or one per element (n_e, 3) towards which local z points (default global z,
    or global x for an element along global z)."""
    d = nodes[elements[:, 1]] - nodes[elements[:, 0]]
    ex = d / np.linalg.norm(d, axis=1)[:, None]
    if orientation is None:
        ref = np.tile([0.0, 0.0, 1.0], (len(ex), 1))
        along_z = np.abs(ex[:, 2]) > 1.0 - 1e-9
        ref[along_z] = [1.0, 0.0, 0.0]
    else:
        ref = np.broadcast_to(np.asarray(orientation, dtype=float), ex.shape)
    ez = ref - np.einsum("ei,ei->e", ref, ex)[:, None] * ex
    norm = np.linalg.norm(ez, axis=1)
    bad = ~(norm > 1e-9 * np.maximum(np.linalg.norm(ref, axis=1), 1e-300))
    if np.any(bad):
        raise ValueError(f"orientation: parallel to elements {np.flatnonzero(bad).tolist()} "
                         "(or zero); give a vector off their axis")
    ez = ez / norm[:, None]
    ey = np.cross(ez, ex)
    return np.stack([ex, ey, ez], axis=2)


class Beam3DModel:
    """Spatial beam model. nodes (n, 3) m; elements (n_e, 2) node indices; sections: one
    Section or one per element; material: Material (E, nu, rho); orientation: local z
    reference (see element_frames); rigid_links: RigidLink sequence; point_masses:
    {node: (mass kg, Jx, Jy, Jz kg m^2 about global axes through the node)}; groups:
    {name: BeamGroup or node indices}, the named places of the analysis face
    (:mod:`.face`; :meth:`add_group`)."""

    def __init__(self, nodes, elements, sections, material: Material, orientation=None,
                 rigid_links=(), point_masses=None, groups=None):
        self.nodes = np.asarray(nodes, dtype=float)
        if self.nodes.ndim != 2 or self.nodes.shape[1] != 3 or not np.all(np.isfinite(self.nodes)):
            raise ValueError(f"nodes must be a finite (n, 3) array, got shape {self.nodes.shape}")
        self.elements = np.asarray(elements, dtype=int).reshape(-1, 2)
        n = len(self.nodes)
        if self.elements.size and (self.elements.min() < 0 or self.elements.max() >= n):
            raise ValueError(f"elements refer to nodes outside 0..{n - 1}")
        if not isinstance(material, Material):
            raise ValueError(f"material = {material!r} must be a flexfem Material")
        self.material = material
        secs = [sections] * len(self.elements) if isinstance(sections, Section) else list(sections)
        if len(secs) != len(self.elements) or not all(isinstance(s, Section) for s in secs):
            raise ValueError(f"sections: need one Section or {len(self.elements)} Sections")
        self.sections = secs
        d = self.nodes[self.elements[:, 1]] - self.nodes[self.elements[:, 0]]
        self.lengths = np.linalg.norm(d, axis=1)
        if np.any(self.lengths <= 0):
            bad = np.flatnonzero(self.lengths <= 0).tolist()
            raise ValueError(f"elements {bad} have zero length")
        self.frames = element_frames(self.nodes, self.elements, orientation)
        self.rigid_links = tuple(rigid_links)
        self.point_masses = dict(point_masses or {})
        self._check_links()
        self.groups = {}
        for name, g in (groups or {}).items():
            self.add_group(name, g)

    def add_group(self, name: str, nodes, span=(0.0, 0.0, 0.0)) -> None:
        """Name ``nodes`` (masters of rigid bodies) a group standing for a face of extent
        ``span`` (dx, dy, dz; m): where the analysis face's supports and loads act."""
        self.groups[name] = BeamGroup.of(name, nodes, span, self.n_nodes)

    def _check_links(self):
        n = len(self.nodes)
        self.master_of = link_masters(self.rigid_links, n, RigidLink)
        for node, value in self.point_masses.items():
            if not 0 <= int(node) < n or len(value) != 4 or min(value) < 0:
                raise ValueError(f"point_masses[{node!r}] = {value!r} must be (m, Jx, Jy, Jz) "
                                 ">= 0 on an existing node")

    @property
    def n_nodes(self) -> int:
        return len(self.nodes)

    @property
    def n_dofs(self) -> int:
        return 6 * len(self.nodes)

    @property
    def n_elements(self) -> int:
        return len(self.elements)

    def section_table(self) -> dict:
        """Shear areas Ay, Az (m^2, inf where shear is off) as (n_e,) arrays, the stiffness
        factors (n_e, 4) and the mass factors (n_e,)."""
        shear = lambda name: np.array([math.inf if getattr(s, name) is None else getattr(s, name)
                                       for s in self.sections], dtype=float)
        return {"Ay": shear("Ay"), "Az": shear("Az"),
                "factors": np.array([s.factors for s in self.sections], dtype=float),
                "mass_factor": np.array([s.mass_factor for s in self.sections], dtype=float)}

    def section_at(self, xi) -> dict:
        """A, Iy, Iz, J, Ip (m^2, m^4) and the rectangles' depth_y, depth_z (m; NaN for a
        general section) of every element at fractions ``xi`` (k,) along it, each (n_e, k)."""
        xi = np.atleast_1d(np.asarray(xi, dtype=float))
        get = lambda name: np.array([math.nan if getattr(s, name) is None else getattr(s, name)
                                     for s in self.sections], dtype=float)
        out = {k: np.repeat(get(k)[:, None], len(xi), axis=1)
               for k in ("A", "Iy", "Iz", "J", "depth_y", "depth_z")}
        tapered = [e for e, s in enumerate(self.sections) if s.taper is not None]
        if tapered:
            t0, t1, tm, w = np.array([self.sections[e].taper for e in tapered]).T
            t = rect_depth(t0, t1, tm, xi)
            w = w[:, None]
            out["depth_y"][tapered] = t
            out["A"][tapered], out["Iy"][tapered] = t * w, t * w**3 / 12.0
            out["Iz"][tapered], out["J"][tapered] = w * t**3 / 12.0, rect_torsion_constant(t, w)
        out["Ip"] = out["Iy"] + out["Iz"]
        return out
