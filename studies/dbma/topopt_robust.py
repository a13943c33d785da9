"""The DBMA-envelope amplifier with a minimum hinge width (the robust formulation,
topopt/robust.py): its constraints read off flexfem's own DBMA model in the same run (the
whole part's k_in and peak von Mises stress at 800 N, the quarter's working mode read by the
optimised shape's code), optimised, verified on its body-fitted shape with its necks, and
stored as a small JSON + npz (examples/topopt/dbma_amplifier.py writes them) that the quick
report reads. SI units."""
import json
from pathlib import Path
import time

import numpy as np

from ...topopt import optimize
from ...topopt.amplifier import amplifier_problem, dbma_quarter, shape_readings, verify_amplifier
from ...topopt.neck_check import detect_width, neck_report
from .analysis import analyze_dbma

FORCE = 800.0                    # N, the actuator's force (the top of the paper's Fig. 14)
K_ACTUATOR, K_OUTPUT = 4e7, 1e5  # N/m, the actuator and the output's load (full part)
ELEMENT, SIZE = 0.2e-3, 0.25e-3  # m: the grid's square elements, the body-fitted triangles
QUARTER_GRID = 0.5e-3            # m: the grid whose groups read the DBMA's quarter
ITERATIONS = 400
THRESHOLD = 0.5                  # the blueprint's level (the intermediate design's threshold)
STORED = Path(__file__).resolve().parents[2] / "examples" / "topopt" / "dbma_amplifier_robust"


def min_hinge() -> float:
    """The least hinge width (m): the DBMA's own leaf thickness b (geometry/dbma)."""
    from ...geometry.dbma.params import paper_design

    return paper_design().b


def dbma_limits(full: dict | None = None) -> dict:
    """The constraints as the DBMA meets them, computed by flexfem: ``k_in_min`` (N/m) and
    ``stress_max`` (Pa, its peak von Mises) of the whole part's 2-D FEM at FORCE, ``fn_min``
    (Hz) the working mode of its quarter read by shape_readings (as the optimised shape is
    read); ``quarter``: those readings."""
    full = full or analyze_dbma(dim=2, force=FORCE)
    # the DBMA's own envelope (its output face at its full height) on the plain grid
    base = amplifier_problem(FORCE, full["k_in"], K_ACTUATOR, K_OUTPUT, element=QUARTER_GRID)
    quarter = shape_readings(base, dbma_quarter(), SIZE)
    return {"k_in_min": float(full["k_in"]), "stress_max": float(full["max_von_mises"]),
            "fn_min": float(quarter["fn_working"]), "R_dbma": float(full["R_fem"]),
            "quarter": quarter}


def robust_problem(limits: dict, iterations: int = ITERATIONS, element: float = ELEMENT):
    """The amplifier problem at the DBMA's limits with min_hinge = the DBMA's b."""
    return amplifier_problem(FORCE, limits["k_in_min"], K_ACTUATOR, K_OUTPUT, element=element,
                             iterations=iterations, fn_min=limits["fn_min"],
                             stress_max=limits["stress_max"], min_hinge=min_hinge(),
                             own_stiffness=True)


