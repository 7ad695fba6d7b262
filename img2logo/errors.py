"""The exceptions img2logo raises on bad input or a failed fit.

Every error the library raises on purpose derives from :class:`Img2LogoError`, and
also from the built-in exception a caller would expect (``ValueError`` for a bad
value, ``FileNotFoundError`` for a missing file), so both ``except Img2LogoError``
and ``except ValueError`` catch it. The command line prints the message of an
``Img2LogoError`` as one line and exits non-zero, with no traceback.
"""

from __future__ import annotations


class Img2LogoError(Exception):
    """Base class of every error img2logo raises deliberately."""


class InputNotFoundError(Img2LogoError, FileNotFoundError):
    """An input file (an image, a JSON document) does not exist or is not a file."""


class ImageNotFoundError(InputNotFoundError):
    """The input image path does not exist or is not a file."""


class InvalidImageError(Img2LogoError, ValueError):
    """The input is not a usable image: unreadable, empty, blank, too small."""


class InvalidParameterError(Img2LogoError, ValueError):
    """A parameter is out of range or of the wrong shape or type."""


class FitError(Img2LogoError, ValueError):
    """A fit could not be computed (too few points, degenerate geometry)."""


class OutputError(Img2LogoError, OSError):
    """An output file could not be written (read-only file system, full disk, a folder in the way, ...)."""


class UnknownOptionError(InvalidParameterError, TypeError):
    """A keyword argument that the function does not take (a ``TypeError``, as Python's own)."""
