"""img2logo: golden ratio logos from images (Hsiao et al., CGF 2023).

The pipeline flows one way: image -> feature lines -> segment graph L = {S, J}
-> levels of abstraction -> writers. The public names below are loaded on first
use (PEP 562), so ``import img2logo`` stays fast for the command line.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from .constants import PHI
from .errors import (
    FitError,
    ImageNotFoundError,
    Img2LogoError,
    InputNotFoundError,
    InvalidImageError,
    InvalidParameterError,
    OutputError,
    UnknownOptionError,
)

__version__ = "0.1.0"

_LAZY = {
    "load_image": "images.loading",
    "extract_feature_lines": "features.preprocessing",
    "detect_kind": "features.preprocessing",
    "LoadedImage": "images.loading",
    "FeatureLines": "features.preprocessing",
    "DownscaleWarning": "images.loading",
    "DetailWarning": "features.detail",
    "PageWarning": "images.loading",
    "build_segment_graph": "segment_graph",
    "SegmentGraph": "segment_graph",
    "Circle": "geometry.primitives",
    "Arc": "geometry.primitives",
    "Abstraction": "geometry.primitives",
    "plot_segment_graph": "export.plotting",
    "plot_abstraction": "export.plotting",
    "write_segment_graph_png": "export.writers",
    "write_json": "export.writers",
    "write_svg": "export.writers",
    "write_png": "export.writers",
    "read_json": "export.writers",
    "abstract": "pipeline",
    "Result": "pipeline",
    "optimize": "fit.progressive",
    "Progression": "fit.progressive",
    "GoldenLadder": "geometry.golden_ladder",
    "FibonacciLadder": "geometry.golden_ladder",
    "run_batch": "app.batch.run",
    "load_mask": "images.loading",
    "Options": "options",
    "ConnectivityWarning": "fit.recovery",
}

#: Submodules reachable as attributes, imported on first use.
_SUBMODULES = ("quality",)

__all__ = [
    "PHI",
    "Abstraction",
    "Arc",
    "Circle",
    "ConnectivityWarning",
    "DetailWarning",
    "DownscaleWarning",
    "FeatureLines",
    "FibonacciLadder",
    "FitError",
    "GoldenLadder",
    "ImageNotFoundError",
    "Img2LogoError",
    "InputNotFoundError",
    "InvalidImageError",
    "InvalidParameterError",
    "LoadedImage",
    "Options",
    "OutputError",
    "PageWarning",
    "Progression",
    "Result",
    "SegmentGraph",
    "UnknownOptionError",
    "__version__",
    "abstract",
    "build_segment_graph",
    "detect_kind",
    "extract_feature_lines",
    "load_image",
    "load_mask",
    "optimize",
    "plot_abstraction",
    "plot_segment_graph",
    "read_json",
    "run_batch",
    "write_json",
    "write_png",
    "write_segment_graph_png",
    "write_svg",
]


def __getattr__(name: str) -> Any:
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'img2logo' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__)


if TYPE_CHECKING:  # for type checkers and IDEs: the lazy names, eagerly
    from .app.batch.run import run_batch
    from .export.plotting import plot_abstraction, plot_segment_graph
    from .export.writers import read_json, write_json, write_png, write_segment_graph_png, write_svg
    from .features.detail import DetailWarning
    from .features.preprocessing import (
        DownscaleWarning,
        FeatureLines,
        LoadedImage,
        detect_kind,
        extract_feature_lines,
        load_image,
        load_mask,
    )
    from .fit.progressive import Progression, optimize
    from .fit.recovery import ConnectivityWarning
    from .geometry.golden_ladder import FibonacciLadder, GoldenLadder
    from .geometry.primitives import Abstraction, Arc, Circle
    from .images.loading import PageWarning
    from .options import Options
    from .pipeline import Result, abstract
    from .segment_graph import SegmentGraph, build_segment_graph
