"""Problems shared by the topology optimisation tests (imported by name, as tests/fem's
meshes.py is: pytest puts this folder on the path)."""
import pytest

from flexfem.topopt import (Constraint, Grid, Load, Optimizer, Passive, Problem, Region,
                            Response, Spring, Support, optimize)


def mbb(nelx=60, nely=20, filter_kind="sensitivity", radius=1.5, **kw) -> Problem:
    """top88's MBB half-beam, unit elements; ``second_load``: a load case 2 of this force
    (N) at the top right corner."""
    loads = (Load(Region("point", (0.0, float(nely))), (0.0, -1.0)),)
    if "second_load" in kw:
        loads += (Load(Region("point", (float(nelx), float(nely))), kw.pop("second_load"), 2),)
    return Problem(Grid(nelx, nely, float(nelx), float(nely)),
                   kw.pop("objective", Response("compliance")),
                   filter_kind=filter_kind, radius=radius,
                   supports=(Support(Region("edge", "left"), ("x",)),
                             Support(Region("point", (float(nelx), 0.0)), ("y",))),
                   loads=loads,
                   constraints=kw.pop("constraints", (Constraint(Response("volume"), upper=0.5),)),
                   optimizer=kw.pop("optimizer", Optimizer("oc", 0.2, 2000, 0.01)), **kw)


def inverter(nelx=40, nely=20, filter_kind="density", iterations=150, **kw) -> Problem:
    """The force inverter's upper half (symmetry line at the bottom edge); ``second_load``:
    a load case 2 of this force (N) at the top right corner."""
    loads = (Load(Region("point", (0.0, 0.0)), (1.0, 0.0)),)
    if "second_load" in kw:
        loads += (Load(Region("point", (float(nelx), float(nely))), kw.pop("second_load"), 2),)
    return Problem(Grid(nelx, nely, float(nelx), float(nely)),
                   Response("displacement", "output"), filter_kind=filter_kind, radius=1.5,
                   supports=(Support(Region("edge", "bottom"), ("y",)),
                             Support(Region("box", ((0.0, nely - 1.0), (0.0, float(nely)))),
                                     ("x", "y"))),
                   loads=loads,
                   springs=(Spring("input", Region("point", (0.0, 0.0)), "x", 0.1),
                            Spring("output", Region("point", (float(nelx), 0.0)), "x", 0.1)),
                   constraints=kw.pop("constraints", (Constraint(Response("volume"), upper=0.3),)),
                   optimizer=Optimizer("mma", 0.2, iterations, 0.01), **kw)


def lbracket(stress_max=1e9, iterations=200) -> Problem:
    """The L-bracket: 50 x 50 unit elements, the top-right 30 x 30 void, clamped along the
    top of its arm, a unit force down spread over the right end (y 15 to 20); volume 0.4,
    the stress norm (P = 8, q = 0.5) at most ``stress_max``; density filter r = 2, MMA."""
    return Problem(Grid(50, 50, 50.0, 50.0), Response("compliance"), filter_kind="density",
                   radius=2.0, supports=(Support(Region("box", ((0.0, 49.99), (20.0, 50.0)))),),
                   loads=(Load(Region("box", ((49.99, 15.0), (50.0, 20.0))), (0.0, -1.0)),),
                   passive=(Passive(Region("box", ((20.0, 20.0), (50.0, 50.0))), "void"),),
                   constraints=(Constraint(Response("volume"), upper=0.4),
                                Constraint(Response("stress"), upper=stress_max)),
                   optimizer=Optimizer("mma", 0.2, iterations, 0.01))


def interrupt_at(problem: Problem, out_dir, iteration: int) -> None:
    """Run ``problem`` into ``out_dir`` and stop it with Ctrl-C at ``iteration``."""
    def stop(k, *_):
        if k == iteration:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        optimize(problem, out_dir=out_dir, progress=stop)
