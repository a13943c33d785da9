"""flexfem.topopt: density-based topology optimisation of 2-D plane-stress structures and
compliant mechanisms on a structured grid of bilinear quads (SIMP or RAMP, sensitivity,
density or Helmholtz filter, Heaviside projection, the robust formulation (a minimum
hinge width), several load cases, compliance,
displacement, volume, lowest-eigenfrequency and stress-norm responses, optimality criteria
or MMA).

    problem = load_problem("examples/topopt/mbb.toml")
    result = optimize(problem, out_dir="mbb_out")    # resumable: rerun to continue
    result.objective, result.iterations, result.summary()
"""
from .grid import Grid
from .interpolation import Interpolation
from .optimize import Result, optimize
from .problem import (Constraint, Load, Optimizer, Passive, Problem, Response, Spring,
                      Support)
from .problem_file import load_problem, problem_from_dict
from .projection import Projection
from .regions import Region
from .robust import Robust

__all__ = ["Constraint", "Grid", "Interpolation", "Load", "Optimizer", "Passive", "Problem",
           "Projection", "Region", "Response", "Result", "Robust", "Spring", "Support", "load_problem",
           "optimize", "problem_from_dict"]
