# The public API of img2logo: one list, read by type checkers and, through lazy_loader.attach_stub,
# by the package itself, which imports each name on first use.
from . import data as data, quality as quality
from .app.batch.run import run_batch as run_batch
from .constants import PHI as PHI
from .errors import (
    FitError as FitError,
    ImageNotFoundError as ImageNotFoundError,
    Img2LogoError as Img2LogoError,
    InputNotFoundError as InputNotFoundError,
    InvalidImageError as InvalidImageError,
    InvalidParameterError as InvalidParameterError,
    OutputError as OutputError,
    UnknownOptionError as UnknownOptionError,
)
from .export.plotting import plot_abstraction as plot_abstraction, plot_segment_graph as plot_segment_graph
from .export.writers import (
    read_json as read_json,
    write_json as write_json,
    write_png as write_png,
    write_segment_graph_png as write_segment_graph_png,
    write_svg as write_svg,
)
from .features.detail import DetailWarning as DetailWarning
from .features.preprocessing import (
    FeatureLines as FeatureLines,
    detect_kind as detect_kind,
    extract_feature_lines as extract_feature_lines,
)
from .fit.progressive import Progression as Progression, TimeBudgetWarning as TimeBudgetWarning, optimize as optimize
from .fit.recovery import ConnectivityWarning as ConnectivityWarning
from .geometry.abstraction import Abstraction as Abstraction
from .geometry.golden_ladder import FibonacciLadder as FibonacciLadder, GoldenLadder as GoldenLadder
from .geometry.primitives import Arc as Arc, Circle as Circle
from .images.loading import (
    DownscaleWarning as DownscaleWarning,
    LoadedImage as LoadedImage,
    PageWarning as PageWarning,
    load_image as load_image,
    load_mask as load_mask,
)
from .options import Options as Options
from .pipeline import Result as Result, abstract as abstract
from .segment_graph import SegmentGraph as SegmentGraph, build_segment_graph as build_segment_graph

__version__: str
