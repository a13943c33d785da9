"""A notch hinge's beam model corrected by the notch's own 2-D model.

    f = notch_factors("circular", l, b, fillet_radius, nu)    # NotchFactors
    hinge = profile_beam(a, b, thickness_fn, w, factors=f)    # its beam, corrected

Beam theory of a notch (Paros and Weisbord's integral of the profile) keeps plane sections
through a thickness that changes quickly along the hinge; the notch's 2-D stress field does
not, and the notch is softer than its beam: 2 % at t/R = 0.05, 6.5 % at 0.2, 13 % at 1 in
rotation (docs/beam.md, "Notch hinges: the 2-D patch"). The correction is computed, not
fitted to a mechanism: the notch alone between two rigid ends, in plane stress (flexfem's
P2 continuum, ``NECK_ELEMENTS`` triangles across the local thickness, finer at the neck's
surface), against the same notch as a beam (:func:`~flexfem.geometry.beam_layout.profile_beam`
without root extension: the ends are rigid in both). Three factors on the profile's beam
elements, multiplying E I, kappa G A and E A, reproduce the patch's 3 x 3 end compliance
(rotation under a moment, deflection under a force, extension under a pull); a symmetric
profile has no other independent entry. The patch's neck stress under a moment and under a
pull, over the beam's nominal 6 M / (w b^2) and N / (w b), gives the notch's
stress-concentration factors. Where the notch enters the bodies it joins is left to the root
extension of :mod:`.beam_layout`, as for every flexure.

The factors depend on the shape alone (t/R, r_f / b, nu: plane stress has no scale and the
out-of-plane width divides out). A circular notch's are tabulated over t/R and nu in
data/notch_factors.toml (written by scripts/notch_factor_table.py with this module's
:func:`patch_factors`) and interpolated there, so a design sweep pays nothing; elsewhere they
are computed, once per shape in a process (0.1-1 s). Lengths in m.
"""
from dataclasses import dataclass
import functools
import math

import numpy as np

from ..data import shared_toml
from ..fem import Fixed, Material, Model, PlaneStress, RigidFace, solve_static
from ..fem.beam import BeamModel, Fixed as BeamFixed
from ..fem.beam.compliance import compliance as beam_compliance
from ..fem.compliance import compliance_matrix
from ..fem.gmsh_session import gmsh_session
from ..fem.mesh import mesh_from_gmsh
from .beam_layout import profile_beam
from .hinge_profiles import (ARC_ELEMENTS, add_hinge_surface, check_hinge_profile, half_height,
                             profile_thickness)

NECK_ELEMENTS = 12  # P2 triangles across the local thickness: the factors to 0.3 % (24: table)
NECK_REFINEMENT = 3  # at the neck's surface the triangles are b / (3 NECK_ELEMENTS): its K_t
BEAM_ELEMENTS = 80  # the reference beam of the profile (its own error < 1e-5)
# the patch tells the shear factor where shear is a fair share of the beam's deflection under a
# force: below 2 % its mesh error (~1e-3 of the deflection) would be 5 % of the factor, which
# is left at 1; from 8 % up it is the patch's; between, blended, so it is continuous in t/R
SHEAR_SHARE = (0.02, 0.08)
TABLE = "notch_factors.toml"


@dataclass(frozen=True)
class NotchFactors:
    """Multipliers of E I, kappa G A and E A on a notch's beam elements (-), and its neck's
    stress-concentration factors under a moment and under a pull (peak von Mises over the
    nominal 6 M / (w b^2) and N / (w b), -; NaN for a filleted hinge, whose peak is at its
    fillets, not its neck)."""

    bending: float
    shear: float
    axial: float
    kt_bending: float
    kt_tension: float


