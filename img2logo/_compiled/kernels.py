"""The compiled kernels of the optimizer's inner loop, loaded without numba at run time.

The kernels themselves are written in :mod:`img2logo._compiled.sqp` (the SQP of
Eqn. 13 for a local window, with its terms in :mod:`img2logo._compiled.sqp_terms` and its KKT
systems in :mod:`img2logo._compiled.kkt`), :mod:`img2logo._compiled.arcs` (arc-arc
intersections, the redundant-intersection test, the arc extraction with its
Fréchet distance, the tangent biarcs' searches), :mod:`img2logo._compiled.circle` (the free circle fit, a
golden circle's centre, the biarc search's worst distances), :mod:`img2logo._compiled.graph`
(the skeleton's shortest paths, the global KKT solve in a band) and
:mod:`img2logo._compiled.front` (the clip-art regions' label sums, labelling, the distance transform),
:mod:`img2logo._compiled.ndimage` (thinning, scipy's 1-D correlation and feature transform), each beneath a
public function whose Python code stays as the reference the tests compare against. This module gives them
to their callers as attributes (``kernels.sqp_dense(...)``), loaded on first use:

1. **Ahead of time.** The entry points below are compiled with numba's ``pycc``
   into one extension module whose name carries a hash of the kernels' source and
   of numpy's major version, so an edited kernel is never run stale. A wheel ships
   it beside this file (``setup.py`` builds it for the architecture's generic
   processor); otherwise the first use in an install compiles it for this
   machine's processor (about a minute of CPU, once, said in one line on stderr)
   into ``img2logo/_compiled/__pycache__`` or, when that is read-only,
   ``$XDG_CACHE_HOME/img2logo``. A run imports that module like any other:
   numba is not imported at all.
   Its import and start-up were ~0.7 s of CPU of every run of the command (the
   library's import, then its typing and lowering registries when the first
   cached kernel loaded), more than the run's own work on a clip art.
2. **Just in time**, where no such module can be built (no C compiler): numba's
   ``njit(cache=True)``, loaded from numba's disk cache.
3. **Just in time, in the process**, where numba cannot cache either (:data:`CACHED` False): every
   process compiles the kernels it calls (seconds, said once in one line on stderr), with the same
   results: the fit and the clip-art front end have no second path through the pipeline, and the
   Python references of their kernels live in the tests, as their oracles.

The compiled forms are the same numba code with the same types, compiled
without fast-math (so nothing is reordered or fused): the same floating-point
operations in the same order for the generic processor and this one.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import threading
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

#: Whether the compiled kernels are usable: False only where neither an
#: ahead-of-time module can be built nor numba's disk cache written.
CACHED = True

#: The entry points: name -> (module, argument types in numba's notation, return type).
#: An argument marked ``!`` is written in place, so it is never converted.
ENTRY_POINTS: dict[str, tuple[str, tuple[str, ...], str]] = {
    "sqp_dense": (
        "sqp",
        tuple(
            "f8[:,::1] i8[::1] f8[::1] !f8[:,::1] f8[:,::1] !f8[:,::1] i8[:,::1] i8[::1] i8[::1] f8[::1] "
            "f8 b1 i8[:,::1] f8[::1] b1[::1] f8 i8 i8 f8 f8".split()
        ),
        "Tuple((i8, b1, f8, f8))",
    ),
    # (loop) the same SQP with the KKT system in a band: a global solve, compiled.
    "sqp_banded": (
        "sqp",
        tuple(
            "f8[:,::1] i8[::1] f8[::1] !f8[:,::1] f8[:,::1] !f8[:,::1] i8[:,::1] i8[::1] i8[::1] f8[::1] "
            "f8 b1 i8[:,::1] f8[::1] b1[::1] f8 i8 i8 f8 f8".split()
        ),
        "Tuple((i8, b1, f8, f8))",
    ),
    # (loop) a photo's merged arc that no circle of its radius can bring within the bound.
    "far_circle_kernel": ("sqp", ("f8[:,::1]", "f8", "f8", "f8", "f8", "i8"), "b1"),
    "extract_arc_kernel": (
        "arcs",
        ("f8", "f8", "f8", "f8[:,::1]", "f8[:,::1]", "f8[::1]", "f8", "f8", "f8", "f8"),
        "Tuple((b1, f8, f8, b1, f8, b1))",
    ),
    "frechet": ("arcs", ("f8[:,::1]", "f8[:,::1]", "f8"), "f8"),
    "redundant_kernel": (
        "arcs",
        ("f8[:,::1]", "i8[::1]", "f8[:,::1]", "i8[::1]", "i8[::1]", "f8", "f8"),
        "Tuple((i8[:,::1], f8[:,::1]))",
    ),
    "arc_pairs_kernel": ("arcs", ("f8[:,::1]", "i8[::1]", "f8"), "i8[:,::1]"),
    "arc_intersections_kernel": ("arcs", ("f8[::1]", "f8[::1]", "f8", "!f8[:,::1]"), "i8"),
    "fit_circle_kernel": ("circle", ("f8[:,::1]", "f8", "f8"), "Tuple((i8, f8, f8, f8, f8, b1))"),
    "fit_center_kernel": ("circle", ("f8[:,::1]", "f8", "f8", "f8", "i8"), "UniTuple(f8, 2)"),
    "mean_abs_error_kernel": ("circle", ("f8[:,::1]", "f8", "f8", "f8"), "f8"),
    # (loop) a lower bound of an arc's Fréchet distance before it is extracted (the tangent pass).
    "largest_gap_kernel": ("circle", ("f8[:,::1]", "f8", "f8", "f8"), "f8"),
    "dijkstra_kernel": ("graph", ("i8[::1]", "i8[::1]", "f8[::1]", "i8[::1]", "!f8[::1]", "!i8[::1]"), "i8"),
    "banded_solve_kernel": ("graph", ("i8[::1]", "i8[::1]", "f8[::1]", "f8[::1]", "!f8[::1]"), "i8"),
    "end_tangents_kernel": (
        "graph",
        ("f8[:,::1]", "i8[::1]", "i8[::1]", "b1[::1]", "f8", "f8"),
        "f8[:,::1]",
    ),
    "label_sums_kernel": ("front", ("i8[::1]", "f8[:,::1]", "i8"), "Tuple((f8[::1], f8[:,::1]))"),
    "spreads_kernel": (
        "front",
        ("f8[:,:,::1]", "i8[:,::1]", "b1[::1]", "b1[::1]"),
        "UniTuple(f4[:,::1], 2)",
    ),
    "label_kernel": ("front", ("i8[:,::1]", "i8", "b1"), "i8[:,::1]"),
    "label_mask_kernel": ("front", ("u1[:,::1]", "i8", "b1"), "i8[:,::1]"),
    "colour_table_kernel": ("front", ("f8[:,:,::1]",), "Tuple((b1, i8[::1], i8[::1]))"),
    "colour_distance_kernel": ("front", ("f8[:,:,::1]", "f8[::1]"), "f8[:,::1]"),
    "bounds_kernel": ("front", ("i8[:,::1]", "i8"), "i8[:,::1]"),
    "relabel_kernel": ("front", ("i8[:,::1]",), "i8[:,::1]"),
    "edt_kernel": ("front", ("u1[:,::1]",), "f8[:,::1]"),
    "palette_regions_kernel": ("front", ("i8[:,::1]", "i8"), "i8[:,::1]"),
    "nearest_colour_kernel": ("front", ("f8[:,::1]", "f8[:,::1]", "b1[:,::1]"), "f8[::1]"),
    "region_depth_kernel": ("front", ("i8[:,::1]",), "f8[:,::1]"),
    "sparse_label_kernel": ("front", ("i8[::1]", "i8[::1]", "i8", "i8"), "i8[::1]"),
    "near_kernel": ("front", ("i8[:,::1]", "i8[::1]", "i8[::1]", "i8", "i8[:,::1]"), "b1[:,::1]"),
    "biarc_worst_kernel": ("circle", tuple("f8[:,::1] f8[:,:,::1] i8[::1] i8[::1] f8 b1".split()), "f8[:,::1]"),
    "biarc_fine_kernel": (
        "arcs",
        tuple("f8[:,::1] f8[:,:,:,::1] f8[:,:,:,::1] i8[:,::1] i8[::1] f8[::1] f8[::1] i8".split()),
        "Tuple((f8[::1], i8[::1], i8[::1]))",
    ),
    "biarc_coarse_kernel": (
        "arcs",
        tuple("f8[:,::1] i8[::1] i8[::1] f8[:,:,:,:,::1] f8[:,:,:,:,::1] f8[::1] f8[::1]".split()),
        "i8[:,:,::1]",
    ),
    "nearest_on_chain_kernel": ("arcs", ("f8[:,::1]", "f8", "f8"), "Tuple((i8, f8, f8, f8))"),
    "thin_kernel": ("ndimage", ("u1[:,::1]",), "b1[:,::1]"),
    "correlate_kernel": ("ndimage", ("f8[:,:,::1]", "f8[::1]", "i8", "f8", "!f8[:,:,::1]"), "i8"),
    "correlate32_kernel": ("ndimage", ("f4[:,:,::1]", "f8[::1]", "i8", "f8", "!f4[:,:,::1]"), "i8"),
    "feature_transform_kernel": ("ndimage", ("u1[:,::1]",), "i4[:,:,::1]"),
}

_DTYPES: dict[str, np.dtype[Any]] = {
    "f8": np.dtype(np.float64),
    "f4": np.dtype(np.float32),
    "i8": np.dtype(np.int64),
    "b1": np.dtype(np.bool_),
    "u1": np.dtype(np.uint8),
}
_SOURCES = (
    "sqp.py",
    "sqp_terms.py",
    "kkt.py",
    "arcs.py",
    "circle.py",
    "graph.py",
    "front.py",
    "ndimage.py",
    "jit.py",
)
_loaded: dict[str, Any] = {}
#: Held while the kernels load: a photo's run loads them from two threads at once (its line maps beside the
#: subject search), and the other thread must not see half the entry points.
_loading = threading.Lock()
#: Where the loaded kernels came from: the ahead-of-time module's path, or "numba's JIT".
source = ""


def usable() -> bool:
    """Whether the compiled kernels should be used (see :data:`CACHED`); loads them."""
    _load()
    return CACHED


def __getattr__(name: str) -> Any:
    if name in ENTRY_POINTS:
        return _load()[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def module_name() -> str:
    """The ahead-of-time module's name: ``_kernels_`` and a hash of the kernels' source, signatures, numpy's ABI.

    numpy's major version stands for its ABI: a module built against a numpy runs with any later one of the same
    major version, and one built against a later numpy than the running one fails to import (then it is rebuilt).
    """
    digest = _sha256(f"numpy {np.__version__.split('.')[0]} {ENTRY_POINTS}".encode())
    here = Path(__file__).parent
    for name in _SOURCES:
        digest.update((here / name).read_bytes())
    return "_kernels_" + digest.hexdigest()[:16]


def _sha256(data: bytes) -> Any:
    """``hashlib.sha256(data)``, by Python's own SHA-256 where it has one: hashlib loads OpenSSL (2 ms a run)."""
    try:
        from _sha256 import sha256  # CPython <= 3.11; the same digest
    except ImportError:
        try:
            from _sha2 import sha256  # type: ignore[no-redef]  # CPython >= 3.12
        except ImportError:
            from hashlib import sha256
    return sha256(data)


