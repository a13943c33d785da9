"""``flexfem balance``: RMS-optimal static balancing of the five-bar robot's motors 2-5."""
import math

from ..lazy import Lazy
from ..options import deferred

balance_robot = Lazy(".design:balance_robot", __package__)  # imported when the command runs


def run(args) -> dict:
    """Optimal balancers for ``args.method`` over the default workspace (SI params)."""
    return balance_robot(args.method)


def _parameter(name: str, value: float) -> str:
    """A balancer's parameter as the paper prints it: angles in degrees, sizes in SI."""
    if name.startswith("q_"):  # q_k, q_c: angles, radians in the code
        return f"{name[:-4]} = {math.degrees(value):.1f} deg"
    unit = {"C_Nm": "N m", "K_Nm_per_rad": "N m/rad"}.get(name, "")
    return f"{name.split('_')[0]} = {value:.4g} {unit}".rstrip()


def summarize(result: dict) -> str:
    lines = [f"{'motor':>5}  {'method':<13} {'RMS red. %':>10} {'max red. %':>10}  balancer"]
    for r in result["results"]:
        params = ", ".join(_parameter(k, v) for k, v in r["params"].items())
        lines.append(f"{r['motor']:>5}  {r['method']:<13} {r['rms_reduction_pct']:>10.1f} "
                     f"{r['max_reduction_pct']:>10.1f}  {params}")
    lines.append(f"({result['n_samples']} workspace samples)")
    return "\n".join(lines)


def register(subparsers):
    parser = subparsers.add_parser(
        "balance", help="optimum static balancing of the five-bar robot (springs, torsion "
                        "springs, counterweights)")
    deferred(parser, _arguments)


def _arguments(parser) -> None:
    """The command's options (its methods: the balancers the design knows)."""
    from .design import METHODS

    parser.add_argument("--method", choices=[*METHODS, "all"], default="all",
                        help="balancer to optimise (default: all)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run, summarize=summarize)
