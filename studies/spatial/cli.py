"""``flexfem constraints MODEL.toml``: the exact-constraint analysis of a spatial model file
(its degrees of freedom and over-constraints, exact_constraint.py)."""
from ..user_model.cli import parse_sets


def run(args) -> dict:
    """The analysis of ``args.model`` with its [[supports]] bodies held: {"model",
    "singular_values", "threshold", "dofs": [{body: twist}], "over_constraints":
    [[{flexure, constraint, weight}]], "summary"}. The whole file is checked, as analyze
    checks it."""
    from ...geometry.user_model import load_spec  # imported when the command runs
    from .exact_constraint import exact_constraint

    spec = load_spec(args.model, parse_sets(args.set))
    if getattr(spec, "spatial", None) is None:
        raise ValueError(f"{args.model}: not a spatial mechanism: no body has a 3-D box, a "
                         "cylinder or a prism (a planar file: docs/model_files.md)")
    report = exact_constraint(spec.spatial, {s.group for s in spec.supports})
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
