"""A notch or filleted hinge's beam model corrected by the hinge's own 2-D model.

    f = notch_factors("circular", l, b, fillet_radius, nu)    # NotchFactors
    hinge = profile_beam(a, b, thickness_fn, w, factors=f)    # its beam, corrected
    f = profile_factors(thickness_fn, length, nu)             # any notch's profile t(s)

Beam theory of a notch (Paros and Weisbord's integral of the profile) keeps plane sections
through a thickness that changes quickly along the hinge, and its end section, which a leaf
loads across its thickness, carries its load near its middle; the 2-D stress field does
neither, and the notch is softer than its beam: 2 % at t/R = 0.05, 8 % at 0.2, 29 % at 1 in
rotation, 12-33 % in extension (docs/beam_validation.md, "Notch hinges: the 2-D patch"). The correction
is computed, not fitted to a mechanism: the hinge with a stub of its end height, as long as
that height, at each end (the least body it can enter), rigid beyond the stubs, in plane
stress (flexfem's P2 continuum, ``NECK_ELEMENTS`` triangles across the local thickness, finer
at the neck's surface), against the same hinge and stubs as beams
(:func:`~flexfem.reduced.layout.profile_beam` without root extension). Three factors on
the hinge's beam elements, multiplying E I, kappa G A and E A, reproduce the patch's end
compliance (rotation under a moment, deflection under a force, extension under a pull; a
symmetric profile has no other independent entry). The patch's neck stress under a moment and
under a pull, over the beam's nominal 6 M / (w b^2) and N / (w b), gives a notch's
stress-concentration factors. The rest of the body the hinge enters is left to the root
extension of :mod:`.beam_layout`, as for every flexure (made for a leaf, it misses part of a
notch's junction with a body much taller than the notch's ends: docs/beam.md).

The factors depend on the shape alone (t/R, r_f / b, nu: plane stress has no scale and the
out-of-plane width divides out). A circular notch's are tabulated over t/R and nu in
data/notch_factors.toml (written by scripts/notch_factor_table.py with this module's
:func:`patch_factors`), and a description's circular or elliptical notch (its profile as
geometry/mechanism/beams.py writes it) over t/R, across / along and nu in
data/notch_description_factors.json (scripts/notch_description_table.py, with
:func:`profile_factors`; E I within 6e-4 of the direct solve, E A 1e-3, kappa G A 3e-3, K_t 5 %:
docs/beam_speed.md); both are interpolated (monotone cubic), so a first analysis and a design
sweep pay nothing. Any other profile, or one outside a table's range, is computed, once per
shape in a process (1-7 s), and says so in the log (logger ``flexfem.reduced.hinge_patch``,
level INFO). Lengths in m.
"""
from dataclasses import dataclass
import functools
from importlib import resources
import json
import logging
import math

import numpy as np

from ..data import shared_toml
from ..fem.beam import BeamModel, Section, beam_chain
from ..fem.beam.supports import NodeFixed as BeamFixed
from ..fem.beam.compliance import compliance as beam_compliance
from ..fem.materials import Material
from .layout import profile_beam
from ..geometry.hinge_profiles import ARC_ELEMENTS, add_hinge_surface, check_hinge_profile, profile_thickness

NECK_ELEMENTS = 12  # P2 triangles across the local thickness: the factors to 0.3 % (24: table)
NECK_REFINEMENT = 3  # at the neck's surface the triangles are b / (3 NECK_ELEMENTS): its K_t
BEAM_ELEMENTS = 80  # the reference beam of the profile (its own error < 1e-5)
# the patch tells the shear factor where shear is a fair share of the beam's deflection under a
# force: below 2 % its mesh error (~1e-3 of the deflection) would be 5 % of the factor, which
# is left at 1; from 8 % up it is the patch's; between, blended, so it is continuous in t/R
SHEAR_SHARE = (0.02, 0.08)
TABLE = "notch_factors.toml"
DESCRIPTION_TABLE = "notch_description_factors.json"
LOG = logging.getLogger(__name__)
PROFILE_SAMPLES = 257  # a general profile's outline: a spline through this many samples
NOTCH_DEPTH = 1.5  # a notch's (fillets') ends are at least this many times its least thickness
# each end of the patch: a stub of the end's height, STUB times as long (the body the notch
# enters is at least that tall; 1 and 1.5 give the same factors to 0.1 %), STUB_ELEMENTS beams
STUB, STUB_ELEMENTS = 1.0, 4


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
    """NotchFactors computed: the hinge's plane-stress 2-D model with its stubs against its
    beam (see the module's text), ``neck_elements`` triangles across its thickness."""
    _check(profile, l, b, fillet_radius, nu)
    r_over_b = fillet_radius / b if profile == "filleted" else 0.0
    return _patch_factors(profile, round(l / b, 12), round(r_over_b, 12), float(nu),
                          int(neck_elements))