def _directories() -> list[Path]:
    """Where the ahead-of-time module may live: next to the package's bytecode, else the user's cache.

    A wheel ships the module beside this file (``setup.py`` builds it); it is looked for there first.
    """
    cache = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    here = Path(__file__).parent
    return [here, here / "__pycache__", Path(cache) / "img2logo"]


def _load() -> dict[str, Any]:
    """The entry points by name: ahead of time if possible, else numba's JIT (see the module's notes)."""
    if _loaded:  # filled in one step, below: never half
        return _loaded
    with _loading:
        if not _loaded:
            _loaded.update(_entry_points())
    return _loaded


def _entry_points() -> dict[str, Any]:
    """The entry points by name, loaded: ahead of time if possible, else numba's JIT."""
    global CACHED, source
    name = module_name()
    # The running interpreter's extension suffix, as pycc names the module. Not sysconfig's EXT_SUFFIX: its
    # variables are filled on first use, unlocked, and a second thread could read None meanwhile (seen once).
    filename = name + importlib.machinery.EXTENSION_SUFFIXES[0]
    module = None
    for directory in _directories():
        if (directory / filename).is_file():
            try:
                module = _import(name, directory / filename)
                break
            except ImportError:  # built against a later numpy than this one: built again below
                continue
    if module is None:
        import sys
        import time

        print(
            "img2logo: compiling its kernels for this machine, once (about a minute of CPU; later runs start in"
            " about a second)...",
            file=sys.stderr,
            flush=True,
        )
        start = time.perf_counter()
        for directory in _directories()[1:]:
            try:
                module = _import(name, build(directory))
                break
            except Exception:  # no compiler, a read-only directory, ...: the next place, then the JIT
                continue
        took = f"compiled in {time.perf_counter() - start:.0f} s" if module is not None else "no C compiler"
        print(f"img2logo: kernels {took}", file=sys.stderr, flush=True)
    if module is not None:
        source = str(module.__file__)
        return {entry: _checked(getattr(module, entry), args) for entry, (_, args, _) in ENTRY_POINTS.items()}
    from . import jit as kernels_jit  # numba's JIT: its import and its cache

    entries = {
        entry: getattr(importlib.import_module(f".{home}", __package__), entry)
        for entry, (home, _, _) in ENTRY_POINTS.items()
    }
    CACHED = CACHED and kernels_jit.CACHED
    source = "numba's JIT"
    if not CACHED:
        import sys

        print(
            "img2logo: no disk cache for its kernels: numba compiles them in this process (seconds, every run)",
            file=sys.stderr,
            flush=True,
        )
    return entries


