"""Profiles of a planar flexure hinge of length l and minimum thickness b along x (SI units).

* ``"leaf"``: a rectangle l x b with sharp corners where it meets the bodies it joins;
* ``"filleted"``: the leaf with a root fillet of radius r_f at each of its four corners, inside
  the length l (Lobontiu's corner-filleted hinge: straight part l - 2 r_f);
* ``"circular"``: the right-circular notch of Paros and Weisbord: a blank of height b + 2 r,
  r = l / 2, with a semicircle of radius r cut from each side, centres b + 2 r apart.

Each profile is drawn as one OpenCASCADE surface whose two end edges (x = x0 and x = x1) are
joined by fragmentation to the bodies on either side; the bodies must be at least as tall as
the profile's ``half_height`` on either side of its centre line.
"""
import math
import numbers


HINGE_PROFILES = ("leaf", "filleted", "circular")
ARC_ELEMENTS = 36  # mesh: element edges per full circle on the arcs (gmsh's curvature sizing)
ARC_SEGMENT_ANGLE = 2 * math.pi / ARC_ELEMENTS  # rad: each chord's sag is < 0.4 % of r


def check_hinge_profile(profile, fillet_radius, owner: str = "hinge") -> None:
    """Raise ValueError for a profile not in HINGE_PROFILES or a fillet radius that is not a
    finite number > 0 (m). ``owner`` prefixes the message (e.g. 'DBMALayout')."""
    if profile not in HINGE_PROFILES:
        raise ValueError(f"{owner}: hinge_profile = {profile!r} must be one of {HINGE_PROFILES}")
    if not (isinstance(fillet_radius, numbers.Real) and not isinstance(fillet_radius, bool)
            and math.isfinite(fillet_radius) and fillet_radius > 0):
        raise ValueError(f"{owner}: hinge_fillet_radius = {fillet_radius!r} must be a finite "
                         "number > 0 (m)")


def profile_radius(profile: str, l: float, fillet_radius: float) -> float:
    """Radius (m) of the profile's arcs: 0 (leaf), r_f (filleted), l / 2 (circular)."""
    return {"leaf": 0.0, "filleted": fillet_radius, "circular": l / 2}[profile]


def half_height(profile: str, l: float, b: float, fillet_radius: float) -> float:
    """Half the profile's height at its ends (m): b / 2 + its arc radius."""
    return b / 2 + profile_radius(profile, l, fillet_radius)


def check_fits(profile: str, l: float, b: float, fillet_radius: float, room: float,
               owner: str = "hinge") -> None:
    """Raise ValueError if a fillet is too long for the hinge (2 r_f >= l) or the profile's
    end height 2 half_height exceeds ``room`` (m), the height the joined bodies offer."""
    if profile == "filleted" and not 2 * fillet_radius < l:
        raise ValueError(f"{owner}: hinge_fillet_radius = {fillet_radius!r} m must be < l / 2 = "
                         f"{l / 2!r} m (the fillets lie inside the hinge length)")
    height = 2 * half_height(profile, l, b, fillet_radius)
    if not height < room:
        raise ValueError(f"{owner}: the {profile} hinge is {height!r} m tall at its ends "
                         f"(b + 2 r) and must be < {room!r} m (it must end on the arm and "
                         "the member it joins)")


def profile_area(profile: str, l: float, b: float, fillet_radius: float) -> float:
    """In-plane area of one hinge (m^2)."""
    if profile == "leaf":
        return l * b
    if profile == "filleted":
        return l * b + (4 - math.pi) * fillet_radius ** 2
    r = l / 2
    return l * (b + 2 * r) - math.pi * r ** 2


def profile_thickness(profile: str, l: float, b: float, fillet_radius: float, s):
    """Thickness t(s) (m) at a distance s (m, array) from the hinge's start, 0 <= s <= l."""
    import numpy as np

    s = np.asarray(s, dtype=float)
    if profile == "leaf":
        return np.full_like(s, b)
    if profile == "circular":
        r = l / 2
        return b + 2 * (r - np.sqrt(np.maximum(r ** 2 - (s - r) ** 2, 0.0)))
    rf = fillet_radius
    # distance into the fillet zone from the straight part (0 on the straight part)
    u = np.maximum(np.maximum(rf - s, s - (l - rf)), 0.0)
    return b + 2 * (rf - np.sqrt(np.maximum(rf ** 2 - u ** 2, 0.0)))