def tabulated(t_over_r: float, nu: float) -> NotchFactors | None:
    """A circular notch's NotchFactors at ``t_over_r`` = b / R and Poisson's ratio ``nu``,
    interpolated in data/notch_factors.toml (monotone cubic in ln(t/R), linear in nu); None
    outside its range."""
    x, nus, values, _ = _table(TABLE, "circular_notch", ("t_over_r", "nu"))
    lx = math.log(t_over_r)
    if not (x[0] <= lx <= x[-1] and nus[0] <= nu <= nus[-1]):
        return None
    k = min(int(np.searchsorted(nus, nu, side="right")) - 1, len(nus) - 2)
    u = (nu - nus[k]) / (nus[k + 1] - nus[k])
    rows = pchip(x, values, lx)  # (fields, nu)
    return NotchFactors(*(float((1 - u) * r[k] + u * r[k + 1]) for r in rows))


def description_tabulated(t_over_r: float, aspect: float, nu: float) -> NotchFactors | None:
    """NotchFactors of a description's notch (geometry/mechanism/beams.py's profile: neck b,
    semi-axes R along the centre line and ``aspect`` R across it) at ``t_over_r`` = b / R,
    interpolated in data/notch_description_factors.json (monotone cubic in ln(t/R),
    ln(aspect) and nu); None outside its range, or where the table was made from another
    profile (beams.STATIONS)."""
    from ..geometry.mechanism.beams import STATIONS

    try:
        x, y, nus, values, stations = _table(DESCRIPTION_TABLE, "description_notch",
                                             ("t_over_r", "aspect", "nu"))
    except FileNotFoundError:
        LOG.warning("notch correction: data/%s is missing (solved directly)", DESCRIPTION_TABLE)
        return None
    point = (math.log(t_over_r), math.log(aspect), nu)
    if stations != STATIONS or not all(a[0] <= p <= a[-1] for a, p in zip((x, y, nus), point)):
        return None
    v = pchip(nus, pchip(y, pchip(x, values, point[0]), point[1]), point[2])  # (fields,)
    return NotchFactors(*(float(f) for f in v))


@functools.lru_cache(maxsize=4)
def _table(name: str, table: str, axes: tuple) -> tuple:
    """(axis nodes (ln for t_over_r and aspect)..., values (fields, *reversed axes), the
    profile's stations or None) of ``table`` in data/``name`` (TOML, or JSON, read 50 times
    faster): each field's nested rows, the first axis innermost, null a NaN."""
    raw = (shared_toml(name) if name.endswith(".toml") else json.loads(
        resources.files(shared_toml.__module__).joinpath(name).read_text()))[table]
    nodes = [np.asarray(raw[a], float) for a in axes]
    nodes = [np.log(n) if a in ("t_over_r", "aspect") else n for a, n in zip(axes, nodes)]
    values = np.array([raw[f] for f in NotchFactors.__dataclass_fields__], float)
    return (*nodes, values, raw.get("stations"))


