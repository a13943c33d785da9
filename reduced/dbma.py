"""Reduced beam model of the DBMA, generated from its parameters (and layout).

    model, info = dbma_beam_model(paper_design())
    info["input_a"], info["input_b"], info["output"]   # master nodes (pad faces, output face)
    model3d, info = dbma_beam3d_model(paper_design())  # spatial: out-of-plane modes

Same reconstruction as the continuum mesh (:func:`flexfem.geometry.dbma.drawing.quarter_rects`,
mirrored into four quarters): each of the 16 hinges is a beam following its profile t(s)
(leaf, filleted or circular notch: :func:`flexfem.geometry.hinge_profiles.profile_thickness`
through :func:`flexfem.fem.beam.beam_from_profile`; a notch or filleted one corrected by its
own 2-D model, :mod:`flexfem.reduced.hinge_patch`), each inclined arm an elastic Timoshenko
beam of width c along its centre line, joined to its two hinges (offset +-h/2 across it) by
rigid offsets; the input members (width a) and output members 4 and 11 (width ls) are elastic
beams along their centre lines, member 11 clamped at its bottom (the mounting face); each input
member where its pad bears on it, with the pad, is a 2-D plane-stress patch condensed onto the
member's beams and the pad face's node (:mod:`.member_patch`; docs/beam_validation_dbma.md, "DBMA: the input
member's patch"). The spatial model lifts the planar one with block members instead (each pad
with the part of its member it spans a rigid block, which the member's halves enter with the
common root extension; docs/beam_validation_dbma.md, "Before the patch: the pad block").
Root extension: see :mod:`flexfem.reduced.layout` (0.38 x root thickness per root by
default, with the root's axial compliance for a block of height c at both ends: the arm's
width; the members' faces around a hinge are about as tall). Lengths in m.
"""
import numpy as np

from ..fem.beam import (BeamGroup, BeamMesh, BeamModel, RigidLink, Section,
                         beam_chain)
from ..fem.materials import Material
from .layout import ROOT_EXTENSION, check_root_extension, profile_beam
from .hinge_patch import notch_factors
from ..geometry.hinge_profiles import profile_thickness
from .spatial import lifted_model
from ..geometry.dbma.drawing import DBMALayout, check_layout, quarter_rects
from .dbma_member_patch import member_cut, member_superelement
from ..geometry.dbma.params import DBMAParams

QUARTERS = ((1, 1), (-1, 1), (1, -1), (-1, -1))
# elements a hinge: a leaf is uniform (each element exact in statics) and light, so 8 give the
# outputs of 48 to 1e-8; a notch's or fillet's profile, quadratic in each element (its
# flexibility exact for that), needs more: 20 give the outputs of 80 to 1e-4
# (tests/studies/dbma/test_dbma_beam_model.py: the convergence tests)
LEAF_ELEMENTS, PROFILE_ELEMENTS = 8, 20


def _hinge_fn(p: DBMAParams, layout: DBMALayout):
    prof, rf = layout.hinge_profile, layout.hinge_fillet_radius
    fn = lambda s: profile_thickness(prof, p.l, p.b, rf, s)  # vectorized over s
    breaks = (rf, p.l - rf) if prof == "filleted" else ()
    return fn, breaks


def _placed(template: BeamMesh, a, b) -> BeamMesh:
    """``template`` (a hinge built from (0, 0) along +x) laid from ``a`` to ``b`` (m): every
    hinge of the DBMA has the same profile, length and blocks, so one profile_beam serves
    all 16 (the same nodes to rounding, the same sections)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = (b - a) / float(np.linalg.norm(b - a))
    nodes = a + template.nodes[:, :1] * d
    return BeamMesh(nodes, template.elements, template.sections, template.point_nodes)


class _Builder:
    """Accumulates nodes, elements and sections; nodes are appended, never merged."""

    def __init__(self):
        self.nodes, self.elements, self.sections, self.n = [], [], [], 0

    def add(self, mesh: BeamMesh) -> list:
        n0, self.n = self.n, self.n + len(mesh.nodes)
        self.nodes.append(mesh.nodes)
        self.elements.append(mesh.elements + n0)
        self.sections += list(mesh.sections)
        return [n0 + k for k in mesh.point_nodes]

    def point(self, xy) -> int:
        n0, self.n = self.n, self.n + 1
        self.nodes.append(np.asarray(xy, float)[None, :])
        return n0


def _column(bld, links, xc, ys, width, depth, hinge_ends, per_length) -> dict:
    """A member as an elastic beam along x = ``xc`` through the heights ``ys`` (m), width
    ``width``; the hinges' ends [(node, y)] joined to it by rigid offsets. {y: node}."""
    ys = sorted(set(ys) | {y for _, y in hinge_ends})
    counts = [max(2, int(round(per_length * (y1 - y0)))) for y0, y1 in zip(ys[:-1], ys[1:])]
    chain = bld.add(beam_chain([(xc, y) for y in ys], Section.rect(depth, width), counts))
    at = {y: chain[k] for k, y in enumerate(ys)}
    for node, y in hinge_ends:
        links.append(RigidLink(at[y], (node,)))
    return at