def add_hinge_surface(occ, x0: float, x1: float, yc: float, b: float, profile: str,
                      fillet_radius: float) -> int:
    """Add one hinge along x in [x0, x1] (m), centred on y = yc, to the OpenCASCADE kernel
    ``occ`` (gmsh.model.occ); return its surface tag. The leaf is ``occ.addRectangle`` exactly
    as before the profiles existed; the others are bounded by lines and quarter arcs."""
    l = x1 - x0
    if profile == "leaf":
        return occ.addRectangle(x0, yc - b / 2, 0.0, l, b)
    r = profile_radius(profile, l, fillet_radius)
    top, bottom, neck_top, neck_bottom = yc + b / 2 + r, yc - b / 2 - r, yc + b / 2, yc - b / 2
    point = lambda x, y: occ.addPoint(x, y, 0.0)
    p0, p1, p2, p3 = point(x0, bottom), point(x0, top), point(x1, top), point(x1, bottom)
    centres = [point(x0 + r, top), point(x1 - r, top), point(x1 - r, bottom), point(x0 + r, bottom)]
    necks = [point(x0 + r, neck_top), point(x1 - r, neck_bottom)]
    if profile == "filleted":  # the straight part of the neck, l - 2 r_f long
        necks.insert(1, point(x1 - r, neck_top))
        necks.insert(3, point(x0 + r, neck_bottom))
    else:                      # circular: one neck point per side, at mid-length
        necks = [necks[0], necks[0], necks[1], necks[1]]
    loop = [occ.addLine(p0, p1), occ.addCircleArc(p1, centres[0], necks[0])]
    if necks[1] != necks[0]:
        loop.append(occ.addLine(necks[0], necks[1]))
    loop += [occ.addCircleArc(necks[1], centres[1], p2), occ.addLine(p2, p3),
             occ.addCircleArc(p3, centres[2], necks[2])]
    if necks[3] != necks[2]:
        loop.append(occ.addLine(necks[2], necks[3]))
    loop.append(occ.addCircleArc(necks[3], centres[3], p0))
    surface = occ.addPlaneSurface([occ.addCurveLoop(loop)])
    occ.remove([(0, c) for c in centres])  # construction points, not part of the part
    return surface


def mesh_hinge_specimen(l: float, b: float, profile: str = "leaf",
                        fillet_radius: float = 0.5e-3, block_height: float = 10e-3,
                        block_length: float = 5e-3, hinge_elements: int = 4,
                        size_factor: float = 1.0):
    """2-D mesh (FEMesh, m) of one hinge between two blocks, for its stiffness alone: left
    block [-block_length, 0] x [-H/2, H/2], the hinge along [0, l] on y = 0, right block
    [l, l + block_length] x [-H/2, H/2], H = block_height. Element size b / hinge_elements
    in the hinge's core l x b, growing to H / 4 (both times size_factor). Groups: 'body',
    'hinges' (cells), 'fixed' (left end), 'tip' (right end), 'top' and 'bottom' (the right
    block's faces y = +-H/2)."""
    from ..fem.gmsh_session import gmsh_session  # meshing only here: the profiles stay light
    from ..fem.mesh import mesh_from_gmsh
    check_hinge_profile(profile, fillet_radius, "mesh_hinge_specimen")
    for name, value in (("l", l), ("b", b), ("block_length", block_length),
                        ("size_factor", size_factor)):
        if not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
            raise ValueError(f"mesh_hinge_specimen: {name} = {value!r} must be a finite number > 0")
    check_fits(profile, l, b, fillet_radius, block_height, "mesh_hinge_specimen")
    if not (isinstance(hinge_elements, int) and hinge_elements >= 1):
        raise ValueError(f"mesh_hinge_specimen: hinge_elements = {hinge_elements!r} must be an "
                         "integer >= 1")
    H, L = block_height, block_length
    with gmsh_session("hinge_specimen") as gmsh:
        occ = gmsh.model.occ
        left = occ.addRectangle(-L, -H / 2, 0.0, L, H)
        hinge = add_hinge_surface(occ, 0.0, l, 0.0, b, profile, fillet_radius)
        right = occ.addRectangle(l, -H / 2, 0.0, L, H)
        occ.fragment([(2, left)], [(2, hinge), (2, right)])
        occ.synchronize()
        cells = [t for _, t in gmsh.model.getEntities(2)]
        gmsh.model.addPhysicalGroup(2, cells, name="body")
        core = [t for t in cells if 0 < occ.getCenterOfMass(2, t)[0] < l]
        gmsh.model.addPhysicalGroup(2, core, name="hinges")
        eps = 1e-3 * b
        for name, (x0, x1, y0, y1) in {"fixed": (-L, -L, -H / 2, H / 2),
                                       "tip": (l + L, l + L, -H / 2, H / 2),
                                       "top": (l, l + L, H / 2, H / 2),
                                       "bottom": (l, l + L, -H / 2, -H / 2)}.items():
            ents = gmsh.model.getEntitiesInBoundingBox(x0 - eps, y0 - eps, -eps,
                                                       x1 + eps, y1 + eps, eps, 1)
            gmsh.model.addPhysicalGroup(1, [t for _, t in ents], name=name)
        field = gmsh.model.mesh.field
        box = field.add("Box")
        for key, value in (("VIn", b / hinge_elements * size_factor),
                           ("VOut", H / 4 * size_factor), ("XMin", 0.0), ("XMax", l),
                           ("YMin", -b / 2), ("YMax", b / 2), ("ZMin", -1.0), ("ZMax", 1.0),
                           ("Thickness", 2 * b + l)):
            field.setNumber(box, key, value)
        field.setAsBackgroundMesh(box)
        for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints"):
            gmsh.option.setNumber(key, 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0 if profile == "leaf" else ARC_ELEMENTS)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)