def _import(name: str, path: Path) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot load {path}")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _checked(fn: Any, args: tuple[str, ...]) -> Any:
    """``fn`` with its array arguments made C-contiguous of the exported dtype.

    An ahead-of-time entry point, unlike the JIT's dispatcher, has one signature
    and does not check what it is given; an in-place argument (``!``) must already
    be right, since a converted copy would lose what the kernel writes.
    """
    arrays = []
    for i, spec in enumerate(args):
        if "[" in spec:
            arrays.append((i, _DTYPES[spec.strip("!")[:2]], spec.count(",") + 1, spec.startswith("!")))

    def call(*values: Any) -> Any:
        values_ = list(values)
        for i, dtype, ndim, in_place in arrays:
            a = values_[i]
            if not (isinstance(a, np.ndarray) and a.dtype == dtype and a.flags.c_contiguous):
                if in_place:
                    raise TypeError(f"argument {i} of {fn.__name__} must be a C-contiguous {dtype} array")
                a = values_[i] = np.ascontiguousarray(a, dtype=dtype)
            if a.ndim != ndim:
                raise TypeError(f"argument {i} of {fn.__name__} must have {ndim} dimensions, got {a.ndim}")
        return fn(*values_)

    call.__name__ = call.__qualname__ = getattr(fn, "__name__", "kernel")
    return call


