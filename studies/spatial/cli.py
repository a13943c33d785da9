"""``flexfem constraints MODEL.toml``: the exact-constraint analysis of a spatial model file
(its degrees of freedom and over-constraints, exact_constraint.py)."""
from ..user_model.cli import parse_sets


def run(args) -> dict:
    """The analysis of ``args.model`` with its [[supports]] bodies held: {"model",
    "singular_values", "threshold", "dofs": [{body: twist}], "over_constraints":
    [[{flexure, constraint, weight}]], "summary"}."""
    from ...geometry.spatial.tables import load_spatial  # imported when the command runs
    from .exact_constraint import exact_constraint

    mechanism, raw, _ = load_spatial(args.model, parse_sets(args.set))
    held = {s.get("group") for s in raw.get("supports", []) if isinstance(s, dict)}
    report = exact_constraint(mechanism, held)
    return {"model": str(args.model), "singular_values": report.singular_values.tolist(),
            "threshold": report.threshold,
            "dofs": [{body: twist.tolist() for body, twist in dof} for dof in report.dofs],
            "over_constraints": [[{"flexure": label, "constraint": what, "weight": weight}
                                  for label, what, weight in combo]
                                 for combo in report.over_constraints],
            "summary": report.summary()}


def summarize(result: dict) -> str:
    return f"{result['model']}: exact-constraint analysis\n{result['summary']}"


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "constraints", help="the DOFs and over-constraints of a spatial mechanism (each "
                            "flexure idealised by its stiff directions)")
    parser.add_argument("model", metavar="MODEL.toml", help="a spatial model file")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a [parameters] entry; repeatable")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run, summarize=summarize)
