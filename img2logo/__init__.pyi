# The public API of img2logo: one list, read by type checkers and, through lazy_loader.attach_stub,
# by the package itself, which imports each name on first use.
from . import quality as quality
from .app.batch.run import run_batch as run_batch
from .constants import PHI as PHI
from .errors import (
    FitError as FitError,
)
from .errors import (
    ImageNotFoundError as ImageNotFoundError,
)
from .errors import (
    Img2LogoError as Img2LogoError,
)
from .errors import (
    InputNotFoundError as InputNotFoundError,
)
from .errors import (
    InvalidImageError as InvalidImageError,
)
from .errors import (
    InvalidParameterError as InvalidParameterError,
)
from .errors import (
    OutputError as OutputError,
)
from .errors import (
    UnknownOptionError as UnknownOptionError,
)
from .export.plotting import plot_abstraction as plot_abstraction
from .export.plotting import plot_segment_graph as plot_segment_graph
from .export.writers import (
    read_json as read_json,
)
from .export.writers import (
    write_json as write_json,
)
from .export.writers import (
    write_png as write_png,
)
from .export.writers import (
    write_segment_graph_png as write_segment_graph_png,
)
from .export.writers import (
    write_svg as write_svg,
)
from .features.preprocessing import (
    FeatureLines as FeatureLines,
)
from .features.preprocessing import (
    detect_kind as detect_kind,
)
from .features.preprocessing import (
    extract_feature_lines as extract_feature_lines,
)
from .fit.progressive import Progression as Progression
from .fit.progressive import optimize as optimize
from .fit.recovery import ConnectivityWarning as ConnectivityWarning
from .geometry.golden_ladder import FibonacciLadder as FibonacciLadder
from .geometry.golden_ladder import GoldenLadder as GoldenLadder
from .geometry.primitives import Abstraction as Abstraction
from .geometry.primitives import Arc as Arc
from .geometry.primitives import Circle as Circle
from .images.loading import (
    DownscaleWarning as DownscaleWarning,
)
from .images.loading import (
    LoadedImage as LoadedImage,
)
from .images.loading import (
    PageWarning as PageWarning,
)
from .images.loading import (
    load_image as load_image,
)
from .images.loading import (
    load_mask as load_mask,
)
from .options import Options as Options
from .pipeline import Result as Result
from .pipeline import abstract as abstract
from .segment_graph import SegmentGraph as SegmentGraph
from .segment_graph import build_segment_graph as build_segment_graph

__version__: str