def _input_member(bld, links, supers, p, layout, J, pad, sx, hinge_ends, root_extension,
                  member_patch) -> int:
    """An input member (arms 2 + 13 or 6 + 9) as elastic beams of width a along its centre
    line, the hinges' ends joined to them by rigid offsets; returns the master node on its
    pad's face, where the actuator pushes.

    Where the pad bears on it, the member is as deep as its span to the first hinges and no
    beam: with ``member_patch`` it is a 2-D patch there, with its pad, condensed onto the
    beams' ends at the cuts and the pad face's node (:mod:`.member_patch`, appended to
    ``supers``). Without (the spatial model's planar part): over the pad's height the member
    is a rigid block carried by the pad, a short beam (pad_height thick) from its face to the
    member's face, which the member's halves enter with the common root extension,
    root_extension x a into it, at most to its middle (a pad lower than 2 x 0.38 a: a point
    support; docs/beam_validation_dbma.md, "Before the patch: the pad block")."""
    xc, face = sx * (J.x0 + J.x1) / 2, (sx * min(abs(pad.x0), abs(pad.x1)), 0.0)
    if member_patch:
        y0 = member_cut(p, layout)
        if any(abs(y) <= y0 for _, y in hinge_ends):
            raise ValueError(f"DBMA: the input member's patch (|y| <= {y0!r} m) reaches a "
                             "hinge")
        ends = []
        for ys in ((-p.ll, -y0), (y0, p.ll)):
            at = _column(bld, links, xc, ys, p.a, p.d,
                         [(n, y) for n, y in hinge_ends if ys[0] <= y <= ys[1]], 6 / p.ll)
            ends.append(at[ys[1] if ys[0] < 0 else ys[0]])
        master = bld.point(face)
        supers.append(member_superelement(p, layout, sx, (*ends, master)))
        return master
    half = layout.pad_height / 2
    y0 = max(half - root_extension * p.a, 0.0)  # the member is rigid for |y| <= y0
    at = _column(bld, links, xc, (-p.ll, p.ll, -y0, y0), p.a, p.d, hinge_ends, 6 / p.ll)
    chain = bld.add(beam_chain([face, (sx * J.x0, 0.0)], Section.rect(p.d, layout.pad_height),
                               2))
    block = [n for y, n in at.items() if abs(y) <= y0 * (1 + 1e-9)]
    links.append(RigidLink(chain[1], tuple(block)))
    return chain[0]


