"""The ``flexfem`` command: a thin layer over the Python API.

Each command module registers its sub-command with ``register(subparsers)`` and sets two
defaults on its parser: ``run(args) -> dict`` (JSON-able, computed by one public function) and
``summarize(result) -> str`` (the human summary). This module only dispatches: with ``--json`` it
prints the dict as one JSON object and nothing else on stdout, otherwise the summary.
"""
import argparse
import importlib
import json
import sys

from .serialize import jsonable

COMMAND_MODULES = [
    "flexfem.studies.cli_reproduce",
    "flexfem.studies.cli_dbma",
    "flexfem.studies.cli_linkage",
    "flexfem.studies.cli_balance",
    "flexfem.studies.cli_optimize",
    "flexfem.studies.cli_studies",
]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="flexfem", description=__doc__.splitlines()[0])
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in COMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as error:
            if error.name != name:
                raise
            continue
        module.register(subparsers)
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
