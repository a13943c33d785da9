#!/usr/bin/env bash
# Install flexfem with its test extras into .venv and run the whole test suite, on two
# processes (pytest-xdist; a test file's tests stay in one process, so its fixtures are built
# once). Local runs may skip the slow checks: bash scripts/test.sh -m "not slow"
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[test,fast,dask]"
# two workers share the cores: each runs its BLAS, MKL (PARDISO) and OpenMP on half of them
# (two multithreaded solvers on two cores contend: the suite ran 20 % slower)
threads=$(( $(nproc) / 2 > 0 ? $(nproc) / 2 : 1 ))
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-$threads} MKL_NUM_THREADS=${MKL_NUM_THREADS:-$threads} \
    OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-$threads}
.venv/bin/python -m pytest -n 2 --dist loadfile "$@"