def dbma_beam_model(p: DBMAParams, layout: DBMALayout | None = None,
                    root_extension: float = ROOT_EXTENSION, arm_elements: int = 8,
                    shear: bool = True, elements_per_hinge: int | None = None,
                    notch_correction: bool = True, member_patch: bool = True,
                    material: Material | None = None) -> tuple:
    """(BeamModel, info) of the DBMA, with the continuum mesh's groups:
    "fixed" (the mounting face), "input_a", "input_b" and "input" (the pad faces), "output"
    (the top of member 4), each with its face's extent. info: "input_a" / "input_b" (masters of the left /
    right input members, on their pads' faces), "output" (master of member 4, on its top
    face), "ground" (the bottom of member 11, its mounting face), "hinges" {label: (first,
    last element) of the hinge-arm-hinge chain}, "hinge_elements" (the 16 hinges' elements,
    their root extensions included). elements_per_hinge: default LEAF_ELEMENTS for a leaf,
    PROFILE_ELEMENTS for a notch or filleted profile. ``notch_correction``: a notch or
    filleted hinge's beam corrected by its own 2-D model
    (:func:`flexfem.reduced.hinge_patch.notch_factors`; False: plain beam theory).
    ``member_patch``: the input members where their pads bear on them as 2-D patches
    (:mod:`.member_patch`; a linear superelement each); False: as rigid blocks on short pad
    beams (the model the spatial beam lifts). ``material``: default E, nu, rho of ``p``."""
    layout = layout or DBMALayout()
    check_layout(p, layout)
    root_extension = check_root_extension(root_extension)
    q = quarter_rects(p, layout)
    J, pad, out4 = q[0], q[1], q[2]
    fn, breaks = _hinge_fn(p, layout)
    n_hinge = elements_per_hinge or (LEAF_ELEMENTS if layout.hinge_profile == "leaf"
                                     else PROFILE_ELEMENTS)
    blocks = (p.c, p.c)  # the height of the faces the hinges enter (arm ends; members, ~)
    factors = None  # a notch or filleted profile: its own 2-D model's correction
    if notch_correction and layout.hinge_profile != "leaf":
        factors = notch_factors(layout.hinge_profile, p.l, p.b, layout.hinge_fillet_radius,
                                p.nu)
    hinge = profile_beam((0.0, 0.0), (p.l, 0.0), fn, p.d, breaks, n_hinge, root_extension,
                         blocks, vectorized=True, factors=factors)
    x_out, x_in, l, h = p.ls / 2, p.ls / 2 + 2 * p.l + p.e, p.l, p.h
    bld, links, supers = _Builder(), [], []
    slaves = {"input_a": [], "input_b": [], "output": []}
    ground, spans, in_hinges = [], {}, []
    for sx, sy in QUARTERS:
        for row, yc in (("i", layout.arm_gap + p.c / 2), ("o", p.ll - p.c / 2)):
            ya, yb = sy * (yc - h / 2), sy * (yc + h / 2)
            e0 = len(bld.sections)
            ha = bld.add(_placed(hinge, (sx * x_out, ya), (sx * (x_out + l), ya)))
            e1 = len(bld.sections)
            arm = bld.add(beam_chain([(sx * (x_out + l), sy * yc), (sx * (x_in - l), sy * yc)],
                                     Section.rect(p.d, p.c), arm_elements))
            e2 = len(bld.sections)
            hb = bld.add(_placed(hinge, (sx * (x_in - l), yb), (sx * x_in, yb)))
            in_hinges += [*range(e0, e1), *range(e2, len(bld.sections))]
            spans[f"{sx:+d}{sy:+d}{row}"] = (e0, len(bld.sections))
            links += [RigidLink(arm[0], (ha[1],)), RigidLink(arm[-1], (hb[0],))]
            (slaves["output"] if sy > 0 else ground).append((ha[0], ya))
            slaves["input_b" if sx > 0 else "input_a"].append((hb[1], yb))
    for name, sx in (("input_a", -1), ("input_b", 1)):
        master = _input_member(bld, links, supers, p, layout, J, pad, sx, slaves[name],
                               root_extension, member_patch)
        slaves[name] = master
    top = _column(bld, links, 0.0, (out4.y0, out4.y1), p.ls, p.d, slaves["output"],
                  6 / p.ll)
    base = _column(bld, links, 0.0, (-out4.y1, -out4.y0), p.ls, p.d, ground, 6 / p.ll)
    master, ground = top[out4.y1], [base[-out4.y1]]
    pads = (0.0, layout.pad_height)
    model = BeamModel(np.vstack(bld.nodes), np.vstack(bld.elements), bld.sections,
                      material or Material("dbma_steel", p.E, p.nu, p.rho), shear=shear,
                      rigid_links=links, superelements=supers,
                      groups={"fixed": BeamGroup(ground, (p.ls, 0.0)),
                              "input_a": BeamGroup(slaves["input_a"], pads),
                              "input_b": BeamGroup(slaves["input_b"], pads),
                              "input": BeamGroup((slaves["input_a"], slaves["input_b"]), pads),
                              "output": BeamGroup(master, (p.ls, 0.0))})
    return model, {"input_a": slaves["input_a"], "input_b": slaves["input_b"],
                   "output": master, "ground": ground, "hinges": spans,
                   "hinge_elements": np.array(in_hinges)}


def dbma_beam3d_model(p: DBMAParams, layout: DBMALayout | None = None,
                      root_extension: float = ROOT_EXTENSION) -> tuple:
    """(Beam3DModel, info) of the DBMA for its out-of-plane modes: the planar model with block
    input members (:func:`dbma_beam_model`, member_patch=False, same info; a superelement has
    no out-of-plane part) lifted into 3-D, every section the rectangle of its in-plane depth
    and the plate thickness d (:func:`..spatial_beam.lifted_model`)."""
    planar, info = dbma_beam_model(p, layout, root_extension, member_patch=False)
    return lifted_model(planar, p.d), info