def _plain(value):
    """JSON-able numbers of ``value`` (numpy scalars and arrays as floats and lists)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v) for v in value]
    if isinstance(value, (np.integer, int)) and not isinstance(value, bool):
        return int(value)
    if isinstance(value, (np.floating, float)):
        return float(value)
    return value


def verify_design(result) -> tuple:
    """(verify_amplifier's readings, the necks with their stresses) of a finished design: the
    outline of the blueprint at THRESHOLD as it is, no closing (the robust design has no
    one-node hinges to close, and a closing of the hinge's radius would fill its voids
    narrower than about twice that), meshed at SIZE."""
    verified = verify_amplifier(result, threshold=THRESHOLD, neck=0.0, size=SIZE)
    problem = result.problem
    return verified, neck_report(problem, verified["outline"], detect_width(problem), SIZE)


def large_reading(problem, density) -> dict:
    """{'small', 'large'}: u_in, u_out (m) and R = u_out / u_in of the density model with
    its springs at FORCE, with small and with large displacements (the robust problem's
    large-displacement solver, topopt/large_displacement.py, 5 increments from zero)."""
    from dataclasses import replace

    from ...topopt.large_displacement import Nonlinear
    from ...topopt.model import Discrete

    out = {}
    for name, nonlinear in (("small", None), ("large", Nonlinear(steps=5))):
        p = replace(problem, nonlinear=nonlinear, constraints=problem.constraints[:1])
        disp = Discrete(p).responses(density)[1]
        out[name] = {"u_in": disp["input"], "u_out": disp["output"],
                     "R": disp["output"] / disp["input"]}
    return out


def reverify(stem=STORED) -> dict:
    """The stored design verified again by :func:`verify_design` (its record updated)."""
    from types import SimpleNamespace

    from ...topopt.model import Discrete

    record = read_stored(stem)
    density = record.pop("density")
    problem = robust_problem(record["limits"], record["problem"]["iterations"],
                             record["problem"]["element"])
    d = Discrete(problem)
    u = d.system.solve(problem.interpolation.modulus(density), d.forces)[:, 0]
    result = SimpleNamespace(problem=problem, density=density, displacements={
        n: float(v @ u) for n, v in d.spring_vectors.items()})
    verified, necks = verify_design(result)
    record.update(verified={k: v for k, v in verified.items() if k != "outline"},
                  necks=necks, large=large_reading(problem, density))
    record["problem"]["close"] = 0.0
    return {"record": _plain(record), "density": density}


def run_robust(limits: dict, out_dir=None, progress=None, iterations: int = ITERATIONS,
               element: float = ELEMENT, start=None) -> dict:
    """Optimise, verify (:func:`verify_design`) and measure the necks: the record the
    report shows (JSON-able) and the physical densities. ``start``: (design variables,
    beta, a note saying where they come from) to begin from instead of the uniform start."""
    clock = time.perf_counter()
    problem = robust_problem(limits, iterations, element)
    result = optimize(problem, out_dir=out_dir, progress=progress,
                      start=None if start is None else start[:2])
    seconds = time.perf_counter() - clock
    verified, necks = verify_design(result)
    record = {"problem": {"element": element, "nelx": problem.grid.nelx,
                          "nely": problem.grid.nely, "min_hinge": min_hinge(),
                          "filter_radius": problem.radius, "thresholds":
                          list(problem.robust.thresholds), "iterations": iterations,
                          "size": SIZE, "threshold": THRESHOLD, "close": 0.0, "force": FORCE,
                          "k_actuator": K_ACTUATOR, "k_output": K_OUTPUT},
              "limits": {k: v for k, v in limits.items() if k != "quarter"},
              "quarter": {k: v for k, v in limits["quarter"].items()},
              "result": result.summary(), "seconds": seconds,
              "verified": {k: v for k, v in verified.items() if k != "outline"},
              "necks": necks, "large": large_reading(problem, result.density)}
    if start is not None:
        record["start"] = {"beta": start[1], "from": start[2]}
    return {"record": _plain(record), "density": result.density, "result": result,
            "verified": verified}


def write_stored(run: dict, stem=STORED) -> list:
    """stem.json (the record) and stem.npz (the physical densities): the paths."""
    stem = Path(stem)
    json_path, npz_path = stem.with_suffix(".json"), stem.with_suffix(".npz")
    json_path.write_text(json.dumps(run["record"], indent=1) + "\n")
    np.savez_compressed(npz_path, density=run["density"])
    return [json_path, npz_path]


def read_stored(stem=STORED) -> dict:
    """The stored record (with ``density`` from the npz)."""
    stem = Path(stem)
    record = json.loads(stem.with_suffix(".json").read_text())
    with np.load(stem.with_suffix(".npz"), allow_pickle=False) as data:
        record["density"] = data["density"]
    return record


# a density-model constraint within this fraction of its bound counts as binding
ACTIVE = 0.02


def density_margins(record: dict) -> dict:
    """{constraint: value / bound - 1, positive beyond the bound} of the density model (the
    worst of its three designs): 'volume', 'k_in', 'frequency', 'stress'."""
    c, lim = record["result"]["constraints"], record["limits"]
    f = record["problem"]["force"] / 2
    u_in = c.get("displacement_input_without_springs", c["displacement_input"])
    checks = (("volume", c["volume"], 0.3, 1), ("k_in", u_in, f / lim["k_in_min"], 1),
              ("frequency", c["frequency"], lim["fn_min"], -1),
              ("stress", c["stress"], lim["stress_max"], 1))
    return {name: sign * (value / bound - 1.0) for name, value, bound, sign in checks}


def density_binding(record: dict) -> list:
    """The density model's constraints within ACTIVE of their bounds (binding)."""
    return [k for k, m in density_margins(record).items() if abs(m) <= ACTIVE]


def density_violated(record: dict) -> list:
    """The density model's constraints beyond their bounds by more than ACTIVE."""
    return [k for k, m in density_margins(record).items() if m > ACTIVE]


def fitted_checks(record: dict) -> dict:
    """{constraint: (body-fitted value, the DBMA's limit, met)} on the body-fitted shape:
    k_in (N/m) >= the DBMA's, the working mode (Hz, pad held) >= the DBMA quarter's, the peak
    von Mises stress (Pa, triangles of SIZE) <= the DBMA's peak."""
    v, lim = record["verified"], record["limits"]
    return {"k_in": (v["k_in"], lim["k_in_min"], v["k_in"] >= lim["k_in_min"]),
            "working mode": (v["fn_working"], lim["fn_min"], v["fn_working"] >= lim["fn_min"]),
            "stress": (v["peak_stress"], lim["stress_max"],
                       v["peak_stress"] <= lim["stress_max"])}


def verdict(record: dict, r_dbma: float) -> dict:
    """Whether the body-fitted design beats the DBMA's R (``r_dbma``, read in this run) with
    every constraint met on its shape and no neck of the outline under min_hinge; else by how
    much it falls short (``shortfall``, a fraction of r_dbma) and which constraints bind or
    are violated (density model) or fail (shape; 'min_hinge' for a neck too narrow)."""
    v = record["verified"]
    checks = fitted_checks(record)
    failed = [name for name, (_, _, ok) in checks.items() if not ok]
    narrowest = min((n["width"] for n in record["necks"]), default=None)
    hinge = record["problem"].get("min_hinge", 0.0)
    if narrowest is not None and narrowest < hinge:
        failed.append("min_hinge")
    r = v["R_fitted"]
    return {"beats": bool(r > r_dbma and not failed), "R_fitted": r, "R_dbma": float(r_dbma),
            "shortfall": max(0.0, 1.0 - r / r_dbma), "binding": density_binding(record),
            "violated": density_violated(record), "failed": failed,
            "fitted_over_density": r / v["R_density"], "narrowest_neck": narrowest}
