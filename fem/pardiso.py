"""MKL PARDISO through ctypes: its entry points (32- and 64-bit integer interfaces), one call
with its error codes as exceptions, the handle's release, the memory its analysis predicts
and flexfem's parameters (iparm). fem/linsolve.py's Factorization is built on these."""
import ctypes
import functools
import glob
import os
import shutil
import sys

import numpy as np

from .factor_protocol import SingularStiffness

ERRORS = {-1: "input inconsistent", -2: "not enough memory", -3: "reordering problem",
                   -4: "zero pivot (the matrix is singular, or not positive definite)",
                   -5: "unclassified internal error", -6: "reordering failed",
                   -7: "diagonal matrix is singular", -8: "32-bit integer overflow",
                   -9: "not enough memory for the out-of-core solver",
                   -10: "error opening out-of-core files", -11: "read/write error with OOC files"}


def mkl_candidates() -> list:
    """Paths where a pip-installed MKL keeps its runtime library (the ``mkl`` wheel, a
    dependency of flexfem on x86-64 Linux, Windows and Intel macOS): the environment's, then
    the user site's; FLEXFEM_MKL_RT or PYPARDISO_MKL_RT name one explicitly."""
    import site

    paths = [os.environ.get("FLEXFEM_MKL_RT"), os.environ.get("PYPARDISO_MKL_RT")]
    for base in dict.fromkeys([sys.prefix, sys.base_prefix, getattr(site, "USER_BASE", None)]):
        if base:
            paths += sorted(glob.glob(os.path.join(base, "lib", "libmkl_rt.*")))
            paths += sorted(glob.glob(os.path.join(base, "Library", "bin", "mkl_rt*.dll")))
    return [p for p in paths if p]


@functools.cache
def mkl_pardiso():
    """MKL's ``pardiso`` entry point (ctypes), found once: the runtime library of the
    installed ``mkl`` wheel (see :func:`mkl_candidates`), else through pypardiso's search
    (~0.8 s); None where neither is found. (Its 32-bit integers serve factors past 2^31
    entries: the 1M-DOF cube's 2.4e9, measured; only iparm[17]'s count overflows.)"""
    library = None
    for path in mkl_candidates():
        try:
            library = ctypes.CDLL(path)
            break
        except OSError:
            continue
    if library is None:
        try:
            import pypardiso
            library = pypardiso.PyPardisoSolver().libmkl
        except Exception:  # not installed, or its library search failed
            return None
    try:
        fn = library.pardiso
    except AttributeError:
        return None
    ip, dp = ctypes.POINTER(ctypes.c_int32), ctypes.c_void_p
    # pt, maxfct, mnum, mtype, phase, n, a, ia, ja, perm, nrhs, iparm, msglvl, b, x, error
    fn.argtypes = [ctypes.POINTER(ctypes.c_int64)] + [ip] * 5 + [dp] * 4 + [ip] * 3 \
        + [dp] * 2 + [ip]
    fn.restype = None
    return fn


def pardiso_call(pt, mtype, phase, n, data, indptr, indices, iparm, b, x) -> None:
    """One call of MKL's pardiso (zero-based CSR, iparm[34] = 1, int32 indices and iparm);
    raises on its error code."""
    fn = mkl_pardiso()
    error = ctypes.c_int32(0)
    one = ctypes.c_int32(1)
    nrhs = 1 if b.ndim == 1 else b.shape[1]
    null = ctypes.c_void_p()
    fn(pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)), ctypes.byref(one), ctypes.byref(one),
       ctypes.byref(ctypes.c_int32(mtype)), ctypes.byref(ctypes.c_int32(phase)),
       ctypes.byref(ctypes.c_int32(n)), data.ctypes.data_as(ctypes.c_void_p),
       indptr.ctypes.data_as(ctypes.c_void_p), indices.ctypes.data_as(ctypes.c_void_p), null,
       ctypes.byref(ctypes.c_int32(nrhs)), iparm.ctypes.data_as(ctypes.POINTER(ctypes.c_int32)),
       ctypes.byref(ctypes.c_int32(0)), b.ctypes.data_as(ctypes.c_void_p),
       x.ctypes.data_as(ctypes.c_void_p), ctypes.byref(error))
    if error.value == -4 or error.value == -7:
        raise SingularStiffness(f"PARDISO: {ERRORS[error.value]}; the model is "
                                  "under-constrained, has disconnected parts or a mechanism")
    if error.value in (-2, -9):
        raise MemoryError(f"PARDISO error {error.value}: {ERRORS[error.value]}")
    if error.value != 0:
        raise RuntimeError(f"PARDISO error {error.value}: "
                           f"{ERRORS.get(error.value, 'unknown')}")


def pardiso_release(pt, mtype, n, iparm, folder: str | None = None) -> None:
    """Release the factor that the handle ``pt`` holds in MKL (phase -1), with the
    ``iparm`` it was made with (the two-level factorization's release crashes on defaults),
    and remove the out-of-core ``folder`` (its factor files); idempotent."""
    if np.any(pt):
        empty_i, empty_d = np.zeros(1, dtype=np.int32), np.zeros(1)
        pardiso_call(pt, mtype, -1, n, empty_d, empty_i, empty_i, iparm, empty_d, empty_d.copy())
        pt[:] = 0
    if folder is not None:
        shutil.rmtree(folder, ignore_errors=True)


def pardiso_memory(iparm) -> tuple[int, int]:
    """(in core, out of core): the peak memory (bytes) of PARDISO's factorization with the
    factor in memory, max(symbolic, permanent + numerical), and with it on disk, max(symbolic,
    permanent + the least out-of-core working set), from its analysis (MKL's iparm[14..16]
    and iparm[62], KiB)."""
    symbolic, permanent, numerical = (int(v) for v in iparm[14:17])
    return (max(symbolic, permanent + numerical) * 1024,
            max(symbolic, permanent + int(iparm[62])) * 1024)


def pardiso_iparm(kind: str) -> np.ndarray:
    """PARDISO's parameters (iparm, 64 int32) of flexfem's factorizations of ``kind``."""
    iparm = np.zeros(64, dtype=np.int32)
    iparm[0] = 1     # these values, not the defaults
    iparm[1] = 3     # nested-dissection ordering (parallel METIS)
    iparm[7] = 0     # no automatic iterative refinement (see solve_and_check)
    iparm[9] = 13 if kind == "general" else 8  # pivot perturbation 1e-13 / 1e-8
    iparm[10] = 1 if kind == "general" else 0  # scaling (non-symmetric only)
    iparm[12] = 1 if kind == "general" else 0  # weighted matching (non-symmetric only)
    iparm[34] = 1    # zero-based indices
    # symmetric kinds: PARDISO groups rows of like pattern (the dim DOFs of a node) into
    # variable-size blocks (VBSR, 80 % alike): the ordering works on the much smaller
    # block graph, -25 % to -40 % CPU on 3-D P2 (docs/performance.md)
    iparm[36] = 0 if kind == "general" else -80
    # two-level factorization: the same factor and time on 2 cores, ~15 MiB less peak on a
    # 3-D P2 K of 36k DOFs; out of core too (one-level VBSR met a false zero pivot there)
    iparm[23] = 1
    return iparm
