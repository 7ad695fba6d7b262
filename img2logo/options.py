"""The options of a run: one frozen :class:`Options` value, checked when it is made.

Every switch and setting of :func:`img2logo.abstract` is a field of
:class:`Options`, declared once with its default, its check, its command-line
flag and whether the levels record it in ``params``. Everything else reads it
from there: :func:`img2logo.abstract` and :func:`img2logo.fit.progressive.optimize`
take an ``Options`` (or its keywords), :func:`img2logo.app.batch.run.run_batch` checks
one before its workers start (not once per image), the command line builds its
flags from the fields (:func:`cli_fields`), and :meth:`Options.record` is what
every level records. A new switch is one new field here.

An unknown keyword or a bad value fails before any work, with a message naming
the option, what was expected and what came.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from ._validation import check_choice, check_positive
from .constants import DETAIL, LOGO_ARCS, MIN_LADDER_RADIUS, MIN_SEGMENT_LENGTH, RDP_TOLERANCE, STRETCH, TOLERANCE
from .errors import InvalidParameterError, UnknownOptionError
from .option_values import (
    check_detail,
    check_length,
    check_stretch,
    check_symmetry_option,
    parse_budget,
    parse_radii,
    refuse_lock_mask,
)

__all__ = [
    "ABSTRACT_OPTIONS",
    "AUTO",
    "SWITCHES",
    "Options",
    "check_abstract_options",
    "check_lock_mask",
    "check_symmetry_option",
    "cli_fields",
    "refuse_lock_mask",
]

#: Default time budget of a run, s of CPU time of the process running it (on an idle machine about the wall time),
#: from the start of ``abstract()``: past it the merge loop stops at its last level (``Options.time_budget``).
TIME_BUDGET: float = 10.0

#: ``max_arc_distance``'s default: ``PHOTO_MAX_ARC_FACTOR * tolerance`` for a photo, no bound otherwise.
AUTO: str = "auto"

#: Stages an option belongs to: ``"input"`` (feature lines and the segment graph,
#: recorded by :func:`img2logo.abstract` with the values it resolved) or
#: ``"optimize"`` (the progressive optimization, recorded by :meth:`Options.record`).
_STAGES = ("input", "optimize")


def _option(
    default: Any,
    *,
    stage: str = "optimize",
    flags: tuple[str, ...] = (),
    batch: bool = True,
    parse: Callable[[Any], Any] | None = None,
    **cli: Any,
) -> Any:
    """A field of :class:`Options`: its default and how the command line offers it.

    ``flags`` are the command-line flags (none: not on the command line),
    ``cli`` the rest of :meth:`argparse.ArgumentParser.add_argument`'s keywords,
    ``batch`` whether ``img2logo batch`` has it too, and ``parse`` turns the
    flag's text into the value after parsing (raising with its own message).
    """
    return field(
        default=default,
        metadata={"stage": stage, "flags": flags, "batch": batch, "parse": parse, "cli": cli},
    )


def _px(default: float, flag: str, what: str, *more: str, stage: str = "optimize", note: str = "") -> Any:
    """A length option in px with its default: ``--flag PX``."""
    extra = f"; {note}" if note else ""
    return _option(
        default,
        stage=stage,
        flags=(flag, *more),
        type=float,
        metavar="PX",
        help=f"{what}, px{extra} (default {default})",
    )


def _switch(flag: str, what: str, *, default: bool = True) -> Any:
    """An on/off option: on by default, ``flag`` (``--no-...``) switches ``what`` off; or off, ``flag`` turns it on."""
    if default:
        return _option(True, flags=(flag,), action="store_false", help=f"switch off {what}")
    return _option(False, flags=(flag,), action="store_true", help=what)


@dataclass(frozen=True)
class Options:
    """Every switch and setting of a run (paper Sec. 4-7 and beyond), checked when made.

    ``Options(tolerance=7.0, ladder="fibonacci")`` or
    ``Options.from_keywords({...})``; change one with :func:`dataclasses.replace`
    (checked again). Lengths are in px of the working image: the input, or for an
    input over 512 px (``PHOTO_WORK_SIDE``, ``SYNTHETIC_WORK_SIDE``) its downscale, whose
    results :func:`img2logo.abstract` scales back to the input's pixels (T and E^s with them).

    Attributes
    ----------
    kind : {"auto", "photo", "clipart", "drawing"}
        The kind of input (:func:`img2logo.extract_feature_lines`).
    rdp_tolerance : float
        Ramer-Douglas-Peucker tolerance of the over-segmentation, px (> 0).
    min_length : float
        Free-hanging segments shorter than this are dropped, px (>= 0).
    foreground : {"auto", "none", "grabcut"}, path or ndarray of bool
        Photos: the subject drawn (:func:`img2logo.features.photo.subject.find_subject`).
    subject : (x, y, w, h), "X,Y,W,H" or None
        Photos: a rectangle around the object that seeds its segmentation, px.
    detail : int
        Clip art: the regions kept besides the background, at least 1
        (:func:`img2logo.features.detail.merge_by_importance`): the least
        important (by Ward's criterion: contrast, length, area) merge into their
        neighbours first. The silhouette, its ink outline and the dark marks on
        the object (eyes) are always kept. Other kinds: unused.
    arcs : int or None
        The logo's arc budget, at least 1, or None (default: about
        ``LOGO_ARCS`` = 40, by the fit alone). Every kind: where the fit within
        T has more arcs, merging goes on past T, up to ``stretch`` T, until the
        logo has this many (:func:`img2logo.fit.progressive.optimize`); where
        it does, the tangent joins add no arcs past it. A clip
        art given a budget also merges regions first
        (:func:`img2logo.features.detail.merge_by_importance`): after
        ``detail``, the regions of least Ward weight per predicted arc, until
        the logo's predicted arcs (:func:`img2logo.features.boundary_cost.boundary_arcs`)
        are at most this; the silhouette and the eyes are kept beyond it.
    stroke_width : float or None
        Width of the logo's strokes in the SVG and PNG, px (> 0), recorded in
        ``params``; None: a line drawing's measured median stroke width
        (:attr:`img2logo.features.preprocessing.FeatureLines.stroke_width`), for the
        other kinds the writers' default
        (:func:`img2logo.export.plotting.default_stroke_width`).
    symmetry : {"none", "auto", "vertical", "horizontal"} or float
        A mirror-symmetric logo (:mod:`img2logo.fit.symmetry`): ``auto`` keeps the
        best mirror axis of the feature lines if it scores well enough; the
        others force its direction (degrees from +x towards +y); ``none``: free.
        Not with a lock mask (:func:`check_lock_mask`).
    tolerance : float
        T of Eqn. 1, px (> 0): merging stops before E^s would exceed it (but
        for ``stretch``).
    stretch : float
        Simplicity past T (beyond the paper), at least 1: where the logo within
        T has more arcs than its budget (``arcs``, default ``LOGO_ARCS``),
        merging goes on, the cheapest merge first, until it has that many or
        E^s would pass ``stretch`` x T; the silhouette's arcs are then held to
        ``stretch`` x T each. 1: the paper's rule (stop at T).
    ladder : {"phi", "fibonacci"}
        Radii ``phi ** (k + bias)`` (Eqn. 10) or ``unit * F(k)`` (Fig. 2b).
    bias : float or None
        The phi ladder's bias sigma in [0, 1); None: Eqn. 14 on the longest segment.
    unit : float or None
        The Fibonacci ladder's unit, px; None: chosen from the longest segment.
    exponents : tuple of int or None
        Only these ladder exponents k (Sec. 7, Fig. 15).
    rounding : {"nearest", "ceil"}
        Radius snapping: nearest rung in log space, or up as in Eqn. 12.
    arc_selection : {"frechet", "sum_of_squares"}
        How an arc is chosen among the candidates on its circle (Fig. 9).
    max_arc_distance : float, None or "auto"
        A merge whose new arc is farther (discrete Fréchet) than this from its
        pixels is rejected, px; None: no bound (the paper); "auto" (default):
        ``PHOTO_MAX_ARC_FACTOR * tolerance`` for a photo, no bound otherwise.
    connectivity, inner_junctions, merging, avoid_intersections, localized, simplify : bool
        The paper's switches: the connectivity constraint (Fig. 11c), junctions
        inside merged arcs as constraints (Fig. 11d), merging (Fig. 11e),
        redundant-intersection avoidance (Fig. 12), localized fitting and
        line-segment simplification (Sec. 5.4, Table 3).
    lines : bool
        Nearly straight segments become straight lines (Sec. 9, Fig. 20b).
    tangency : bool
        Tangent joins (beyond the paper): where two arcs end at a node where the
        input's line runs on smoothly, their circles touch there (an equality of
        the constrained fit, Eqn. 13). Off: the paper's kinks.
    time_budget : float or None
        Seconds of CPU time (of the process running it; on an idle machine
        about the wall time) a run may take, > 0; None: no bound. Counted from
        the start of :func:`img2logo.abstract` (reading the image, its feature
        lines and segment graph included), or of
        :func:`img2logo.fit.progressive.optimize` called alone, once the
        compiled kernels have loaded: their one compilation on a new machine
        is not counted (without a C compiler numba's JIT compiles each kernel
        on its first call, inside the budget).
        Past it the merge loop stops at its last level (every level is within T)
        and the tangent joins try no level before it, with a
        :class:`~img2logo.fit.progressive.TimeBudgetWarning` saying so in one line.
        A run that stays within it is the same as an unbounded one; not recorded in
        ``params``. CPU time, not wall time: other processes' load does not shorten it.

    Raises
    ------
    InvalidParameterError
        Naming the first value out of range (see :func:`check_abstract_options`).

    Examples
    --------
    >>> from img2logo import Options
    >>> opts = Options(tolerance=9.0, ladder="fibonacci")
    >>> opts.tolerance, opts.ladder
    (9.0, 'fibonacci')
    """

    # ----------------------------------------------------------------- feature lines, segment graph
    kind: str = _option(
        "auto",
        stage="input",
        flags=("--kind",),
        choices=("auto", "photo", "clipart", "drawing"),
        help="kind of input (default: auto, chosen from the image and reported)",
    )
    rdp_tolerance: float = _px(
        RDP_TOLERANCE, "--rdp", "Ramer-Douglas-Peucker tolerance of the over-segmentation", stage="input"
    )
    min_length: float = _px(
        MIN_SEGMENT_LENGTH, "--min-length", "drop free-hanging segments shorter than this", stage="input"
    )
    foreground: object = _option(
        "auto",
        stage="input",
        flags=("--foreground",),
        metavar="auto|none|grabcut|MASK.png",
        help="photos: the subject drawn: auto (default: the main object if there is one, else the whole image), "
        "none (the whole image), grabcut (what GrabCut finds), or a mask image (white = object)",
    )
    subject: object = _option(
        None,
        stage="input",
        flags=("--subject",),
        batch=False,
        metavar="X,Y,W,H",
        help="photos: a rectangle around the object, px (x, y of its top-left corner, width, height); "
        "it seeds the object's segmentation",
    )
    symmetry: object = _option(
        "none",
        stage="input",
        flags=("--symmetry",),
        metavar="auto|none|vertical|horizontal|DEGREES",
        help="a mirror-symmetric logo: auto (the best mirror axis of the feature lines, kept if it scores at least "
        "the threshold; said in one line), vertical, horizontal or the axis direction in degrees from +x towards "
        "+y (forced); none (default): free",
    )
    detail: int = _option(
        DETAIL,
        stage="input",
        flags=("--detail",),
        type=int,
        metavar="N",
        help="clip art: the regions kept besides the background; the least important (hatching, highlights, "
        "blotches, tiny fills) merge into their neighbours first; the silhouette and dark marks such as eyes are "
        f"always kept (default {DETAIL})",
    )
    arcs: int | None = _option(
        None,
        stage="input",
        flags=("--arcs",),
        type=int,
        metavar="N",
        help="the logo's arc budget: where the fit within T has more arcs, merging goes on past T (up to "
        "--stretch times T); a clip art also merges regions first, the least visual weight (contrast times area) "
        "per predicted arc first, keeping the silhouette and dark marks such as eyes (default: about "
        f"{LOGO_ARCS} arcs, by the fit alone)",
    )
    stroke_width: float | None = _option(
        None,
        stage="input",
        flags=("--stroke-width",),
        type=float,
        metavar="PX",
        help="width of the logo's strokes in the SVG and PNG, px (default: a line drawing's own median stroke "
        "width, measured; clip arts and photos 1/128 of the longer image side)",
    )
    # ----------------------------------------------------------------- the optimization
    tolerance: float = _px(
        TOLERANCE, "--tolerance", "largest similarity error E^s", "-T", note="larger gives fewer arcs"
    )
    stretch: float = _option(
        STRETCH,
        flags=("--stretch",),
        type=float,
        metavar="F",
        help="how far past T merging may go, as a factor of T, while the logo has more arcs than its budget "
        f"(--arcs); the silhouette's arcs are held to it too; 1: stop at T, as the paper does (default {STRETCH:.3f}, "
        "phi)",
    )
    ladder: str = _option(
        "phi",
        flags=("--ladder",),
        choices=("phi", "fibonacci"),
        help="the radii: phi**(k + bias) (default, the paper) or unit * F(k), F(k) = 1, 1, 2, 3, 5, 8, ... the "
        "Fibonacci grid designers draw (paper Fig. 2b)",
    )
    bias: float | None = _option(
        None, flags=("--bias",), type=float, metavar="S", help="phi ladder bias sigma in [0, 1) (default: Eqn. 14)"
    )
    unit: float | None = _option(
        None,
        flags=("--unit",),
        type=float,
        metavar="PX",
        help="Fibonacci ladder unit, the smallest radius, px (default: the largest <= 1 px putting the longest "
        "segment's radius on a rung)",
    )
    exponents: tuple[int, ...] | None = _option(
        None,
        flags=("--radii",),
        parse=parse_radii,
        metavar="K1,K2,...",
        help="only these ladder exponents k: radii phi**(k + bias) (or unit * F(k))",
    )
    rounding: str = _option(
        "nearest",
        flags=("--rounding",),
        choices=("nearest", "ceil"),
        help="radius snapping (ceil: the paper's Eqn. 12)",
    )
    arc_selection: str = _option("frechet")
    max_arc_distance: float | str | None = _option(AUTO)
    connectivity: bool = _switch("--no-connectivity", "the connectivity constraint (Fig. 11c)")
    inner_junctions: bool = _switch("--no-inner-junctions", "junctions inside merged arcs as constraints (Fig. 11d)")
    merging: bool = _switch("--no-merging", "merging segments (Fig. 11e)")
    avoid_intersections: bool = _switch(
        "--no-intersection-avoidance", "rejecting merges that leave redundant intersections (Fig. 12)"
    )
    localized: bool = _switch("--no-localized", "localized fitting (Sec. 5.4)")
    simplify: bool = _switch("--no-simplify", "line-segment simplification (Sec. 5.4)")
    lines: bool = _switch(
        "--lines",
        "let nearly straight segments be straight lines, not arcs of huge circles (paper Sec. 9, Fig. 20b)",
        default=False,
    )
    tangency: bool = _switch(
        "--no-tangency", "tangent joins: circles that touch where the input's line runs on smoothly (beyond the paper)"
    )
    time_budget: float | None = _option(
        TIME_BUDGET,
        flags=("--time-budget",),
        parse=parse_budget,
        metavar="S|none",
        help="seconds of CPU time the run may take, from its start; past them merging stops at the last level, which "
        f"is within T, and says so in one line; none: no bound (default {TIME_BUDGET:g})",
    )

    def __post_init__(self) -> None:
        import numpy as np

        from .geometry.golden_ladder import make_ladder

        put = object.__setattr__
        put(self, "tolerance", check_length(self.tolerance, "tolerance"))
        put(self, "stretch", check_stretch(self.stretch))
        put(self, "rdp_tolerance", check_length(self.rdp_tolerance, "rdp_tolerance"))
        put(self, "min_length", check_length(self.min_length, "min_length", allow_zero=True))
        put(self, "detail", check_detail(self.detail))
        if self.arcs is not None:
            put(self, "arcs", check_detail(self.arcs, "arcs", "arcs"))
        if self.stroke_width is not None:
            put(self, "stroke_width", check_length(self.stroke_width, "stroke_width"))
        check_choice(self.kind, "kind", ("auto", "photo", "clipart", "drawing"))
        # The photo modules load only for a value to check (the default "auto" needs none): a clip art's run skips them.
        if not (isinstance(self.foreground, str) and self.foreground == "auto"):
            from .features.photo.subject import check_foreground_option

            check_foreground_option(self.foreground)
        if self.subject is not None:
            from .features.photo.subject import subject_rectangle_numbers

            subject_rectangle_numbers(self.subject)
        if self.max_arc_distance is not None and not (
            isinstance(self.max_arc_distance, str) and self.max_arc_distance == AUTO
        ):
            put(self, "max_arc_distance", check_length(self.max_arc_distance, "max_arc_distance"))
        if self.unit is not None:
            put(self, "unit", check_length(self.unit, "unit", low=MIN_LADDER_RADIUS))
        if self.time_budget is not None:
            if isinstance(self.time_budget, bool | np.bool_ | str):
                what = f"{self.time_budget!r}"
                raise InvalidParameterError(f"time_budget must be a number of seconds or None, got {what}")
            put(self, "time_budget", check_positive(self.time_budget, "time_budget"))
        if isinstance(self.bias, bool | np.bool_ | str):
            raise InvalidParameterError(f"bias must be a number in [0, 1), got {self.bias!r}")
        for name in SWITCHES:
            value = getattr(self, name)
            if not isinstance(value, bool | np.bool_):
                raise InvalidParameterError(f"{name} must be True or False, got {value!r}")
            put(self, name, bool(value))
        check_symmetry_option(self.symmetry)
        check_choice(self.arc_selection, "arc_selection", ("frechet", "sum_of_squares"))
        make_ladder(
            self.ladder,
            1.0,  # a stand-in radius: only the values given are checked
            bias=self.bias,
            unit=self.unit,
            exponents=self.exponents,
            rounding=self.rounding,
        )
        if self.exponents is not None:
            put(self, "exponents", tuple(int(k) for k in np.ravel(np.asarray(self.exponents, dtype=object))))

    # ----------------------------------------------------------------- building one
    @classmethod
    def from_keywords(
        cls, keywords: Mapping[str, Any], *, base: Options | None = None, also: frozenset[str] = frozenset()
    ) -> Options:
        """The options named in ``keywords`` (the others from ``base``, default the defaults), checked.

        Parameters
        ----------
        keywords : mapping
            Option name -> value.
        base : Options, optional
            Where the options not named come from.
        also : frozenset of str
            Other names the caller accepts (and handles itself): they are not
            unknown, and are ignored here (``abstract``'s ``lock_mask``, ``progress``).

        Raises
        ------
        UnknownOptionError
            Naming the first unknown option and the nearest known name (an
            InvalidParameterError and a TypeError).
        InvalidParameterError
            Naming the first value out of range.
        """
        allowed = ABSTRACT_OPTIONS_FIELDS | also
        for name in keywords:
            if name not in allowed:
                import difflib  # only for the message

                near = difflib.get_close_matches(str(name), sorted(allowed), n=1)
                hint = f" (did you mean {near[0]!r}?)" if near else ""
                raise UnknownOptionError(
                    f"unknown option {name!r}{hint}: expected keyword arguments of img2logo.abstract "
                    f"({', '.join(sorted(allowed))})"
                )
        given = {k: v for k, v in keywords.items() if k in ABSTRACT_OPTIONS_FIELDS}
        return dataclasses.replace(base or cls(), **given)

    # ----------------------------------------------------------------- reading one
    def keywords(self) -> dict[str, Any]:
        """The options that differ from the defaults, as keyword arguments of :func:`img2logo.abstract`."""
        default = Options()
        return {
            f.name: getattr(self, f.name)
            for f in _fields()
            if _differs(getattr(self, f.name), getattr(default, f.name))
        }

    def record(self) -> dict[str, Any]:
        """What every level records in ``params`` of the optimization's options (JSON-safe values).

        ``tolerance``, ``bias_given``, ``exponents`` (a list or None), ``rounding``,
        the Fibonacci ladder's ``ladder`` and ``unit_given`` (only on that ladder),
        every switch, ``arc_selection``, ``max_arc_distance`` (only when there is
        a bound; "auto" is resolved by :func:`img2logo.abstract` first), and any
        optimization option added later under its own name.
        """
        out: dict[str, Any] = {}
        for f in _fields("optimize"):
            value = getattr(self, f.name)
            if f.name == "bias":
                out["bias_given"] = value
            elif f.name == "exponents":
                out["exponents"] = list(value) if value else None
            elif f.name == "ladder":
                if value == "fibonacci":
                    out["ladder"] = "fibonacci"
            elif f.name == "unit":
                if self.ladder == "fibonacci":
                    out["unit_given"] = value
            elif f.name == "max_arc_distance":
                if value is not None and value != AUTO:
                    out["max_arc_distance"] = value
            elif f.name == "time_budget":
                continue  # how long a run may take, not what it makes (a run within it is an unbounded run)
            else:
                out[f.name] = value
        return out

    @property
    def arc_bound(self) -> float | None:
        """``max_arc_distance`` as a bound in px, or None ("auto" counts as none: the kind is not known here)."""
        value = self.max_arc_distance
        return None if value is None or value == AUTO else float(value)


def _differs(a: Any, b: Any) -> bool:
    import numpy as np

    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return True
    return type(a) is not type(b) or a != b


def _fields(stage: str | None = None) -> Iterator[dataclasses.Field[Any]]:
    for f in dataclasses.fields(Options):
        if stage is None or f.metadata["stage"] == stage:
            yield f


def cli_fields(*, batch: bool = False) -> list[tuple[str, dataclasses.Field[Any]]]:
    """The options the command line offers: (stage, field) with ``field.metadata`` giving flags and argparse keywords.

    With ``batch``, those of ``img2logo batch``. The flag's value is
    ``metadata["parse"]`` of the parsed text when given, and goes to the option
    of the field's name (``dest``).
    """
    return [
        (f.metadata["stage"], f)
        for f in dataclasses.fields(Options)
        if f.metadata["flags"] and (f.metadata["batch"] or not batch)
    ]


#: The on/off switches of the optimization (paper Fig. 11, 12, Sec. 5.4, 9): the boolean options.
SWITCHES: tuple[str, ...] = tuple(f.name for f in dataclasses.fields(Options) if isinstance(f.default, bool))

#: Names of the fields of :class:`Options`.
ABSTRACT_OPTIONS_FIELDS: frozenset[str] = frozenset(f.name for f in dataclasses.fields(Options))

#: Keyword arguments of :func:`img2logo.abstract` (not ``image``): the options and
#: ``lock_mask`` (an image's mask) and ``progress`` (a callback), which are no options.
ABSTRACT_OPTIONS: frozenset[str] = ABSTRACT_OPTIONS_FIELDS | {"lock_mask", "progress"}


def check_abstract_options(options: Mapping[str, Any], allowed: frozenset[str] = ABSTRACT_OPTIONS) -> Options:
    """Check keyword arguments of :func:`img2logo.abstract` without doing any work; the :class:`Options`.

    Parameters
    ----------
    options : mapping
        Name -> value; names not given keep the defaults.
    allowed : frozenset of str
        The names accepted (a batch does not take ``lock_mask`` nor ``progress``).

    Raises
    ------
    UnknownOptionError
        Naming the first unknown option and the nearest known name.
    InvalidParameterError
        Naming the first value out of range: ``tolerance`` and ``rdp_tolerance`` > 0 px,
        ``min_length`` >= 0 px, ``kind``, ``foreground`` and ``subject``,
        ``max_arc_distance`` > 0 px, the switches True or False, ``symmetry``
        (and not with ``lock_mask``),
        ``arc_selection``, the ladder's ``ladder``, ``bias``, ``unit``,
        ``exponents`` and ``rounding`` (as :func:`img2logo.geometry.golden_ladder.make_ladder`
        checks them).
    """
    checked = Options.from_keywords(options, also=allowed - ABSTRACT_OPTIONS_FIELDS)
    check_lock_mask(checked, options.get("lock_mask"))
    return checked


def check_lock_mask(options: Options, lock_mask: object) -> None:
    """Raise if a lock mask is given with a symmetric run: the two cannot be combined."""
    if check_symmetry_option(options.symmetry) is not None:
        refuse_lock_mask(lock_mask)
