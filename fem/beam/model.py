"""Planar beam models: rigid links, supports and loads, and the model (its mesh:
:mod:`.mesh`).

    mesh = beam_chain([(0, 0), (0.05, 0)], Section.rect(0.01, 0.5e-3), n_per_segment=20)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, steel)

DOFs per node: (u, v, theta) = x and y displacement (m) and rotation (rad, counter-clockwise).
"""
from dataclasses import dataclass

import numpy as np

from ..materials import Material
from .groups import BeamGroup
from .section import PLANAR_COLUMNS, Section
from .superelement import Superelement


@dataclass(frozen=True)
class RigidLink:
    """Nodes ``slaves`` move rigidly with node ``master`` (exact rigid-body constraint)."""

    master: int
    slaves: tuple

    def __post_init__(self):
        object.__setattr__(self, "slaves", tuple(int(s) for s in np.atleast_1d(self.slaves)))
        object.__setattr__(self, "master", int(self.master))


def link_masters(rigid_links, n_nodes: int, link_type) -> np.ndarray:
    """(n_nodes,) the master node of each slave node, -1 for a node no link holds; a
    ValueError for a link of another type, a node outside the model, a node slaved twice or to
    itself, or a master that is itself a slave."""
    master_of = -np.ones(n_nodes, dtype=int)
    for link in rigid_links:
        if not isinstance(link, link_type):
            raise ValueError(f"rigid_links: {link!r} is not a RigidLink")
        for node in (link.master,) + link.slaves:
            if not 0 <= node < n_nodes:
                raise ValueError(f"rigid_links: node {node} outside 0..{n_nodes - 1}")
        for s in link.slaves:
            if s == link.master or master_of[s] >= 0:
                raise ValueError(f"rigid_links: node {s} is slaved twice or to itself")
            master_of[s] = link.master
    if np.any(master_of[master_of[master_of >= 0]] >= 0):
        raise ValueError("rigid_links: a master node is itself a slave; use one master")
    return master_of


class BeamModelBase:
    """What the planar and the spatial beam model share: nodes (n, dim) m, elements (n_e, 2)
    node indices, sections (one Section or one per element), material, shear (Timoshenko
    shear deformation where a section has a shear area), rigid links, point masses, groups
    ({name: BeamGroup or node indices}: the places the analysis face's supports and loads
    name, :mod:`.face`) and the derived-data cache. ``dim`` 2 or 3; ``PER_NODE`` DOFs a
    node; ``POINT_MASS`` (entries of a point mass, their words)."""

    dim, PER_NODE, POINT_MASS = 0, 0, (0, "")

    def _setup(self, nodes, elements, sections, material: Material, shear: bool) -> np.ndarray:
        """Check and set nodes, elements, material, shear, sections and the element lengths
        (m); returns the element chords (n_e, dim) m."""
        dim = self.dim
        self.nodes = np.asarray(nodes, dtype=float)
        shape = self.nodes.shape
        if self.nodes.ndim != 2 or shape[1] != dim or not np.all(np.isfinite(self.nodes)):
            raise ValueError(f"nodes must be a finite (n, {dim}) array, got shape "
                             f"{self.nodes.shape}")
        self.elements = np.asarray(elements, dtype=int).reshape(-1, 2)
        n = len(self.nodes)
        if self.elements.size and (self.elements.min() < 0 or self.elements.max() >= n):
            raise ValueError(f"elements refer to nodes outside 0..{n - 1}")
        if not isinstance(material, Material):
            raise ValueError(f"material = {material!r} must be a flexfem Material")
        self.material, self.shear = material, bool(shear)
        secs = [sections] * len(self.elements) if isinstance(sections, Section) else list(sections)
        if len(secs) != len(self.elements) or not all(isinstance(s, Section) for s in secs):
            raise ValueError(f"sections: need one Section or {len(self.elements)} Sections")
        self.sections = secs
        d = self.nodes[self.elements[:, 1]] - self.nodes[self.elements[:, 0]]
        self.lengths = np.hypot(d[:, 0], d[:, 1]) if dim == 2 else np.linalg.norm(d, axis=1)
        if np.any(self.lengths <= 0):
            bad = np.flatnonzero(self.lengths <= 0).tolist()
            raise ValueError(f"elements {bad} have zero length")
        return d

    def _links(self, rigid_links, point_masses) -> None:
        """Set and check the rigid links (master_of) and the point masses."""
        n = len(self.nodes)
        self.rigid_links = tuple(rigid_links)
        self.point_masses = dict(point_masses or {})
        self.master_of = link_masters(self.rigid_links, n, RigidLink)
        size, words = self.POINT_MASS
        for node, value in self.point_masses.items():
            if not 0 <= int(node) < n or len(value) != size or min(value) < 0:
                raise ValueError(f"point_masses[{node!r}] = {value!r} must be {words} on an "
                                 "existing node")

    def _groups(self, groups) -> None:
        self.groups = {}
        for name, g in (groups or {}).items():
            self.add_group(name, g)

    def add_group(self, name: str, nodes, span=None) -> None:
        """Name ``nodes`` (a BeamGroup, or node indices with the face's extent ``span``, m,
        one per axis; default none) as group ``name`` (a support on it needs its nodes to
        be no rigid-link slaves)."""
        span = (0.0,) * self.dim if span is None else span
        self.groups[name] = BeamGroup.of(name, nodes, span, self.n_nodes)

    def cached(self, key, compute):
        """``compute()`` once per model and ``key``: data derived from the model (its patterns,
        element matrices), which is not changed once built; arrays are returned read-only."""
        cache = self.__dict__.setdefault("_derived", {})
        if key not in cache:
            value = compute()
            for a in value if isinstance(value, tuple) else (value,):
                if isinstance(a, np.ndarray):
                    a.setflags(write=False)
            cache[key] = value
        return cache[key]

    def is_cached(self, key) -> bool:
        """Whether ``cached(key, ...)`` has been computed for this model."""
        return key in self.__dict__.get("_derived", {})

    @property
    def n_nodes(self) -> int:
        return len(self.nodes)

    @property
    def n_dofs(self) -> int:
        return self.PER_NODE * len(self.nodes)

    @property
    def n_elements(self) -> int:
        return len(self.elements)


