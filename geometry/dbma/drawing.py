"""Geometry and mesh of the double-row bow-type micro-displacement amplifier (DBMA).

The paper (Micromachines 2020, 11(3), 312) has no drawing in its text; the structure is
reconstructed from Sections 2-3 (see docs/dbma.md) as a bow (bridge) amplifier whose every
quarter joins an input member to an output member by two parallel rows of arms:

    left input member (arms 13 + 2, width a, each of length ll), pushed outward by the actuator
      --hinge--[arm 3, outer row]--hinge--  output member 4 (width ls), top
      --hinge--[arm 1, inner row]--hinge--  output member 4

The two hinges of an arm are offset across it by h (Eq. 5: h = l1 - l2): pulled outward by the
input members, the arms lift output member 4 and lower output member 11 (Eq. 3). The upper
and lower halves are the two bow-type amplifiers in series: their outputs add between members 4
and 11. The part is symmetric about x = 0 and y = 0; the actuator lies along y = 0. Lengths in m.
"""
import math
import numbers
from dataclasses import dataclass

import numpy as np

from ...fem.gmsh_session import gmsh_session
from ...fem.mesh import FEMesh, mesh_from_gmsh
from ..hinge_profiles import (
    ARC_ELEMENTS,
    add_hinge_surface,
    check_fits,
    check_hinge_profile,
    profile_area,
)
from .params import DBMAParams

MM = 1e-3


@dataclass(frozen=True)
class DBMALayout:
    """Dimensions the paper leaves unstated (m), chosen once (docs/dbma.md).

    arm_gap : clearance between the actuator axis y = 0 and the inner row of arms, room for the
        actuator between output members 4 and 11; 8 mm (a GMA rod of up to ~14 mm diameter).
    pad_height : height of the input pads, the faces the actuator's end caps push on; 10 mm.
    pad_depth : how far each input pad stands out of its input member toward the actuator;
        2 mm.
    hinge_profile : "leaf" (default: a sharp-cornered l x b rectangle), "filleted" (the leaf
        with root fillets of radius hinge_fillet_radius inside the length l) or "circular"
        (right-circular notch of minimum thickness b, radius l / 2), see
        :mod:`flexfem.geometry.hinge_profiles`. The paper names no profile.
    hinge_fillet_radius : root-fillet radius of the "filleted" profile (m); 0.5 mm.
    """

    arm_gap: float = 8.0 * MM
    pad_height: float = 10.0 * MM
    pad_depth: float = 2.0 * MM
    hinge_profile: str = "leaf"
    hinge_fillet_radius: float = 0.5 * MM

    def __post_init__(self):
        for name in ("arm_gap", "pad_height", "pad_depth"):
            value = getattr(self, name)
            if not (isinstance(value, numbers.Real) and not isinstance(value, bool)
                    and math.isfinite(value) and value > 0):
                raise ValueError(f"DBMALayout: {name} = {value!r} must be a finite number > 0 (m)")
            object.__setattr__(self, name, float(value))
        check_hinge_profile(self.hinge_profile, self.hinge_fillet_radius, "DBMALayout")
        object.__setattr__(self, "hinge_fillet_radius", float(self.hinge_fillet_radius))


@dataclass(frozen=True)
class Rect:
    """Axis-aligned rectangle [x0, x1] x [y0, y1] (m) with a role and a label."""

    x0: float
    x1: float
    y0: float
    y1: float
    role: str   # "hinge", "arm", "input_member", "output_member", "pad"
    label: str  # the paper's arm number, e.g. "7", a hinge "H7a", a pad "P-"

    def mirrored(self, sx: int, sy: int, label: str) -> "Rect":
        xs = sorted((sx * self.x0, sx * self.x1))
        ys = sorted((sy * self.y0, sy * self.y1))
        return Rect(xs[0], xs[1], ys[0], ys[1], self.role, label)