def notch_factors(profile: str, l: float, b: float, fillet_radius: float,
                  nu: float) -> NotchFactors:
    """NotchFactors of a ``profile`` hinge ('circular' or 'filleted') of length ``l`` and
    neck ``b`` (m), fillet radius ``fillet_radius`` (m, filleted only), Poisson's ratio
    ``nu``: a circular notch in the table's range interpolated from it (to ~0.1 %), any
    other computed (:func:`patch_factors`)."""
    _check(profile, l, b, fillet_radius, nu)
    if profile == "circular":
        found = tabulated(2 * b / l, nu)
        if found is not None:
            return found
    return patch_factors(profile, l, b, fillet_radius, nu)


def patch_factors(profile: str, l: float, b: float, fillet_radius: float, nu: float,
                  neck_elements: int = NECK_ELEMENTS) -> NotchFactors:
    """NotchFactors computed: the notch's plane-stress 2-D model between rigid ends against
    its beam (see the module's text), ``neck_elements`` triangles across its thickness."""
    _check(profile, l, b, fillet_radius, nu)
    r_over_b = fillet_radius / b if profile == "filleted" else 0.0
    return _patch_factors(profile, round(l / b, 12), round(r_over_b, 12), float(nu),
                          int(neck_elements))


def tabulated(t_over_r: float, nu: float) -> NotchFactors | None:
    """A circular notch's NotchFactors at ``t_over_r`` = b / R and Poisson's ratio ``nu``,
    interpolated in data/notch_factors.toml (monotone cubic in ln(t/R), linear in nu); None
    outside its range."""
    table = _table()
    x, nus = table["log_t_over_r"], table["nu"]
    lx = math.log(t_over_r)
    if not (x[0] <= lx <= x[-1] and nus[0] <= nu <= nus[-1]):
        return None
    k = min(int(np.searchsorted(nus, nu, side="right")) - 1, len(nus) - 2)
    u = (nu - nus[k]) / (nus[k + 1] - nus[k])
    values = [(1 - u) * table[name][k](lx) + u * table[name][k + 1](lx)
              for name in NotchFactors.__dataclass_fields__]
    return NotchFactors(*(float(v) for v in values))


@functools.lru_cache(maxsize=1)
def _table() -> dict:
    from scipy.interpolate import PchipInterpolator

    raw = shared_toml(TABLE)["circular_notch"]
    x = np.log(np.asarray(raw["t_over_r"], float))
    out = {"log_t_over_r": x, "nu": np.asarray(raw["nu"], float)}
    for name in NotchFactors.__dataclass_fields__:
        out[name] = [PchipInterpolator(x, np.asarray(row, float)) for row in raw[name]]
    return out


def _check(profile, l, b, fillet_radius, nu) -> None:
    check_hinge_profile(profile, fillet_radius, "notch_factors")
    if profile == "leaf":
        raise ValueError("notch_factors: a leaf hinge has no notch; its beam is exact between "
                         "rigid ends (the root extension stands for the blocks)")
    for name, value in (("l", l), ("b", b)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"notch_factors: {name} = {value!r} must be a finite number > 0 (m)")
    if not (isinstance(nu, (int, float)) and math.isfinite(nu) and -1 < nu < 0.5):
        raise ValueError(f"notch_factors: nu = {nu!r} must be a number in (-1, 0.5)")
    if profile == "filleted" and not 2 * fillet_radius < l:
        raise ValueError(f"notch_factors: fillet_radius = {fillet_radius!r} m must be < l / 2 "
                         f"= {l / 2!r} m")


