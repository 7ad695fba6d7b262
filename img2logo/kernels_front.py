"""Compiled kernels of the front end: the clip-art regions' per-label sums.

:func:`label_sums_kernel` is ``clipart.label_means``'s ``np.bincount`` per
channel in one pass over the pixels: each label's count and its sums, added
in the pixels' order as ``np.bincount`` adds them, so the same bits.

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo.kernels` (ahead of time, or numba's JIT as a fallback), never
imported by the pipeline directly.
"""

from __future__ import annotations

import numpy as np

from .kernels_jit import jit as _jit


@_jit
def label_sums_kernel(labels, values, n):  # pragma: no cover - compiled
    """Pixel count (n,) and per-channel sums (n, C) of every label of ``labels`` (N,), ``values`` (N, C)."""
    counts = np.zeros(n)
    sums = np.zeros((n, values.shape[1]))
    for i in range(len(labels)):
        k = labels[i]
        counts[k] += 1.0
        for c in range(values.shape[1]):
            sums[k, c] += values[i, c]
    return counts, sums
