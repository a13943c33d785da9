"""Write guide.step: a 3-D parallel leaf-spring guide as a CAD file would give it (one solid,
no groups), for the model file guide_step.toml. Run: python make_guide_step.py

Leaves of length L = 20 mm, thickness t = 1 mm and width w = 3 mm (z), 16 mm apart, between a
base (y < 0) and a stage (y > L). STEP stores millimetres; flexfem reads it in metres.
"""
import gmsh

L, t, w, d, hb, hs, m = 0.02, 0.001, 0.003, 0.016, 0.004, 0.006, 0.004


def write_guide_step(path: str = "guide.step") -> None:
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")  # model in m, file in mm
        occ = gmsh.model.occ
        e = d / 2 + t / 2 + m
        base = occ.addBox(-e, -hb, 0, 2 * e, hb, w)
        stage = occ.addBox(-e, L, 0, 2 * e, hs, w)
        leaves = [occ.addBox(x - t / 2, 0, 0, t, L, w) for x in (-d / 2, d / 2)]
        occ.fuse([(3, base)], [(3, stage)] + [(3, leaf) for leaf in leaves])
        occ.synchronize()
        gmsh.write(path)
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    write_guide_step()
