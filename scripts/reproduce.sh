#!/usr/bin/env bash
# Install flexfem into .venv and reproduce the source documents' results into report/.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e .
.venv/bin/flexfem reproduce --out report "$@"
