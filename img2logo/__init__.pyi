# The public API of img2logo: one list, read by type checkers and, through lazy_loader.attach_stub,
# by the package itself, which imports each name on first use.
from . import quality
from .app.batch.run import run_batch
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
from .export.plotting import plot_abstraction, plot_segment_graph
from .export.writers import read_json, write_json, write_png, write_segment_graph_png, write_svg
from .features.preprocessing import FeatureLines, detect_kind, extract_feature_lines
from .fit.progressive import Progression, optimize
from .fit.recovery import ConnectivityWarning
from .geometry.golden_ladder import FibonacciLadder, GoldenLadder
from .geometry.primitives import Abstraction, Arc, Circle
from .images.loading import DownscaleWarning, LoadedImage, PageWarning, load_image, load_mask
from .options import Options
from .pipeline import Result, abstract
from .segment_graph import SegmentGraph, build_segment_graph

__version__: str
