"""img2logo: golden ratio logos from images (Hsiao et al., CGF 2023).

The pipeline flows one way: image -> feature lines (:mod:`img2logo.features`) -> segment
graph L = {S, J} (:mod:`img2logo.segment_graph`) -> levels of abstraction
(:mod:`img2logo.fit`) -> design edits (:mod:`img2logo.design`) -> files
(:mod:`img2logo.export`). The public names, listed once in ``__init__.pyi``, are
imported on first use (``lazy_loader.attach_stub``, PEP 562), so ``import img2logo``
stays fast for the command line.

Examples
--------
>>> import img2logo
>>> image = img2logo.data.ring()  # a black ring, 50 px round, on 160 x 160 px
>>> result = img2logo.abstract(image, progress=False)
>>> [(round(arc.circle.r, 1), arc.is_full_circle) for arc in result.final.arcs]
[(50.0, True)]
"""

import lazy_loader as _lazy

__version__ = "0.1.0"

_load, __dir__, __all__ = _lazy.attach_stub(__name__, __file__)
__all__ = [*__all__, "__version__"]


def __getattr__(name: str) -> object:
    if name not in __all__:  # Python's own message, not lazy_loader's
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return _load(name)
