"""The ``flexfem`` command: a thin layer over the Python API.

Each command module registers its sub-command with ``register(subparsers)`` and sets two
defaults on its parser: ``run(args) -> dict`` (JSON-able, computed by one public function) and
``summarize(result) -> str`` (the human summary). The mechanisms' commands come from the
registry (studies/mechanisms.py); this module only dispatches: with ``--json`` it prints the
dict as one JSON object and nothing else on stdout, otherwise the summary.
"""
import argparse
import json
import sys

from . import run_cli
from .engine.serialize import jsonable
from .mechanisms import command_modules, optimizers
from .options import Parser
from .report import cli as report_cli


def register_optimize(subparsers) -> None:
    """``flexfem optimize MECHANISM``: the design search of each mechanism that has one."""
    parser = subparsers.add_parser("optimize", help="design search of a mechanism's dimensions")
    choices = parser.add_subparsers(dest="mechanism", required=True, metavar="MECHANISM")
    for name, module in optimizers().items():
        sub = choices.add_parser(name, help=module.HELP)
        module.add_arguments(sub)
        sub.set_defaults(run=module.run, summarize=module.summarize)


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="flexfem", description=__doc__.splitlines()[0])
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    report_cli.register(subparsers)
    for module in command_modules():
        module.register(subparsers)
    register_optimize(subparsers)
    run_cli.register(subparsers)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        result = args.run(args)
    except (ValueError, FileNotFoundError) as error:
        print(f"flexfem {args.command}: error: {error}", file=sys.stderr)
        return 2
    if getattr(args, "json", False):
        json.dump(jsonable(result), sys.stdout)
        sys.stdout.write("\n")
    else:
        print(args.summarize(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