def check_layout(p: DBMAParams, layout: DBMALayout) -> None:
    """Raise ValueError if the parameters cannot form a DBMA: hinges longer than an arm, hinges
    off the members they join, or the two rows of arms colliding."""
    if not p.l < p.e:
        raise ValueError(f"DBMA: hinge length l = {p.l!r} m must be < arm length e = {p.e!r} m")
    if not p.h + p.b < p.c:
        raise ValueError(f"DBMA: h = {p.h!r} m must be < c - b = {p.c - p.b!r} m (the hinges "
                         "of an arm, offset by h, must both lie within its width)")
    if not p.h + p.b < p.ls:
        raise ValueError(f"DBMA: h + b = {p.h + p.b!r} m must be < ls = {p.ls!r} m "
                         "(the hinge must end on the output member)")
    need = 2 * p.c + p.b + layout.arm_gap
    if not p.ll > need:
        raise ValueError(f"DBMA: ll = {p.ll!r} m must be > 2 c + b + arm_gap = {need!r} m "
                         "(the two rows of arms must not collide)")
    if not layout.pad_height / 2 < layout.arm_gap:
        raise ValueError(f"DBMALayout: pad_height = {layout.pad_height!r} m must be < 2 arm_gap "
                         f"= {2 * layout.arm_gap!r} m (the pads sit between the inner rows)")
    if not layout.pad_depth < p.e + 2 * p.l:
        raise ValueError(f"DBMALayout: pad_depth = {layout.pad_depth!r} m must be < e + 2 l")
    if layout.hinge_profile != "leaf":
        # the profile's end height b + 2 r, offset h / 2 from the arm's centre line, must stay
        # within the arm's width c (and so within the members, which are wider)
        check_fits(layout.hinge_profile, p.l, p.b, layout.hinge_fillet_radius, p.c - p.h,
                   "DBMALayout")


def quarter_rects(p: DBMAParams, layout: DBMALayout) -> list[Rect]:
    """Rectangles of the top-right quarter (x >= 0, y >= 0), m. The input member and pad
    (they straddle y = 0) and output member (it straddles x = 0) are given whole."""
    g, c, l, e, h, b = layout.arm_gap, p.c, p.l, p.e, p.h, p.b
    x_out = p.ls / 2                    # side face of the output member
    x_in = x_out + 2 * l + e            # inner face of the input member
    rects = [
        Rect(x_in, x_in + p.a, -p.ll, p.ll, "input_member", "J"),
        Rect(x_in - layout.pad_depth, x_in, -layout.pad_height / 2, layout.pad_height / 2,
             "pad", "P"),
        Rect(-x_out, x_out, g, p.ll, "output_member", "4"),
    ]
    for row, yc in (("i", g + c / 2), ("o", p.ll - c / 2)):
        # the input-member end hinge is higher by h: pulled outward, the arm lifts member 4
        rects += [
            Rect(x_in - l, x_in, yc + h / 2 - b / 2, yc + h / 2 + b / 2, "hinge", row + "b"),
            Rect(x_out + l, x_in - l, yc - c / 2, yc + c / 2, "arm", row),
            Rect(x_out, x_out + l, yc - h / 2 - b / 2, yc - h / 2 + b / 2, "hinge", row + "a"),
        ]
    return rects


# the paper's arm numbers, going round the part: 1, 2, 3 top left; 4 top output member;
# 5, 6, 7 top right; 8, 9, 10 bottom right; 11 bottom output member; 12, 13, 14 bottom left.
# (sx, sy) -> (inner-row arm, half input member, outer-row arm)
_ARM_NUMBERS = {
    (-1, 1): ("1", "2", "3"), (1, 1): ("7", "6", "5"),
    (1, -1): ("8", "9", "10"), (-1, -1): ("14", "13", "12"),
}


def dbma_rects(p: DBMAParams, layout: DBMALayout | None = None) -> list[Rect]:
    """Every rectangle of the part (m), non-overlapping, labelled with the paper's arm numbers:
    arms '1'...'14' (an input member is the two halves '2'+'13' or '6'+'9', drawn whole as
    'J-' / 'J+'), hinges 'H<arm>a' (output-member end) and 'H<arm>b' (input-member end),
    input pads 'P-' / 'P+'."""
    layout = layout or DBMALayout()
    check_layout(p, layout)
    q = quarter_rects(p, layout)
    rects = []
    for sx in (1, -1):
        side = "+" if sx > 0 else "-"
        rects += [q[0].mirrored(sx, 1, "J" + side), q[1].mirrored(sx, 1, "P" + side)]
    rects += [q[2], q[2].mirrored(1, -1, "11")]
    for (sx, sy), (inner, _, outer) in _ARM_NUMBERS.items():
        for r in q[3:]:
            arm = inner if r.label[0] == "i" else outer
            label = arm if r.role == "arm" else f"H{arm}{r.label[1]}"
            rects.append(r.mirrored(sx, sy, label))
    return rects


