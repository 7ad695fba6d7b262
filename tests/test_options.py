"""Tests of the options value: defaults, checks, what the levels record, what the command line offers."""

from __future__ import annotations

import argparse
import dataclasses
import pickle

import pytest

from img2logo.errors import InvalidParameterError, UnknownOptionError
from img2logo.options import (
    ABSTRACT_OPTIONS,
    AUTO,
    SWITCHES,
    Options,
    check_abstract_options,
    cli_fields,
)


def test_defaults_and_record():
    o = Options()
    assert (o.tolerance, o.kind, o.ladder, o.max_arc_distance, o.arc_bound) == (5.0, "auto", "phi", AUTO, None)
    assert o.record() == {
        "tolerance": 5.0,
        "stretch": pytest.approx(1.618, abs=1e-3),
        "bias_given": None,
        "exponents": None,
        "rounding": "nearest",
        "arc_selection": "frechet",
        **dict.fromkeys(SWITCHES, True),
        "lines": False,
    }
    fib = Options(ladder="fibonacci", unit=2.0, exponents=[5, 3], max_arc_distance=4)
    record = fib.record()
    assert record["ladder"] == "fibonacci" and record["unit_given"] == 2.0
    assert record["exponents"] == [5, 3] and record["max_arc_distance"] == 4.0
    assert fib.exponents == (5, 3) and fib.arc_bound == 4.0


def test_switches_are_the_boolean_options():
    assert SWITCHES == (
        "connectivity",
        "inner_junctions",
        "merging",
        "avoid_intersections",
        "localized",
        "simplify",
        "lines",
        "tangency",
    )
    assert ABSTRACT_OPTIONS == {f.name for f in dataclasses.fields(Options)} | {"lock_mask", "progress"}


@pytest.mark.parametrize(
    ("keywords", "message"),
    [
        ({"tolerance": 0}, r"^tolerance must be > 0, got 0\.0$"),
        ({"min_length": -5}, r"^min_length must be >= 0, got -5\.0$"),
        ({"kind": "painting"}, "kind must be one of 'auto', 'photo', 'clipart', 'drawing', got 'painting'"),
        ({"merging": 1}, r"^merging must be True or False, got 1$"),
        ({"max_arc_distance": -1}, r"^max_arc_distance must be > 0"),
        ({"arc_selection": "l2"}, "arc_selection must be one of 'frechet', 'sum_of_squares'"),
        ({"bias": 1.5}, r"bias must be in \[0, 1\)"),
        ({"unit": 2.0}, "unit is a parameter of the Fibonacci ladder"),
        ({"exponents": []}, "exponents must not be empty"),
        ({"subject": "1,2,3"}, "subject must be a rectangle X,Y,W,H of four numbers"),
    ],
)
def test_bad_values_are_refused_when_made(keywords, message):
    with pytest.raises(InvalidParameterError, match=message):
        Options(**keywords)
    with pytest.raises(InvalidParameterError, match=message):
        Options.from_keywords(keywords)


def test_unknown_keywords_name_the_nearest():
    with pytest.raises(UnknownOptionError, match=r"unknown option 'connectvity' \(did you mean 'connectivity'\?\)"):
        Options.from_keywords({"connectvity": False})
    with pytest.raises(UnknownOptionError, match=r"expected keyword arguments of img2logo.abstract \(.*lock_mask"):
        check_abstract_options({"colour": "red"})
    # A batch takes no lock mask: named unknown there.
    with pytest.raises(UnknownOptionError, match="unknown option 'lock_mask'"):
        check_abstract_options({"lock_mask": None}, ABSTRACT_OPTIONS - {"lock_mask", "progress"})
    assert check_abstract_options({"lock_mask": None, "tolerance": 7}) == Options(tolerance=7.0)


def test_from_keywords_replaces_a_base_and_replace_checks_again():
    base = Options(tolerance=9.0, merging=False)
    o = Options.from_keywords({"lines": True}, base=base)
    assert (o.tolerance, o.merging, o.lines) == (9.0, False, True)
    assert o.keywords() == {"tolerance": 9.0, "merging": False, "lines": True}
    with pytest.raises(InvalidParameterError, match="tolerance must be > 0"):
        dataclasses.replace(o, tolerance=-1.0)
    assert pickle.loads(pickle.dumps(o)) == o