def pchip(x, y, at: float) -> np.ndarray:
    """Monotone piecewise cubic through the nodes ``x`` (increasing) and values ``y`` (nodes
    along the last axis), at the point ``at`` in [x[0], x[-1]]: scipy's PchipInterpolator
    (Fritsch and Carlson's derivatives), in numpy (scipy.interpolate costs 0.6 s to import)."""
    h, y = np.diff(x), np.asarray(y, float)
    m = np.diff(y, axis=-1) / h
    d = np.zeros_like(y)
    w1, w2 = 2 * h[1:] + h[:-1], h[1:] + 2 * h[:-1]
    flat = (np.sign(m[..., 1:]) != np.sign(m[..., :-1])) | (m[..., 1:] == 0) | (m[..., :-1] == 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        d[..., 1:-1] = np.where(flat, 0.0, (w1 + w2) / (w1 / m[..., :-1] + w2 / m[..., 1:]))
    for end, (h0, h1, m0, m1) in ((0, (h[0], h[1], m[..., 0], m[..., 1])),
                                  (-1, (h[-1], h[-2], m[..., -1], m[..., -2]))):
        e = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
        e = np.where(np.sign(e) != np.sign(m0), 0.0, e)
        d[..., end] = np.where((np.sign(m0) != np.sign(m1)) & (np.abs(e) > 3 * np.abs(m0)),
                               3 * m0, e)
    k = min(max(int(np.searchsorted(x, at, side="right")) - 1, 0), len(x) - 2)
    s, slope = at - x[k], m[..., k]
    t = (d[..., k] + d[..., k + 1] - 2 * slope) / h[k]
    return y[..., k] + d[..., k] * s + ((slope - d[..., k]) / h[k] - t) * s ** 2 + t / h[k] * s ** 3


def _check(profile, l, b, fillet_radius, nu) -> None:
    check_hinge_profile(profile, fillet_radius, "notch_factors")
    if profile == "leaf":
        raise ValueError("notch_factors: a leaf hinge has no notch; its beam is exact between "
                         "rigid ends (the root extension stands for the blocks)")
    for name, value in (("l", l), ("b", b)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"notch_factors: {name} = {value!r} must be a finite number > 0 (m)")
    _check_nu(nu, "notch_factors")
    if profile == "filleted" and not 2 * fillet_radius < l:
        raise ValueError(f"notch_factors: fillet_radius = {fillet_radius!r} m must be < l / 2 "
                         f"= {l / 2!r} m")


def _check_nu(nu, owner: str) -> None:
    if not (isinstance(nu, (int, float)) and math.isfinite(nu) and -1 < nu < 0.5):
        raise ValueError(f"{owner}: nu = {nu!r} must be a number in (-1, 0.5)")


@functools.lru_cache(maxsize=512)
def _patch_factors(profile: str, l_over_b: float, r_over_b: float, nu: float,
                   neck_elements: int) -> NotchFactors:
    b = 1e-3  # the factors are scale-free: any size gives the same
    l, rf = l_over_b * b, (r_over_b * b if profile == "filleted" else b)
    thickness = lambda s: profile_thickness(profile, l, b, rf, s)
    outline = lambda occ: add_hinge_surface(occ, 0.0, l, 0.0, b, profile, rf)
    breaks = (rf, l - rf) if profile == "filleted" else ()
    neck = l / 2 if profile == "circular" else None  # a fillet's peak is at its fillets
    return _fit(thickness, l, breaks, nu, outline, neck, neck_elements)


def profile_factors(thickness, length: float, nu: float,
                    neck_elements: int = NECK_ELEMENTS, table: bool = True) -> NotchFactors:
    """NotchFactors of a straight flexure of ``length`` (m) whose in-plane thickness is
    ``thickness(s)`` (m, s from its first end), symmetric about its centre line: its outline
    a spline through 257 samples of the profile (a model file's notch, any shape); K_t at its
    thinnest section where that is a point (a notch; NaN for a filleted leaf's flat neck).
    A description's notch in its table's range is interpolated there (``table``, and the
    default ``neck_elements``, the table's); any other profile is computed once per shape in
    a process (the key: the samples) and logged."""
    if not (isinstance(length, (int, float)) and math.isfinite(length) and length > 0):
        raise ValueError(f"profile_factors: length = {length!r} must be a finite number > 0 (m)")
    s = np.linspace(0.0, length, PROFILE_SAMPLES)
    t = np.array([float(thickness(x)) for x in s])
    if not np.all(np.isfinite(t) & (t > 0)):
        raise ValueError("profile_factors: the thickness must be finite and > 0 along the "
                         "flexure")
    _check_nu(nu, "profile_factors")
    found = _described(s, t, nu) if table and neck_elements == NECK_ELEMENTS else None
    if found is not None:
        return found
    b = t.min()
    return _sampled_factors(round(length / b, 9), tuple(np.round(t / b, 9)), float(nu),
                            int(neck_elements))


def _described(s, t, nu: float) -> NotchFactors | None:
    """The table's NotchFactors where the samples ``t`` (m) at ``s`` (m) are a description's
    notch (beams.py's profile of neck t.min(), semi-axes s[-1] / 2 along and
    (t[0] - t.min()) / 2 across, to 1e-9 of the neck) in the table's range; None elsewhere."""
    from ..geometry.mechanism.beams import profile
    from ..geometry.mechanism.description import Notch

    b, along = float(t.min()), float(s[-1]) / 2
    across = (float(t[0]) - b) / 2
    if not across > 0:
        return None
    own = profile(Notch(("", ""), (0.0, 0.0), (2 * along, 0.0), b, along, across), 2 * along)
    if np.abs(own.at(s) - t).max() > 1e-9 * b:
        return None
    return description_tabulated(b / along, across / along, nu)


def has_notch(thickness, length: float) -> bool:
    """Whether the profile t(s) over ``length`` (m) is a notch or filleted hinge: thinnest
    inside it (not at an end) and at least NOTCH_DEPTH times thicker at both ends (a
    circular, elliptic or parabolic notch, a leaf with root fillets; not a leaf or a
    taper)."""
    t = np.array([float(thickness(x)) for x in np.linspace(0.0, length, PROFILE_SAMPLES)])
    return bool(min(t[0], t[-1]) >= NOTCH_DEPTH * t.min())


@functools.lru_cache(maxsize=512)
def _sampled_factors(l_over_b: float, t_over_b: tuple, nu: float,
                     neck_elements: int) -> NotchFactors:
    LOG.info("notch correction: no table holds this profile (l / b = %.6g, nu = %.6g): its "
             "2-D patch is solved directly (1-7 s, once in a process)", l_over_b, nu)
    b = 1e-3
    l = l_over_b * b
    s = np.linspace(0.0, l, len(t_over_b))
    t = np.asarray(t_over_b) * b
    thickness = _spline(s, t)
    # a notch's neck is a point, where its K_t belongs; a filleted leaf's straight part is
    # long, and its peak is at the fillets (no K_t here)
    neck = s[int(np.argmin(t))] if np.mean(t <= 1.01 * t.min()) < 0.25 else None

    def outline(occ):
        point = lambda x, y: occ.addPoint(x, y, 0.0)
        top = [point(x, y / 2) for x, y in zip(s, t)]
        bottom = [point(x, -y / 2) for x, y in zip(s, t)]
        loop = [occ.addSpline(top), occ.addLine(top[-1], bottom[-1]),
                occ.addSpline(bottom[::-1]), occ.addLine(bottom[0], top[0])]
        return occ.addPlaneSurface([occ.addCurveLoop(loop)])

    return _fit(thickness, l, (), nu, outline, neck, neck_elements, arcs=False)


def _spline(s, t):
    """t(s) (vectorized) through the samples, as the outline's splines draw it."""
    from scipy.interpolate import CubicSpline

    spline = CubicSpline(s, t)
    return lambda x: spline(np.clip(x, s[0], s[-1]))


def _fit(thickness, l: float, breaks, nu: float, outline, neck, neck_elements: int,
         arcs: bool = True):
    """NotchFactors of the flexure ``outline(occ)`` draws along [0, l] (m), with a stub of
    its end's height, STUB times as long, at each end, against its beam of profile
    ``thickness`` (m) with the stubs as beams; K_t at the section ``neck`` (m from the start;
    None: NaN). The beam's compliance is linear in each factor's inverse, which four solves
    separate (the notch's bending, shear and axial parts and the rest)."""
    from ..fem import Fixed, Model, PlaneStress  # the continuum only where a patch is solved
    from ..fem.compliance import compliance_matrix
    w = 1e-3
    b = float(thickness(neck if neck is not None else l / 2))
    h0, h1 = float(thickness(0.0)), float(thickness(l))
    x0, x1 = -STUB * h0, l + STUB * h1
    material = Material("notch_patch", E=200e9, nu=nu, rho=1.0)

    def drawn(occ):
        stubs = [(2, occ.addRectangle(x0, -h0 / 2, 0.0, -x0, h0)),
                 (2, occ.addRectangle(l, -h1 / 2, 0.0, x1 - l, h1))]
        fused, _ = occ.fuse([(2, outline(occ))], stubs)
        return [tag for _, tag in fused]

    patch = Model(_patch_mesh(drawn, l, (x0, x1), thickness, neck, b, neck_elements, arcs),
                  material, PlaneStress(w), order=2)
    C2 = compliance_matrix(patch, [Fixed("root")], "tip", point=(x1, 0.0)).matrix

    def beam(bending=1.0, shear=1.0, axial=1.0):
        f = NotchFactors(bending, shear, axial, math.nan, math.nan)
        notch = profile_beam((0.0, 0.0), (l, 0.0), thickness, w, breaks, BEAM_ELEMENTS, 0.0,
                             vectorized=True, factors=f)
        mesh = beam_chain([(x0, 0.0), (0.0, 0.0)], Section.rect(w, h0), STUB_ELEMENTS)
        for part in (notch, beam_chain([(l, 0.0), (x1, 0.0)], Section.rect(w, h1),
                                       STUB_ELEMENTS)):
            mesh = mesh.join(part, tol=1e-9 * l)
        model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, material, shear=True)
        return beam_compliance(model, [BeamFixed(mesh.node_at((x0, 0.0)))],
                               mesh.node_at((x1, 0.0)))

    C1 = beam()
    B, S, A = (2 * (C1 - beam(**{name: 2.0})) for name in ("bending", "shear", "axial"))
    bending = B[2, 2] / (C2[2, 2] - (C1[2, 2] - B[2, 2]))
    axial = A[0, 0] / (C2[0, 0] - (C1[0, 0] - A[0, 0]))
    patch_shear = C2[1, 1] - (C1[1, 1] - B[1, 1] - S[1, 1]) - B[1, 1] / bending
    lo, hi = SHEAR_SHARE
    weight = min(1.0, max(0.0, (S[1, 1] / C1[1, 1] - lo) / (hi - lo)))
    shear = 1.0
    if weight > 0 and patch_shear > 0:
        shear = 1.0 + weight * (S[1, 1] / patch_shear - 1.0)
    kt_bending = kt_tension = math.nan
    if neck is not None:
        kt_bending = _neck_stress(patch, neck, b, moment=1.0) / (6.0 / (w * b ** 2))
        kt_tension = _neck_stress(patch, neck, b, force=(1.0, 0.0)) / (1.0 / (w * b))
    return NotchFactors(float(bending), float(shear), float(axial), kt_bending, kt_tension)


