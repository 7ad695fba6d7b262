"""Options that act on one kind of image only, and the warning that they were ignored.

The command and the batch say so in one line when an image turns out to be of
another kind (:attr:`img2logo.features.preprocessing.FeatureLines.kind`): a
``--subject`` given for what is read as a drawing, a ``--detail`` for a photo.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from ..constants import DETAIL
from ..options import Options

__all__ = ["ONLY_KIND", "ignored_options", "kind_options"]

#: What only an image of a kind has, for which the options of :func:`kind_options` do something.
ONLY_KIND = {"photo": "only a photo has a subject to find", "clipart": "only a clip art has colour regions to keep"}


def kind_options(options: Options, subject: str | None = None) -> dict[str, list[str]]:
    """The options given that act on one kind of image only, as typed: ``{"photo": [...], "clipart": [...]}``.

    ``--subject`` and ``--foreground`` (other than auto) choose a photo's
    subject; ``--detail`` (other than its default) chooses the regions a clip
    art keeps (``--arcs`` acts on every kind: the fit goes past T to meet
    it). ``subject`` is ``--subject`` as typed (it is checked against the
    image, so it is not yet in ``options``).

    Examples
    --------
    >>> from img2logo import Options
    >>> from img2logo.app.kind_options import kind_options
    >>> kind_options(Options(detail=5))
    {'photo': [], 'clipart': ['--detail 5']}
    """
    fg = options.foreground
    photo = [] if subject is None else [f"--subject {subject}"]
    if not (isinstance(fg, str) and fg == "auto"):
        photo.append(f"--foreground {fg if isinstance(fg, str | Path) else 'MASK'}")
    clipart = [] if options.detail == DETAIL else [f"--detail {options.detail}"]
    return {"photo": photo, "clipart": clipart}


def ignored_options(lines: Any, given: Mapping[str, Sequence[str]]) -> list[str]:
    """The warnings that options ``given`` for another kind of image (:func:`kind_options`) are ignored.

    Only a photo has a subject to find (:mod:`img2logo.features.photo.subject`);
    only a clip art has colour regions whose detail to choose
    (:mod:`img2logo.features.detail`). ``lines`` is the run's
    :class:`~img2logo.features.preprocessing.FeatureLines`.
    """
    out = []
    for kind, flags in given.items():
        if flags and lines.kind != kind:
            which = " and ".join(flags)
            verb = "is" if len(flags) == 1 else "are"
            out.append(
                f"{which} {verb} ignored: the image is {lines.kind} ({lines.reason}), and {ONLY_KIND[kind]} "
                f"(give --kind {kind} to treat it as one)"
            )
    return out