def part_area(p: DBMAParams, layout: DBMALayout | None = None) -> float:
    """In-plane area of the part (m^2): the rectangles do not overlap; a hinge counts its
    profile's area (the rectangle l x b for the default leaf)."""
    layout = layout or DBMALayout()
    if layout.hinge_profile == "leaf":
        return float(sum((r.x1 - r.x0) * (r.y1 - r.y0) for r in dbma_rects(p, layout)))
    hinge = profile_area(layout.hinge_profile, p.l, p.b, layout.hinge_fillet_radius)
    return float(sum((r.x1 - r.x0) * (r.y1 - r.y0) if r.role != "hinge" else hinge
                     for r in dbma_rects(p, layout)))


def part_mass(p: DBMAParams, layout: DBMALayout | None = None) -> float:
    """Mass of the part, area * d * rho (kg)."""
    return part_area(p, layout) * p.d * p.rho


def arm_masses_reconstructed(p: DBMAParams, layout: DBMALayout | None = None) -> dict:
    """Masses (kg) of the arms as Eq. 19 names them, in this reconstruction: m1 (an inclined
    arm between its hinges), m2 (half an input member, arms 2, 6, 9, 13), m4 and m11 (the
    output members)."""
    rects = {r.label: r for r in dbma_rects(p, layout)}
    area = lambda r: (r.x1 - r.x0) * (r.y1 - r.y0)
    return {"m1": p.rho * p.d * area(rects["1"]), "m2": p.rho * p.d * area(rects["J-"]) / 2,
            "m4": p.rho * p.d * area(rects["4"]), "m11": p.rho * p.d * area(rects["11"])}


def hinge_boxes(p: DBMAParams, layout: DBMALayout | None = None) -> list[Rect]:
    """The 16 hinge rectangles (m)."""
    return [r for r in dbma_rects(p, layout) if r.role == "hinge"]


def group_boxes(p: DBMAParams, layout: DBMALayout | None = None) -> dict:
    """Bounding boxes (x0, x1, y0, y1), m, of the boundary groups: input_a / input_b (the
    faces of the left / right input pads the actuator pushes on), output (top face of output
    member 4), fixed (bottom face of output member 11: the mounting face)."""
    layout = layout or DBMALayout()
    pad, member = quarter_rects(p, layout)[1], quarter_rects(p, layout)[2]
    return {
        "input_a": (-pad.x0, -pad.x0, pad.y0, pad.y1),
        "input_b": (pad.x0, pad.x0, pad.y0, pad.y1),
        "output": (member.x0, member.x1, member.y1, member.y1),
        "fixed": (member.x0, member.x1, -member.y1, -member.y1),
    }