def _neck_stress(patch, x: float, b: float, moment: float = 0.0, force=(0.0, 0.0)) -> float:
    """Largest von Mises stress (Pa) at the surface points (x, +-b / 2) of the neck under the
    tip face's ``moment`` (N m) or ``force`` (N), the root clamped."""
    from ..fem import Fixed, RigidFace, solve_static
    res = solve_static(patch, [Fixed("root")], [],
                       rigid_faces=[RigidFace("tip", moment=moment, force=force)])
    y = 0.5 * b * (1 - 1e-6)
    s = res.stress_at(np.array([[x, y], [x, -y]]))
    sxx, syy, sxy = s[:, 0, 0], s[:, 1, 1], s[:, 0, 1]
    return float(np.sqrt(sxx ** 2 - sxx * syy + syy ** 2 + 3 * sxy ** 2).max())


def _patch_mesh(drawn, l: float, span, thickness, neck, b: float, neck_elements: int,
                arcs: bool = True):
    """The surfaces ``drawn(occ)`` draws (their tags) along ``span`` = (x0, x1) (m), a notch
    along [0, l] with its stubs: triangles of about thickness(x) / ``neck_elements`` (x
    clipped to the notch), down to b / (NECK_REFINEMENT neck_elements) at the neck's surface
    points (``neck``, +-b / 2; none if None; b its thickness, m); boundary groups 'root' (x =
    x0) and 'tip' (x = x1). ``arcs``: the outline's curves are arcs (curvature sizing on)."""
    from ..fem.gmsh_session import gmsh_session
    from ..fem.mesh import mesh_from_gmsh
    fine = b / (NECK_REFINEMENT * neck_elements)
    xs = np.linspace(0.0, l, PROFILE_SAMPLES)
    ts = np.asarray(thickness(xs), dtype=float)  # the size follows these (gmsh asks often)

    def size(dim, tag, x, y, z, lc):
        local = float(np.interp(x, xs, ts)) / neck_elements
        if neck is not None:
            local = min(local, fine + 0.5 * math.hypot(x - neck, abs(y) - b / 2))
        return min(lc, local)

    with gmsh_session("notch_patch") as gmsh:
        occ = gmsh.model.occ
        surfaces = drawn(occ)
        occ.synchronize()
        gmsh.model.addPhysicalGroup(2, surfaces, name="body")
        height = max(ts[0], ts[-1], b)
        eps = 1e-3 * min(l, b) + 1e-7  # OCC's bounding boxes are 1e-7 m larger
        for name, x in zip(("root", "tip"), span):
            ends = gmsh.model.getEntitiesInBoundingBox(x - eps, -height, -1.0, x + eps,
                                                       height, 1.0, 1)
            gmsh.model.addPhysicalGroup(1, [t for _, t in ends], name=name)
        for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints"):
            gmsh.option.setNumber(key, 0)
        # curvature sizing resolves the exact profiles' arcs; on a sampled profile's splines
        # it costs seconds and the thickness sizing alone gives the same factors (to 1e-4)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", ARC_ELEMENTS if arcs else 0)
        gmsh.option.setNumber("Mesh.MeshSizeMax", height / neck_elements)
        gmsh.model.mesh.setSizeCallback(size)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)