def test_the_command_line_flags_come_from_the_fields():
    p = argparse.ArgumentParser()
    for _, f in cli_fields():
        p.add_argument(*f.metadata["flags"], dest=f.name, default=f.default, **f.metadata["cli"])
    args = p.parse_args(["--no-merging", "--lines", "-T", "7", "--radii", "3,5", "--rdp", "3"])
    assert (args.merging, args.lines, args.tolerance, args.rdp_tolerance) == (False, True, 7.0, 3.0)
    exponents = dict((f.name, f) for _, f in cli_fields())["exponents"]
    assert exponents.metadata["parse"](args.exponents) == (3, 5)
    with pytest.raises(InvalidParameterError, match="--radii must be integers separated by commas"):
        exponents.metadata["parse"]("3,x")
    flags = {f.name for _, f in cli_fields()}
    assert set(SWITCHES) <= flags and "subject" in flags
    assert "subject" not in {f.name for _, f in cli_fields(batch=True)}
    assert {f.name for _, f in cli_fields()} == ABSTRACT_OPTIONS - {
        "lock_mask",
        "progress",
        "arc_selection",
        "max_arc_distance",
    }


# --- bounds and types at the boundary ------------------------------
@pytest.mark.parametrize(
    ("keywords", "message"),
    [
        ({"rdp_tolerance": 1e308}, r"^rdp_tolerance must be at most 1e\+07 px \(longer than any image\), got 1e\+308$"),
        ({"rdp_tolerance": 1e200}, r"^rdp_tolerance must be at most 1e\+07 px"),
        ({"tolerance": 1e300}, r"^tolerance must be at most 1e\+07 px"),
        ({"min_length": 1e30}, r"^min_length must be at most 1e\+07 px"),
        ({"max_arc_distance": 1e30}, r"^max_arc_distance must be at most 1e\+07 px"),
        ({"ladder": "fibonacci", "unit": 1e308}, r"^unit must be in 0\.001\.\.1e\+07 px, got 1e\+308$"),
        ({"ladder": "fibonacci", "unit": 1e-9}, r"^unit must be in 0\.001\.\.1e\+07 px, got 1e-09$"),
        (
            {"exponents": [99999]},
            r"^exponents \(--radii\) must be in -14\.\.33 \(radii phi\*\*\(k \+ bias\) .* got k = 99999$",
        ),
        ({"exponents": [3, -1000000]}, r"^exponents \(--radii\) must be in -14\.\.33 .* got k = -1000000$"),
        ({"ladder": "fibonacci", "exponents": [2, 99999]}, r"^exponents \(--radii\) of the Fibonacci ladder of unit"),
        ({"tolerance": "5"}, r"^tolerance must be a number of px, got '5'$"),
        ({"tolerance": True}, r"^tolerance must be a number of px, got True$"),
        ({"rdp_tolerance": "2"}, r"^rdp_tolerance must be a number of px, got '2'$"),
        ({"bias": "0.5"}, r"^bias must be a number in \[0, 1\), got '0\.5'$"),
        ({"symmetry": 1e308}, r"^symmetry angle must be a number of degrees in -360\.\.360, got 1e\+308$"),
        ({"symmetry": "-360.5"}, r"^symmetry angle must be a number of degrees in -360\.\.360, got '-360\.5'$"),
    ],
)
def test_out_of_range_lengths_and_radii_are_refused_without_numpy_warnings(keywords, message):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow RuntimeWarning would fail here
        with pytest.raises(InvalidParameterError, match=message):
            Options(**keywords)


def test_the_largest_lengths_and_radii_are_accepted():
    o = Options(tolerance=1e7, rdp_tolerance=1e7, exponents=[-14, 33])
    assert (o.tolerance, o.exponents) == (1e7, (-14, 33))
    assert Options(ladder="fibonacci", unit=1e-3).unit == 1e-3
    assert Options(symmetry=-360).symmetry == -360 and Options(symmetry="360").symmetry == "360"