def draw_dbma(gmsh, p: DBMAParams, layout: DBMALayout | None = None, dim: int = 2,
              layers: int = 2) -> None:
    """Build the DBMA in the open gmsh session (OpenCASCADE): a conforming set of surfaces
    (2-D), extruded by d in ``layers`` structured layers in 3-D, with physical groups 'body'
    and 'hinges' (dim) and 'input_a', 'input_b', 'input', 'output', 'fixed' (dim - 1). The
    hinges have the layout's ``hinge_profile``."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    layout = layout or DBMALayout()
    rects = dbma_rects(p, layout)
    occ = gmsh.model.occ
    leaf = layout.hinge_profile == "leaf"  # the rectangles exactly as before the profiles
    tags = [occ.addRectangle(r.x0, r.y0, 0.0, r.x1 - r.x0, r.y1 - r.y0)
            if r.role != "hinge" or leaf
            else add_hinge_surface(occ, r.x0, r.x1, (r.y0 + r.y1) / 2, p.b, layout.hinge_profile,
                                   layout.hinge_fillet_radius) for r in rects]
    occ.fragment([(2, t) for t in tags[:1]], [(2, t) for t in tags[1:]])
    occ.synchronize()
    if dim == 3:
        occ.extrude(gmsh.model.getEntities(2), 0.0, 0.0, p.d, numElements=[layers])
        occ.synchronize()
    cells = [t for _, t in gmsh.model.getEntities(dim)]
    gmsh.model.addPhysicalGroup(dim, cells, name="body")
    hinges = hinge_boxes(p, layout)
    gmsh.model.addPhysicalGroup(dim, [t for t in cells if _inside_any(gmsh, dim, t, hinges)],
                                name="hinges")
    eps = 1e-3 * p.b  # above the OpenCASCADE bounding-box tolerance (1e-7 m)
    z1 = p.d if dim == 3 else 0.0
    found = {}
    for name, (x0, x1, y0, y1) in group_boxes(p, layout).items():
        ents = gmsh.model.getEntitiesInBoundingBox(x0 - eps, y0 - eps, -eps,
                                                   x1 + eps, y1 + eps, z1 + eps, dim - 1)
        found[name] = [t for _, t in ents]
        if not found[name]:
            raise RuntimeError(f"DBMA geometry: no boundary found for group {name!r}")
        gmsh.model.addPhysicalGroup(dim - 1, found[name], name=name)
    gmsh.model.addPhysicalGroup(dim - 1, found["input_a"] + found["input_b"], name="input")


def _inside_any(gmsh, dim, tag, boxes) -> bool:
    x, y, _ = gmsh.model.occ.getCenterOfMass(dim, tag)
    return any(r.x0 <= x <= r.x1 and r.y0 <= y <= r.y1 for r in boxes)


def check_mesh_options(dim: int, hinge_elements: int, size_factor: float) -> None:
    """Raise ValueError for a dim other than 2 or 3, hinge_elements < 1 or a size_factor
    outside [0.05, 20]."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    if not (isinstance(hinge_elements, (int, np.integer)) and hinge_elements >= 1):
        raise ValueError(f"hinge_elements = {hinge_elements!r} must be an integer >= 1")
    if not (isinstance(size_factor, numbers.Real) and math.isfinite(size_factor)
            and 0.05 <= size_factor <= 20):
        raise ValueError(f"size_factor = {size_factor!r} must be in [0.05, 20]")


def set_mesh_sizes(gmsh, p: DBMAParams, layout: DBMALayout | None = None, dim: int = 2,
                   hinge_elements: int = 4, size_factor: float = 1.0) -> dict:
    """Mesh-size fields: element size b / hinge_elements inside and near every hinge (a Box
    field per hinge), growing to the coarse size c / 2 (2-D) or c (3-D) away from them;
    both scaled by size_factor; arcs of non-leaf hinge profiles get ARC_ELEMENTS edges per
    full circle at most. Returns {"hinge_size", "coarse_size"} (m)."""
    check_mesh_options(dim, hinge_elements, size_factor)
    fine = p.b / hinge_elements * size_factor
    coarse = (p.c / 2 if dim == 2 else p.c) * size_factor
    field = gmsh.model.mesh.field
    boxes = []
    for r in hinge_boxes(p, layout):
        f = field.add("Box")
        field.setNumber(f, "VIn", fine)
        field.setNumber(f, "VOut", coarse)
        for key, value in (("XMin", r.x0), ("XMax", r.x1), ("YMin", r.y0), ("YMax", r.y1),
                           ("ZMin", -1.0), ("ZMax", 1.0)):
            field.setNumber(f, key, value)
        field.setNumber(f, "Thickness", 2 * p.b + p.l)
        boxes.append(f)
    fmin = field.add("Min")
    field.setNumbers(fmin, "FieldsList", boxes)
    field.setAsBackgroundMesh(fmin)
    for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(key, 0)
    if layout is not None and layout.hinge_profile != "leaf":
        # arcs of notch and fillet: at most 10 degrees an element edge (chord sag < 0.4 % of
        # the radius), on top of the size fields
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", ARC_ELEMENTS)
    return {"hinge_size": fine, "coarse_size": coarse}


