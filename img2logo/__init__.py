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

from __future__ import annotations

from collections.abc import Callable as _Callable

__version__ = "0.1.0"

#: lazy_loader's (``__getattr__``, ``__dir__``, ``__all__``) of the stub, made on first use: the command line
#: imports its own modules (``import img2logo.app.cli``) and never reads a public name here, so it does not
#: parse the stub (with ``ast``, about 3 ms of CPU a start).
_attached: tuple[_Callable[[str], object], _Callable[[], list[str]], list[str]] | None = None


def _public() -> tuple[_Callable[[str], object], _Callable[[], list[str]], list[str]]:
    global _attached
    if _attached is None:
        import lazy_loader

        load, names, public = lazy_loader.attach_stub(__name__, __file__)
        _attached = (load, names, [*public, "__version__"])
    return _attached


def __getattr__(name: str) -> object:
    load, _, public = _public()
    if name == "__all__":
        return list(public)
    if name not in public:  # Python's own message, not lazy_loader's
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return load(name)


def __dir__() -> list[str]:
    return _public()[1]()
