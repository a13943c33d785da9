#!/usr/bin/env bash
# The API reference (HTML, by pdoc: pip install -e ".[docs]") into docs/api/, or the folder
# given; fails on any pdoc warning.
set -euo pipefail
cd "$(dirname "$0")/.."
python scripts/api_docs.py "$@"
