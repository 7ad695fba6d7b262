"""The decorator of the compiled kernels: ``numba.njit``, cached on disk where it can be.

The kernels (:mod:`img2logo._compiled.sqp`, :mod:`img2logo._compiled.arcs`) are
written once, in the subset of Python that numba compiles; :mod:`img2logo._compiled.kernels`
loads them either as one ahead-of-time compiled extension module or, where that
cannot be built, through numba's just-in-time compiler with this decorator.
"""

from __future__ import annotations

from numba import njit

#: Whether numba can cache the kernels on disk. When it cannot (a read-only
#: install and no writable user cache directory), every process compiles them
#: again (seconds, more than the whole run; :mod:`img2logo._compiled.kernels` says so).
CACHED = True


def jit(fn):
    """``numba.njit(cache=True)``, or uncached (and ``CACHED`` False) where no cache directory can be written."""
    global CACHED
    try:
        return njit(cache=True, nogil=True)(fn)
    except RuntimeError:  # numba: "cannot cache function ...: no locator available for file ..."
        CACHED = False
        return njit(cache=False, nogil=True)(fn)
