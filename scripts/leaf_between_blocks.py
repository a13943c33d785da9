"""A leaf hinge between two blocks, flexfem's 3-D solid beside the lifted beam model: the
numbers of docs/beam_validation_3d.md, "The strong axis's roots" (strong-axis bending and torsion).

    .venv/bin/python scripts/leaf_between_blocks.py 0.6,4.41,10,10,20    # t,l,w,H,Lb in mm

Each argument is a specimen: leaf t x l x w between two H x Lb x w blocks, the near block's
end clamped, the far block's end face rigid. The solid is the drawing's quadrilaterals
extruded through w in layers of Q2 hexahedra that grow by 1.35 from FIRST_LAYER at both faces
(about a minute and up to 12 GB a specimen at t = 0.6 mm; a thinner leaf needs more). It
prints the 6 x 6 diagonal of beam / solid - 1 (x, y, z, r_x, r_y, r_z), and the hinge's
effective torsion factor on its Saint-Venant J beside Vlasov's rigid-end one.
"""
import sys

import numpy as np

FIRST_LAYER = 0.3e-3  # m, the layers' thickness at the faces
ACROSS = 4  # elements across the leaf's thickness


def solid(t, l, w, H, Lb) -> np.ndarray:
    from flexfem.fem import Fixed, Material, Model, Solid3D, compliance_matrix, gmsh_session
    from flexfem.fem import mesh_from_gmsh

    sizes = [FIRST_LAYER / w]
    while sum(sizes) < 0.5:
        sizes.append(sizes[-1] * 1.35)
    half = np.array(sizes) * 0.5 / sum(sizes)
    heights = np.cumsum(np.concatenate([half, half[::-1]]))
    with gmsh_session("leaf_between_blocks") as gmsh:
        occ, field = gmsh.model.occ, gmsh.model.mesh.field
        near = occ.addRectangle(-Lb, -H / 2, 0, Lb, H)
        leaf = occ.addRectangle(0, -t / 2, 0, l, t)
        far = occ.addRectangle(l, -H / 2, 0, Lb, H)
        occ.fragment([(2, near)], [(2, leaf), (2, far)])
        occ.synchronize()
        box = field.add("Box")
        for key, value in (("VIn", t / ACROSS), ("VOut", H / 4), ("XMin", -t), ("XMax", l + t),
                           ("YMin", -t), ("YMax", t), ("ZMin", -1), ("ZMax", 1),
                           ("Thickness", 3 * H)):
            field.setNumber(box, key, value)
        field.setAsBackgroundMesh(box)
        for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                    "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(key, 0)
        for key, value in (("Mesh.RecombineAll", 1), ("Mesh.Algorithm", 6),
                           ("Mesh.SubdivisionAlgorithm", 1)):
            gmsh.option.setNumber(key, value)
        occ.extrude(gmsh.model.getEntities(2), 0, 0, w, numElements=[1] * len(heights),
                    heights=list(heights / heights[-1]), recombine=True)
        occ.synchronize()
        gmsh.model.addPhysicalGroup(3, [tag for _, tag in gmsh.model.getEntities(3)], name="body")
        eps = 1e-6  # above OpenCASCADE's bounding-box padding
        for name, x in (("fixed", -Lb), ("tip", l + Lb)):
            faces = gmsh.model.getEntitiesInBoundingBox(x - eps, -H, -eps, x + eps, H, w + eps, 2)
            gmsh.model.addPhysicalGroup(2, [tag for _, tag in faces], name=name)
        gmsh.model.mesh.generate(3)
        mesh = mesh_from_gmsh(gmsh)
    model = Model(mesh, Material("steel", 200e9, 0.3, 7800.0), Solid3D(), order=2)
    print(f"  solid: {model.basis.N} DOFs", flush=True)
    return compliance_matrix(model, [Fixed("fixed")], "tip", point=(l + Lb, 0.0, w / 2)).matrix


def beam(t, l, w, H, Lb, j_factor: float) -> np.ndarray:
    """The lifted beam model of the specimen (``leaf_between_blocks``), the leaf's J times
    ``j_factor``."""
    from flexfem.fem.beam.spatial import compliance3d
    from flexfem.fem.beam.supports import NodeFixed
    from flexfem.reduced.spatial import lifted_model
    from flexfem.reduced.specimen import leaf_between_blocks
    from flexfem.reduced.torsion import TorsionScaled

    planar, root, tip, leaf = leaf_between_blocks(t, l, w, H, Lb)
    factors = np.ones(len(planar.elements))
    factors[leaf] = j_factor
    model = TorsionScaled(lifted_model(planar, w), factors)
    return compliance3d(model, [NodeFixed(root)], tip)


def main(argv) -> None:
    from flexfem.reduced.torsion import vlasov_factor

    for spec in argv:
        t, l, w, H, Lb = (float(v) * 1e-3 for v in spec.split(","))
        print(f"leaf {t * 1e3:g} x {l * 1e3:g} x {w * 1e3:g} mm, blocks {H * 1e3:g} x "
              f"{Lb * 1e3:g} mm", flush=True)
        C = np.diag(solid(t, l, w, H, Lb))
        vlasov = vlasov_factor(l, t, w, 0.3)
        with_v, plain = np.diag(beam(t, l, w, H, Lb, vlasov)), np.diag(beam(t, l, w, H, Lb, 1.0))
        print("  beam (Vlasov) / solid - 1, x y z rx ry rz:",
              " ".join(f"{v:+.2%}" for v in with_v / C - 1))
        # the torsion compliance is the blocks' plus the leaf's over its J factor
        leaf = (plain[3] - with_v[3]) / (1 - 1 / vlasov)
        print(f"  leaf's torsion factor: solid {leaf / (C[3] - (plain[3] - leaf)):.3f}, "
              f"Vlasov's rigid ends {vlasov:.3f}")


if __name__ == "__main__":
    main(sys.argv[1:])
