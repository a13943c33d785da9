"""The spatial beam model of a :class:`~flexfem.geometry.spatial.description.SpatialMechanism`
(docs/spatial.md, "The beam model").

- Each body is one rigid node at its centroid carrying the body's mass and its inertia about
  the global axes through the centroid (geometry/spatial/mass.py; products of inertia left
  out), named by the body's name (a group of one node, standing for a face of the body's
  extent).
- Each flexure is a chain of ``elements`` beam elements over its **free span** (its axis
  between the faces of the bodies it joins), both ends held rigidly by those bodies'
  nodes (RigidLink): the roots are clamped at the faces, their own compliance (the
  stresses spreading into the body over about a thickness) is not modelled.
- A wire: a round section of diameter d, A = pi d^2 / 4, I = pi d^4 / 64 about both axes,
  J = pi d^4 / 32, shear area k A with Cowper's k = 6 (1 + nu) / (7 + 6 nu) (G. R. Cowper,
  "The shear coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335-340).
- A leaf: the rectangle w x t (Section.rect, shear area 5/6 A, Saint-Venant J of the
  series), its width along ``width_along`` (the element's local z), its bending stiffness
  across the thickness times the anticlastic plate factor of its curvature
  (plate_action.py; 1 at rest).

SI units (m, kg, N, Pa).
"""
from dataclasses import dataclass, replace
import math

import numpy as np

from ...fem import Fixed, Force, Prescribed
from ...fem.beam.spatial import Beam3DModel, NodalLoad, RigidLink, Section
from ...geometry.spatial.description import Plate, SpatialMechanism
from ...geometry.spatial.mass import mass_properties
from .plate_action import plate_factor
from .roots import axial_factor, block_depth, warping_factor

#: Beam elements along each flexure's free span, by default.
ELEMENTS = 8
AXES = ("x", "y", "z")


def wire_section(diameter: float, nu: float) -> Section:
    """The round section of a wire of ``diameter`` (m), Poisson's ratio ``nu``."""
    area = math.pi * diameter ** 2 / 4
    second = math.pi * diameter ** 4 / 64
    shear = 6 * (1 + nu) / (7 + 6 * nu) * area
    return Section(A=area, Iy=second, Iz=second, J=2 * second, Ay=shear, Az=shear)


def leaf_section(leaf: Plate, nu: float, curvature: float = 0.0, length: float | None = None,
                 depths=None) -> Section:
    """The rectangle of a leaf (width along local z), its bending across the thickness
    stiffened by :func:`~.plate_action.plate_factor` at ``curvature`` (1/m); given its free
    ``length`` (m) and its bodies' ``depths`` (H_1, H_2) (m) along it, its roots' rules
    (roots.py): G J with restrained warping, E A with the roots' axial compliance."""
    section = Section.rect(leaf.width, leaf.thickness)
    factor = plate_factor(leaf.width, leaf.thickness, nu, curvature)
    axial = 1.0 if depths is None else axial_factor(leaf.thickness, length, depths)
    section = replace(section, factors=(factor, 1.0, axial, 1.0))
    if length is None:
        return section
    return replace(section, J=section.J * warping_factor(leaf.width, leaf.thickness, length,
                                                         nu, section.J))


def _across(axis) -> np.ndarray:
    """A unit vector perpendicular to ``axis``: a wire's local z (its section is round)."""
    e = np.asarray(axis, float) / np.linalg.norm(axis)
    ref = np.eye(3)[int(np.argmin(np.abs(e)))]
    v = ref - (ref @ e) * e
    return v / np.linalg.norm(v)


@dataclass(frozen=True, eq=False)
class SpatialBeam:
    """A mechanism's beam model: ``model`` (Beam3DModel with the bodies' names as groups),
    ``masters`` {body name: its node}, ``flexure_elements`` [element indices per flexure],
    ``mechanism``."""

    model: Beam3DModel
    masters: dict
    flexure_elements: list
    mechanism: SpatialMechanism

    def node(self, body: str) -> int:
        """The rigid node of ``body``; ValueError naming the bodies."""
        if body not in self.masters:
            raise ValueError(f"{body!r} is no body of the mechanism; bodies: "
                             f"{', '.join(self.masters)}")
        return self.masters[body]