class BeamModel(BeamModelBase):
    """A planar beam model: co-rotational beams between nodes, 3 DOFs a node (u, v in m,
    theta in rad), analysed by the face (``flexfem.fem.solve_static`` and the others) with
    the group supports and loads of ``flexfem.fem`` (``Fixed("root")``, ``Force("tip",
    (fx, fy))``) on its ``groups``.

    Parameters
    ----------
    nodes : array_like, shape (n, 2)
        Node coordinates (m).
    elements : array_like, shape (n_e, 2)
        The two node indices of each element.
    sections : Section or sequence of Section
        One section for every element, or one per element (:class:`.section.Section`).
    material : Material
        The elastic material (E, nu in Pa and -, rho in kg/m^3).
    shear : bool
        Timoshenko shear deformation where a section has a shear area (default off:
        Euler-Bernoulli).
    rigid_links : sequence of RigidLink
        Nodes that move rigidly with a master node (a body).
    point_masses : dict, optional
        {node: (mass kg, rotary inertia kg m^2)}.
    superelements : sequence of Superelement
        Linear parts condensed onto pairs of nodes (assembled after the elements).
    groups : dict, optional
        {name: BeamGroup or node indices}: the places supports and loads name.

    Raises
    ------
    ValueError
        Nodes, elements, sections or links that do not fit together, naming which.
    """

    dim, PER_NODE, POINT_MASS = 2, 3, (2, "(m >= 0, J >= 0)")

    def __init__(self, nodes, elements, sections, material: Material, shear: bool = False,
                 rigid_links=(), point_masses=None, superelements=(), groups=None):
        d = self._setup(nodes, elements, sections, material, shear)
        self.section_table = np.array([s.planar_row for s in self.sections],
                                      dtype=float).reshape(-1, PLANAR_COLUMNS)
        self.angles = np.arctan2(d[:, 1], d[:, 0])
        self._links(rigid_links, point_masses)
        self.superelements = tuple(superelements)
        self._pairs()
        self._groups(groups)

    def _pairs(self):
        parts = []
        for sup in self.superelements:
            if not isinstance(sup, Superelement):
                raise ValueError(f"superelements: {sup!r} is not a Superelement")
            if max(sup.nodes) >= self.n_nodes or min(sup.nodes) < 0:
                raise ValueError(f"superelements: nodes {sup.nodes} outside "
                                 f"0..{self.n_nodes - 1}")
            parts.append(sup.pairs())
        empty = (np.zeros((0, 2), dtype=int), np.zeros((0, 6, 6)), np.zeros((0, 6, 6)))
        self.pairs, self.pair_stiffness, self.pair_mass = (
            np.concatenate([p[k] for p in parts]) if parts else empty[k] for k in range(3))
        self.connectivity = np.vstack([self.elements, self.pairs]).astype(int)

    def section_at(self, xi):
        """(A m^2, Iz m^4, c m) of every element at fractions ``xi`` (k,) along it: (n_e, k)."""
        xi = np.atleast_1d(np.asarray(xi, dtype=float))
        rect, w, t0, t1, A, I, c, _, tm = self.section_table.T[:9]
        t = t0[:, None] + (t1 - t0)[:, None] * xi[None, :]
        quadratic = np.isfinite(tm)
        if quadratic.any():
            x = xi[None, :]
            t_q = (t0[:, None] * (1 - x) * (1 - 2 * x) + 4 * tm[:, None] * x * (1 - x)
                   + t1[:, None] * x * (2 * x - 1))
            t = np.where(quadratic[:, None], t_q, t)
        is_rect = rect[:, None] > 0  # np.where broadcasts the general sections' (n_e, 1)
        A_ = np.where(is_rect, w[:, None] * t, A[:, None])
        I_ = np.where(is_rect, w[:, None] * t ** 3 / 12.0, I[:, None])
        c_ = np.where(is_rect, t / 2.0, c[:, None])
        return A_, I_, c_
