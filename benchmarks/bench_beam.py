"""Time the reduced beam model (flexfem.fem.beam) on a parallel leaf-spring guide: a linear
design point and a nonlinear stroke. Not a test: prints a table (times are medians).

    .venv/bin/python benchmarks/bench_beam.py                # 50 + 50 elements, 20 steps
    .venv/bin/python benchmarks/bench_beam.py --elements 200 --steps 40 --repeat 5
    .venv/bin/python benchmarks/bench_beam.py --continuum   # + beam vs 2-D continuum (~10 s)

Guide: two steel leaves 50 mm x 10 mm x 0.5 mm, 30 mm apart, clamped at x = 0; a rigid stage
(rigid link) at x = 50 mm. Linear design point: build the model, solve the static
deflection under 1 N, the 3x3 stage compliance and the first 3 modes. Stroke: the stage
moved 5 mm (10 % of L) sideways by a prescribed DOF, in ``--steps`` load steps.

``--continuum``: one hinge (leaf or circular notch, l/b = 2.5 .. 20, b = 0.5 mm, w = 5 mm)
between two 10 mm x 5 mm blocks, clamped at one block's end, 1 N sideways on the other's:
the tip deflection of the beam model (blocks as beams, hinge from its profile, shear on)
against flexfem's plane-stress P2 model of ``mesh_hinge_specimen``, with both times.
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np

from flexfem.fem import Material
from flexfem.fem.beam import (BeamModel, NodalLoad, RigidLink, Section, beam_chain,
                              beam_from_profile, compliance, solve_beam_modes,
                              solve_beam_nonlinear, solve_beam_static)
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed

L, W, T, GAP, STROKE = 0.05, 0.01, 0.5e-3, 0.03, 0.005
STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)


def guide(n_per_leaf: int):
    """(model, supports, stage node) of the parallel guide with n_per_leaf elements a leaf."""
    a = beam_chain([(0, 0), (L, 0)], Section.rect(W, T), n_per_leaf)
    b = beam_chain([(0, GAP), (L, GAP)], Section.rect(W, T), n_per_leaf)
    g = a.join(b)
    nodes = np.vstack([g.nodes, [(L, GAP / 2)]])
    stage = len(nodes) - 1
    model = BeamModel(nodes, g.elements, g.sections, STEEL,
                      rigid_links=[RigidLink(stage, (g.point_nodes[1], g.point_nodes[3]))])
    return model, [NodeFixed((g.point_nodes[0], g.point_nodes[2]))], stage


def linear_point(n_per_leaf: int) -> dict:
    model, supports, stage = guide(n_per_leaf)
    static = solve_beam_static(model, supports, [NodalLoad(stage, fy=1.0)])
    C = compliance(model, supports, stage)
    modes = solve_beam_modes(model, supports, n=3)
    return {"k_y N/m": 1.0 / C[1, 1], "f1 Hz": modes.frequencies_hz[0],
            "stress MPa/N": static.max_stress / 1e6}


def stroke(n_per_leaf: int, steps: int) -> dict:
    model, supports, stage = guide(n_per_leaf)
    res = solve_beam_nonlinear(model, supports + [NodePrescribed(stage, "y", STROKE)], steps=steps)
    return {"force N": res.final.reactions[stage][1], "shortening um": -res.final.q[stage, 0] * 1e6,
            "iterations": sum(res.iterations), "stress MPa": res.final.max_stress / 1e6}


def hinge_beam(profile: str, l: float, b: float, w: float, block: tuple):
    """Tip deflection (m) under 1 N of the beam model of a hinge between two blocks."""
    from flexfem.geometry.hinge_profiles import profile_thickness

    H, Lb = block
    thickness = lambda s: float(profile_thickness(profile, l, b, 0.5e-3, s))
    g = beam_chain([(-Lb, 0), (0, 0)], Section.rect(w, H), 4)
    g = g.join(beam_from_profile((0, 0), (l, 0), thickness, w, 40))
    g = g.join(beam_chain([(l, 0), (l + Lb, 0)], Section.rect(w, H), 4))
    model = BeamModel(g.nodes, g.elements, g.sections, STEEL, shear=True)
    tip = g.node_at((l + Lb, 0))
    return solve_beam_static(model, [NodeFixed(g.node_at((-Lb, 0)))],
                             [NodalLoad(tip, fy=1.0)]).q[tip, 1]


def continuum_comparison():
    """Rows (profile, l/b, FE deflection, FE s, beam deflection, beam s, beam / FE - 1)."""
    from flexfem.fem import Fixed as FEFixed, Force, Model, PlaneStress, solve_static
    from flexfem.geometry.hinge_profiles import mesh_hinge_specimen

    w, b, block = 5e-3, 0.5e-3, (10e-3, 5e-3)
    rows = []
    for profile in ("leaf", "circular"):
        for ratio in (20, 10, 5, 2.5):
            l = ratio * b
            if profile == "circular" and b + l >= block[0]:
                continue
            start = time.perf_counter()
            mesh = mesh_hinge_specimen(l, b, profile, block_height=block[0],
                                       block_length=block[1], hinge_elements=4)
            model = Model(mesh, STEEL, PlaneStress(w), order=2)
            fe = solve_static(model, [FEFixed("fixed")], [Force("tip", (0.0, 1.0))])
            fe_v, fe_s = fe.mean_displacement("tip")[1], time.perf_counter() - start
            beam_s, _, beam_v = timed(lambda: hinge_beam(profile, l, b, w, block), 3)
            rows.append((profile, ratio, fe_v, fe_s, beam_v, beam_s, beam_v / fe_v - 1))
    return rows


def timed(fn, repeat):
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times), out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--elements", type=int, default=50, help="elements per leaf")
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--continuum", action="store_true",
                        help="also compare hinges with the 2-D continuum model")
    args = parser.parse_args(argv)
    n = args.elements
    stroke(n, args.steps)  # warm-up (imports, caches)
    rows = [("linear design point", *timed(lambda: linear_point(n), args.repeat)),
            (f"nonlinear stroke, {args.steps} steps",
             *timed(lambda: stroke(n, args.steps), args.repeat))]
    load = os.getloadavg()[0]
    print(f"parallel guide, {2 * n} elements ({3 * (2 * n + 3)} DOFs), median of "
          f"{args.repeat}; load average {load:.2f} on {os.cpu_count()} cores\n")
    print("| case | median s | min s | result |\n|---|---|---|---|")
    for name, med, best, out in rows:
        text = ", ".join(f"{k} {v:.4g}" for k, v in out.items())
        print(f"| {name} | {med:.4f} | {best:.4f} | {text} |")
    if args.continuum:
        print("\n| hinge | l/b | 2-D FE m/N | FE s | beam m/N | beam s | beam / FE - 1 |\n"
              "|---|---|---|---|---|---|---|")
        for p, r, fv, fs, bv, bs, err in continuum_comparison():
            print(f"| {p} | {r:g} | {fv:.4e} | {fs:.2f} | {bv:.4e} | {bs:.4f} | {err:+.1%} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