def beam_model(mechanism: SpatialMechanism, material, elements: int = ELEMENTS,
               curvatures=None, roots: bool = True) -> SpatialBeam:
    """The :class:`SpatialBeam` of ``mechanism`` in ``material`` (E, nu, rho); ``elements``
    per flexure; ``curvatures``: one per flexure (1/m, the leaves' plate factor; None: 0,
    at rest); ``roots``: the leaves' root rules (roots.py; False: a rectangle clamped at
    the faces)."""
    if not (isinstance(elements, int) and elements >= 1):
        raise ValueError(f"elements = {elements!r} must be a whole number >= 1 per flexure")
    n_f = len(mechanism.flexures)
    curvatures = [0.0] * n_f if curvatures is None else list(curvatures)
    if len(curvatures) != n_f:
        raise ValueError(f"curvatures: {len(curvatures)} given for {n_f} flexures")
    props = [mass_properties(b) for b in mechanism.bodies]
    nodes = [p.centroid for p in props]
    masters = {b.name: k for k, b in enumerate(mechanism.bodies)}
    slaves = {name: [] for name in masters}
    chain, sections, orientation, owned = [], [], [], []
    for i, f in enumerate(mechanism.flexures):
        span = mechanism.span(i)
        first = len(nodes)
        nodes += [span.a + s * (span.b - span.a) for s in np.linspace(0, 1, elements + 1)]
        slaves[f.between[0]].append(first)
        slaves[f.between[1]].append(first + elements)
        owned.append(list(range(len(chain), len(chain) + elements)))
        chain += [(first + k, first + k + 1) for k in range(elements)]
        if isinstance(f, Plate):
            depths = (block_depth(mechanism, i, 0), block_depth(mechanism, i, 1))
            section = (leaf_section(f, material.nu, curvatures[i], span.length, depths)
                       if roots else leaf_section(f, material.nu, curvatures[i]))
            z = f.width_along
        else:
            section, z = wire_section(f.diameter, material.nu), _across(span.d)
        sections += [section] * elements
        orientation += [np.asarray(z, float)] * elements
    masses = {}
    for k, p in enumerate(props):
        j = np.diag(p.inertia(material.density_or_nan))
        masses[k] = (p.mass(material.density_or_nan), *(float(v) for v in j))
    model = Beam3DModel(np.array(nodes), np.array(chain), sections, material,
                        orientation=np.array(orientation),
                        rigid_links=[RigidLink(masters[n], tuple(s)) for n, s in slaves.items()],
                        point_masses=masses, shear=True)
    for b in mechanism.bodies:
        lo, hi = b.extent()
        model.add_group(b.name, [masters[b.name]], span=tuple(np.subtract(hi, lo)))
    return SpatialBeam(model, masters, owned, mechanism)


def supports_and_loads(spec, beam: SpatialBeam | None = None) -> tuple:
    """The analysis face's supports (Fixed, Prescribed) and loads of a spatial model file's
    spec: its forces (Force, the body's total, N; a traction is refused: a body is one
    node) and, given its ``beam``, its moments (NodalLoad on the body's node, N m)."""
    supports = [Fixed(s.group) if s.components is None else
                Prescribed(s.group, **{AXES[i]: v for i, v in s.components.items()})
                for s in spec.supports]
    loads = []
    for load in spec.loads:
        if load.kind != "force":
            raise ValueError(f"{load.source or spec.source}: [[loads]] {load.kind} on "
                             f"{load.group!r}: the beam model's bodies are rigid nodes; give "
                             "the body's total force = [Fx, Fy, Fz] (N)")
        loads.append(Force(load.group, load.vector))
    for body, (mx, my, mz), _ in (spec.spatial.moments if beam is not None else ()):
        loads.append(NodalLoad(beam.node(body), mx=mx, my=my, mz=mz))
    return supports, loads