def build(directory: Path, cpu: str = "host") -> Path:
    """Compile the entry points ahead of time into ``directory`` (numba's ``pycc``); the module's path.

    ``cpu``: LLVM's processor name; ``"host"`` this machine's (as numba's JIT compiles), ``""`` the
    architecture's generic processor (a wheel's, which runs on any machine of the architecture). The
    module is written under a temporary name and renamed into place, so that processes building at
    once never load a half-written file.

    numba's ``pycc`` is pending deprecation; when a numba release drops it, the kernels keep to numba's
    JIT (:func:`_entry_points`' second way) until they are built by its successor (numba's planned
    ahead-of-time compiler), and ``numba`` is pinned below that release in ``pyproject.toml`` meanwhile.
    """
    import tempfile
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pycc is marked for deprecation; it still compiles, with numba's code
        from numba.pycc import CC

        name = module_name()
        directory.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(dir=directory) as tmp:
            cc = CC(name)
            cc.output_dir = tmp
            cc.target_cpu = cpu
            cc.verbose = False
            for entry, (source, args, result) in ENTRY_POINTS.items():
                module = importlib.import_module(f".{source}", __package__)
                signature = f"{result}({', '.join(a.strip('!') for a in args)})"
                cc.export(entry, signature)(getattr(module, entry).py_func)
            cc.compile()
            built = next(Path(tmp).glob(name + "*"))
            target = directory / built.name
            os.replace(built, target)
    return target


def main(argv: list[str] | None = None) -> int:
    """``python -m img2logo._compiled.kernels``: build (if need be) and load the kernels; print where from."""
    _load()
    print(f"img2logo kernels: {source}" + ("" if CACHED else " (no disk cache: compiled in every process)"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