@functools.lru_cache(maxsize=512)
def _patch_factors(profile: str, l_over_b: float, r_over_b: float, nu: float,
                   neck_elements: int) -> NotchFactors:
    b, w = 1e-3, 1e-3  # the factors are scale-free: any size gives the same
    l, rf = l_over_b * b, (r_over_b * b if profile == "filleted" else b)
    material = Material("notch_patch", E=200e9, nu=nu, rho=1.0)
    thickness = lambda s: profile_thickness(profile, l, b, rf, s)
    patch = Model(_patch_mesh(profile, l, b, rf, thickness, neck_elements), material,
                  PlaneStress(w), order=2)
    C2 = compliance_matrix(patch, [Fixed("root")], "tip", point=(l, 0.0)).matrix
    breaks = (rf, l - rf) if profile == "filleted" else ()
    beam = profile_beam((0.0, 0.0), (l, 0.0), thickness, w, breaks, BEAM_ELEMENTS, 0.0,
                        vectorized=True)
    C_shear, C_bend = (_beam_compliance(beam, material, shear) for shear in (True, False))
    bending = C_shear[2, 2] / C2[2, 2]
    axial = C_shear[0, 0] / C2[0, 0]
    beam_shear = C_shear[1, 1] - C_bend[1, 1]  # the beam's shear deflection per unit force
    patch_shear = C2[1, 1] - C_bend[1, 1] / bending
    lo, hi = SHEAR_SHARE
    weight = min(1.0, max(0.0, (beam_shear / C_shear[1, 1] - lo) / (hi - lo)))
    shear = 1.0
    if weight > 0 and patch_shear > 0:
        shear = 1.0 + weight * (beam_shear / patch_shear - 1.0)
    kt_bending = kt_tension = math.nan
    if profile == "circular":  # its peak is at the neck, mid-length
        kt_bending = _neck_stress(patch, l, b, moment=1.0) / (6.0 / (w * b ** 2))
        kt_tension = _neck_stress(patch, l, b, force=(1.0, 0.0)) / (1.0 / (w * b))
    return NotchFactors(float(bending), float(shear), float(axial), kt_bending, kt_tension)


def _beam_compliance(mesh, material, shear: bool) -> np.ndarray:
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, material, shear=shear)
    first, last = mesh.point_nodes
    return beam_compliance(model, [BeamFixed(first)], last)


def _neck_stress(patch, l: float, b: float, moment: float = 0.0, force=(0.0, 0.0)) -> float:
    """Largest von Mises stress (Pa) at the neck's two surface points under the tip face's
    ``moment`` (N m) or ``force`` (N), the root clamped."""
    res = solve_static(patch, [Fixed("root")], [],
                       rigid_faces=[RigidFace("tip", moment=moment, force=force)])
    y = 0.5 * b * (1 - 1e-6)
    s = res.stress_at(np.array([[l / 2, y], [l / 2, -y]]))
    sxx, syy, sxy = s[:, 0, 0], s[:, 1, 1], s[:, 0, 1]
    return float(np.sqrt(sxx ** 2 - sxx * syy + syy ** 2 + 3 * sxy ** 2).max())


def _patch_mesh(profile: str, l: float, b: float, rf: float, thickness, neck_elements: int):
    """The hinge alone along [0, l] (m): triangles of about thickness(x) / ``neck_elements``,
    down to b / (NECK_REFINEMENT neck_elements) at the neck's surface points (l / 2, +-b / 2);
    boundary groups 'root' (x = 0) and 'tip' (x = l)."""
    height = 2 * half_height(profile, l, b, rf)
    fine = b / (NECK_REFINEMENT * neck_elements)

    def size(dim, tag, x, y, z, lc):
        local = float(thickness(min(max(x, 0.0), l))) / neck_elements
        return min(lc, local, fine + 0.5 * math.hypot(x - l / 2, abs(y) - b / 2))

    with gmsh_session("notch_patch") as gmsh:
        occ = gmsh.model.occ
        surface = add_hinge_surface(occ, 0.0, l, 0.0, b, profile, rf)
        occ.synchronize()
        gmsh.model.addPhysicalGroup(2, [surface], name="body")
        eps = 1e-3 * min(l, b) + 1e-7  # OCC's bounding boxes are 1e-7 m larger
        for name, x in (("root", 0.0), ("tip", l)):
            ends = gmsh.model.getEntitiesInBoundingBox(x - eps, -height, -1.0, x + eps,
                                                       height, 1.0, 1)
            gmsh.model.addPhysicalGroup(1, [t for _, t in ends], name=name)
        for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints"):
            gmsh.option.setNumber(key, 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", ARC_ELEMENTS)
        gmsh.option.setNumber("Mesh.MeshSizeMax", height / neck_elements)
        gmsh.model.mesh.setSizeCallback(size)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)
