"""Write data/notch_factors.toml: a circular notch's 2-D correction of its beam model
(flexfem.reduced.hinge_patch.patch_factors) over t/R and Poisson's ratio.

    .venv/bin/python scripts/notch_factor_table.py      # about a minute

The table is flexfem's own computation, not a published source: each entry is the notch with
a stub of its end height at each end, rigid beyond, in plane stress (P2, NECK_ELEMENTS_TABLE
triangles across the local thickness) against the same as beams.
tests/geometry/test_hinge_patch.py recomputes entries and checks the interpolation between
them.
"""
from pathlib import Path
import time

T_OVER_R = (0.02, 0.03, 0.05, 0.07, 0.1, 0.14, 0.2, 0.28, 0.4, 0.56, 0.8, 1.1, 1.5, 2.0)
NU = (0.2, 0.25, 0.3, 0.35, 0.4)
NECK_ELEMENTS_TABLE = 24
FIELDS = ("bending", "shear", "axial", "kt_bending", "kt_tension")


def main() -> None:
    from flexfem.reduced.hinge_patch import patch_factors

    start = time.perf_counter()
    rows = {name: [] for name in FIELDS}
    b = 1e-3
    for nu in NU:
        found = [patch_factors("circular", 2 * b / t, b, b, nu, NECK_ELEMENTS_TABLE)
                 for t in T_OVER_R]
        for name in FIELDS:
            rows[name].append([getattr(f, name) for f in found])
        print(f"nu = {nu}: {time.perf_counter() - start:.0f} s", flush=True)
    fmt = lambda values: "[" + ", ".join(f"{v:.9g}" for v in values) + "]"
    lines = [
        "# A circular notch hinge's 2-D correction of its beam model, computed by flexfem:",
        "# scripts/notch_factor_table.py (flexfem.reduced.hinge_patch.patch_factors), not a",
        "# published source. The notch with a stub of its end height (as long) at each end, rigid",
        "# beyond, in plane stress (P2 triangles, "
        f"{NECK_ELEMENTS_TABLE} across the local thickness, finer at",
        "# the neck's surface) against the same as beams (Paros-Weisbord's plane sections):",
        "# bending, shear and axial multiply E I, kappa G A and E A on the notch's beam",
        "# elements; kt_bending and kt_tension are the neck's peak von Mises stress over the",
        "# nominal 6 M / (w b^2) and N / (w b).",
        "# Rows: nu; columns: t_over_r = b / R (neck b, notch radius R = l / 2).",
        "",
        "[circular_notch]",
        f"neck_elements = {NECK_ELEMENTS_TABLE}",
        f"t_over_r = {fmt(T_OVER_R)}",
        f"nu = {fmt(NU)}",
    ]
    for name in FIELDS:
        lines.append(f"{name} = [")
        lines += [f"    {fmt(row)}," for row in rows[name]]
        lines.append("]")
    target = Path(__file__).resolve().parent.parent / "data" / "notch_factors.toml"
    target.write_text("\n".join(lines) + "\n")
    print(f"wrote data/notch_factors.toml in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