def layers_through_thickness(p: DBMAParams, size_factor: float = 1.0) -> int:
    """Number of element layers through the thickness d in 3-D: d / (c / 3), at least 2."""
    return max(2, int(round(p.d / (p.c / 3) / size_factor)))


def mesh_dbma(params: DBMAParams, layout: DBMALayout | None = None, dim: int = 2,
              hinge_elements: int | None = None, size_factor: float = 1.0) -> FEMesh:
    """Mesh the DBMA. 2-D: triangles (for a plane-stress model of thickness d), with
    ``hinge_elements`` (default 4) elements through the hinge thickness b. 3-D: the 2-D
    quadrilateral mesh extruded by d in hexahedral layers (default 2 elements through b: the
    quadratic hexahedra bend well). Groups: see :func:`draw_dbma`. Coordinates in m."""
    layout = layout or DBMALayout()
    check_layout(params, layout)
    if hinge_elements is None:
        hinge_elements = 4 if dim == 2 else 2
    check_mesh_options(dim, hinge_elements, size_factor)
    with gmsh_session("dbma") as gmsh:
        draw_dbma(gmsh, params, layout, dim, layers_through_thickness(params, size_factor))
        set_mesh_sizes(gmsh, params, layout, dim, hinge_elements, size_factor)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(dim)
        return mesh_from_gmsh(gmsh)


def dbma_outline_figure(params: DBMAParams, layout: DBMALayout | None = None, path=None):
    """Labelled drawing (PNG at ``path``) of the reconstructed DBMA: arms numbered 1-14,
    hinges in red, the groups the analyses use (input pads, output face, mounting face)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    layout = layout or DBMALayout()
    colours = {"hinge": "tab:red", "arm": "0.75", "input_member": "tab:blue",
               "output_member": "tab:green", "pad": "tab:orange"}
    fig, ax = plt.subplots(figsize=(7.5, 7.5))
    mm = 1e3
    for r in dbma_rects(params, layout):
        ax.add_patch(Rectangle((r.x0 * mm, r.y0 * mm), (r.x1 - r.x0) * mm, (r.y1 - r.y0) * mm,
                               facecolor=colours[r.role], edgecolor="k", linewidth=0.4))
        if r.role in ("arm", "output_member"):
            ax.text((r.x0 + r.x1) / 2 * mm, (r.y0 + r.y1) / 2 * mm, r.label, ha="center",
                    va="center", fontsize=10, weight="bold")
    for r in dbma_rects(params, layout):  # halves of the input members: arms 2, 6, 9, 13
        if r.role == "input_member":
            sx = 1 if r.x0 > 0 else -1
            top, bottom = ("6", "9") if sx > 0 else ("2", "13")
            xc = (r.x0 + r.x1) / 2 * mm
            ax.text(xc, r.y1 * mm * 0.5, top, ha="center", va="center", fontsize=10, weight="bold")
            ax.text(xc, r.y0 * mm * 0.5, bottom, ha="center", va="center", fontsize=10,
                    weight="bold")
    boxes = group_boxes(params, layout)
    for name, (x0, x1, y0, y1) in boxes.items():
        ax.plot([x0 * mm, x1 * mm], [y0 * mm, y1 * mm], lw=3,
                color={"fixed": "k", "output": "tab:purple"}.get(name, "tab:orange"))
        ax.annotate(name, ((x0 + x1) / 2 * mm, (y0 + y1) / 2 * mm), fontsize=8,
                    xytext=(0, 10 if name != "fixed" else -14), textcoords="offset points",
                    ha="center")
    ax.annotate("", xy=(-boxes["input_a"][0] * mm * 0.6, 0), xytext=(boxes["input_a"][0] * mm * 0.6, 0),
                arrowprops={"arrowstyle": "<->", "color": "tab:orange"})
    ax.text(0, 1.5, "actuator (GMA)", ha="center", fontsize=8, color="tab:orange")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"DBMA reconstruction: h = {params.h * mm:.2f} mm, b = {params.b * mm:.2f} mm "
                 "(hinges red)", fontsize=10)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=130)
    plt.close(fig)
    return path
