"""The single place that decides how hubbeam's kernels are compiled.

Every kernel is compiled with ``cache=True`` so that a second process loads machine code from
disk instead of compiling again. ``hubbeam/__init__.py`` points ``NUMBA_CACHE_DIR`` at a directory
keyed by a hash of the package sources, because numba's cache does not notice edits in other
modules. Setting ``HUBBEAM_NO_JIT_CACHE=1`` disables the on-disk cache (useful when profiling
compilation).
"""

import os
import warnings

import numba
from numba.core.errors import NumbaIRAssumptionWarning

# Inlining at numba's IR level (``inline_kernel``) trips a pedantic internal check about the scope
# of renamed variables; the check is informational (numba asks for reports, the code is correct
# and covered by tests), so it is silenced here instead of being shown to every user on compile.
warnings.filterwarnings("ignore", category=NumbaIRAssumptionWarning)

_CACHE = os.environ.get("HUBBEAM_NO_JIT_CACHE", "0") not in ("1", "true", "yes")

# error_model="numpy": division by zero gives inf/nan like numpy instead of raising, which keeps
# the kernels branch-free; divergence is detected explicitly by the integrator.
JIT_OPTIONS = dict(cache=_CACHE, error_model="numpy", fastmath=False)


def kernel(func):
    """Decorate a numerical kernel with the project's jit options."""
    return numba.njit(**JIT_OPTIONS)(func)


def borrowing_kernel(func):
    """A kernel that only borrows arrays: it neither allocates nor returns one.

    Numba's runtime counts references to every array a function receives; for a function that
    takes structures of arrays (the problem and work-array namedtuples) it cannot prove the counts
    unnecessary, so each call and each field access costs an atomic increment and decrement.
    On the integrator's hot path that was 40 % of a CFOAM run (``perf``, docs/architecture.md).
    Compiled without the runtime, the kernel leaves every count to its caller, which owns the
    arrays for the whole call; numba refuses to compile such a kernel if it allocates or returns
    a new array. ``_nrt`` is a private numba option (hence the pinned numba version);
    ``tests/test_simulate.py`` checks that runs still free every block the runtime allocates.
    """
    return numba.njit(_nrt=False, **JIT_OPTIONS)(func)


def internal_kernel(func):
    """A :func:`borrowing_kernel` that only other kernels call: compiled without the CPython
    entry point numba otherwise builds for every function (the code that unboxes each argument
    from Python objects), which is compile time spent on code that never runs."""
    return numba.njit(_nrt=False, no_cpython_wrapper=True, **JIT_OPTIONS)(func)


def inline_kernel(func):
    """A small kernel on a hot path, inlined into its callers at numba's IR level.

    Every call between jitted functions passes array arguments by value and adjusts their
    reference counts; for the many-array structures of this project (``SystemMatrices``, the
    integrator's work arrays) that costs more than the arithmetic of a small kernel. Inlining
    removes the call boundary at the price of longer compilation.
    """
    return numba.njit(inline="always", **JIT_OPTIONS)(func)
