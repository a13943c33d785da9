"""Problems shared by the topology optimisation tests (imported by name, as tests/fem's
meshes.py is: pytest puts this folder on the path)."""
import pytest

from flexfem.topopt import (Constraint, Grid, Load, Optimizer, Problem, Region, Response,
                            Spring, Support, optimize)


def mbb(nelx=60, nely=20, filter_kind="sensitivity", radius=1.5, **kw) -> Problem:
    """top88's MBB half-beam, unit elements."""
    return Problem(Grid(nelx, nely, float(nelx), float(nely)), Response("compliance"),
                   filter_kind=filter_kind, radius=radius,
                   supports=(Support(Region("edge", "left"), ("x",)),
                             Support(Region("point", (float(nelx), 0.0)), ("y",))),
                   loads=(Load(Region("point", (0.0, float(nely))), (0.0, -1.0)),),
                   constraints=(Constraint(Response("volume"), upper=0.5),),
                   optimizer=kw.pop("optimizer", Optimizer("oc", 0.2, 2000, 0.01)), **kw)


def inverter(nelx=40, nely=20, filter_kind="density", iterations=150, **kw) -> Problem:
    """The force inverter's upper half (symmetry line at the bottom edge)."""
    return Problem(Grid(nelx, nely, float(nelx), float(nely)),
                   Response("displacement", "output"), filter_kind=filter_kind, radius=1.5,
                   supports=(Support(Region("edge", "bottom"), ("y",)),
                             Support(Region("box", ((0.0, nely - 1.0), (0.0, float(nely)))),
                                     ("x", "y"))),
                   loads=(Load(Region("point", (0.0, 0.0)), (1.0, 0.0)),),
                   springs=(Spring("input", Region("point", (0.0, 0.0)), "x", 0.1),
                            Spring("output", Region("point", (float(nelx), 0.0)), "x", 0.1)),
                   constraints=kw.pop("constraints", (Constraint(Response("volume"), upper=0.3),)),
                   optimizer=Optimizer("mma", 0.2, iterations, 0.01), **kw)


def interrupt_at(problem: Problem, out_dir, iteration: int) -> None:
    """Run ``problem`` into ``out_dir`` and stop it with Ctrl-C at ``iteration``."""
    def stop(k, *_):
        if k == iteration:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        optimize(problem, out_dir=out_dir, progress=stop)
