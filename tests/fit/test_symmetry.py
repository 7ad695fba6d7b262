"""Tests of img2logo.fit.symmetry: the mirror axis, the symmetric segment graph, symmetric levels, output."""

from __future__ import annotations

import json
import math
import re
import warnings

import cv2
import numpy as np
import pytest
from helpers import blank

import img2logo
from img2logo import InvalidParameterError
from img2logo.app.cli import main
from img2logo.export.contract import to_document
from img2logo.export.writers import to_svg
from img2logo.fit.constants import SYMMETRY_THRESHOLD
from img2logo.fit.constrained_fit import fit_constrained
from img2logo.fit.symmetry import (
    Axis,
    check_symmetry_option,
    choose_axis,
    circle_pairs,
    find_axis,
    half_graph,
    is_symmetric,
)
from img2logo.segment_graph import SegmentGraph

BLACK = (0, 0, 0)


def gull(rotate: float = 0.0, asymmetric: bool = False) -> np.ndarray:
    """Two mirrored arcs joined on the axis x = 120 and a circle centred on it (240 px, RGB).

    ``rotate`` turns the drawing by that many degrees (counter-clockwise on
    screen) about the image centre; ``asymmetric`` replaces the right arc by a
    square off the axis.
    """
    im = blank(240)
    cv2.ellipse(im, (70, 170), (50, 50), 0, 200, 360, BLACK, 4, cv2.LINE_AA)
    if asymmetric:
        cv2.rectangle(im, (150, 40), (215, 95), BLACK, 4, cv2.LINE_AA)
    else:
        cv2.ellipse(im, (170, 170), (50, 50), 0, 180, 340, BLACK, 4, cv2.LINE_AA)
    cv2.circle(im, (120, 80), 30, BLACK, 4, cv2.LINE_AA)
    if rotate:
        turn = cv2.getRotationMatrix2D((120, 120), rotate, 1.0)
        im = cv2.warpAffine(im, turn, (240, 240), borderValue=(255, 255, 255))
    return im


@pytest.fixture(scope="module")
def symmetric_run():
    return img2logo.abstract(gull(), kind="drawing", symmetry="auto", progress=False)


def record(level) -> tuple[list[float], list[float]]:
    rec = level.params["symmetry"]
    return rec["point"], rec["direction"]


# --------------------------------------------------------------------------- the axis
def test_the_axis_of_a_symmetric_drawing_is_found_upright(symmetric_run):
    choice = symmetric_run.symmetry
    assert choice.axis is not None and choice.axis.score >= SYMMETRY_THRESHOLD
    assert choice.axis.angle == pytest.approx(90.0, abs=1e-9)  # made exactly upright
    assert choice.axis.point[0] == pytest.approx(120.0, abs=1.0)
    assert "symmetric" in choice.description


def test_a_rotated_copy_gives_the_rotated_axis():
    lines = img2logo.extract_feature_lines(img2logo.load_image(gull(rotate=30.0)), kind="drawing").lines
    axis = find_axis(lines)
    # Turned 30 degrees counter-clockwise on screen (y down): the upright axis is at 60 degrees.
    assert axis.angle == pytest.approx(60.0, abs=1.0)
    assert axis.score >= SYMMETRY_THRESHOLD
    centre = np.array([120.0, 120.0])
    pivot = np.array([120.0, 80.0])  # the circle's centre, on the axis before turning
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    turned = centre + np.array([[c, s], [-s, c]]) @ (pivot - centre)
    normal = np.array([-axis.direction[1], axis.direction[0]])
    assert abs(float((turned - axis.point) @ normal)) < 2.0


def test_an_asymmetric_drawing_gives_no_axis():
    run = img2logo.abstract(gull(asymmetric=True), kind="drawing", symmetry="auto", progress=False)
    assert run.symmetry.axis is None and run.symmetry.best.score < SYMMETRY_THRESHOLD
    assert "symmetry" not in run.final.params
    assert "free" in run.symmetry.description


def test_a_forced_axis_is_kept_whatever_its_score():
    lines = img2logo.extract_feature_lines(img2logo.load_image(gull(asymmetric=True)), kind="drawing").lines
    choice = choose_axis(lines, "horizontal")
    assert choice.axis is not None and choice.axis.angle == pytest.approx(0.0)
    assert np.array_equal(choice.axis.direction, [1.0, 0.0])
    assert choose_axis(lines, "45").axis.angle == pytest.approx(45.0)


def test_the_reflection_is_an_involution_about_the_axis():
    axis = Axis(np.array([10.0, 5.0]), np.array([1.0, 2.0]), 1.0)
    pts = np.array([[0.0, 0.0], [3.0, -7.0], [10.0, 5.0]])
    assert np.allclose(axis.reflect(axis.reflect(pts)), pts)
    assert np.allclose(axis.reflect(pts[2:]), pts[2:])  # a point of the axis stays


@pytest.mark.parametrize("value", ["diagonal", "", True, float("nan"), [90]])
def test_bad_symmetry_values_are_refused(value):
    with pytest.raises(InvalidParameterError, match="symmetry"):
        check_symmetry_option(value)


def test_symmetry_option_values():
    assert check_symmetry_option("none") is None and check_symmetry_option(None) is None
    assert check_symmetry_option("Auto") == "auto"
    assert check_symmetry_option(45) == "45" and check_symmetry_option("12.5") == "12.5"


# --------------------------------------------------------------------------- the half graph
def test_a_segment_across_the_axis_is_split_there_and_runs_into_its_mirror_image():
    # One arc of a circle centred on the axis x = 50, crossing it square, and a line on one side.
    t = np.linspace(math.radians(200), math.radians(340), 60)
    arc = np.column_stack([50 + 30 * np.cos(t), 60 + 30 * np.sin(t)])
    line = np.array([arc[-1], [80.0, 10.0]])
    graph = SegmentGraph((arc, line), np.array([arc[0], arc[-1], [80.0, 10.0]]), np.array([[0, 1], [1, 2]]), 100, 80)
    axis = Axis(np.array([50.0, 0.0]), np.array([0.0, 1.0]), 1.0)
    half = half_graph(graph, axis)
    g, c = half.graph, half.constraints
    on_axis = list(c.nodes)
    assert len(on_axis) == 1 and g.junctions[on_axis[0], 0] == 50.0  # exactly on the axis
    assert half.rotation == 0.0
    # The kept half has the line (more length) and half the arc, which ends square to the axis.
    expected = float(np.hypot(*(line[1] - line[0]))) + 30 * math.radians(70)
    assert g.n_segments == 2 and sum(g.lengths) == pytest.approx(expected, rel=0.01)
    assert len(c.smooth) == 1 and next(iter(c.smooth))[1] == on_axis[0]


def test_the_constrained_fit_holds_centres_and_junctions_on_the_axis():
    # A circle through a junction, its centre held on x = 20: only its y moves.
    t = np.linspace(0.2, 1.2, 30)
    pts = np.column_stack([23 + 10 * np.cos(t), 7 + 10 * np.sin(t)])
    fit = fit_constrained(
        [pts],
        [10.0],
        [[23.0, 7.0]],
        [[20.4, 17.0]],
        np.array([[0, 0]]),
        axis=20.0,
        axis_circles=[0],
        axis_junctions=[0],
    )
    assert fit.converged
    assert fit.centers[0, 0] == 20.0
    assert 20.4 + fit.displacements[0, 0] == pytest.approx(20.0, abs=1e-12)
    assert abs(np.hypot(*(fit.centers[0] - ([20.4, 17.0] + fit.displacements[0]))) - 10.0) < 1e-6
    with pytest.raises(InvalidParameterError, match="axis"):
        fit_constrained([pts], [10.0], [[23.0, 7.0]], [[20.0, 17.0]], np.array([[0, 0]]), axis_circles=[0])


# --------------------------------------------------------------------------- symmetric levels
def test_the_synthetic_drawing_gives_exact_pairs(symmetric_run):
    final = symmetric_run.final
    point, direction = record(final)
    pairs, on_axis, alone = circle_pairs(final.circles, point, direction)
    assert not alone and pairs and on_axis
    circles = final.circles
    axis = Axis(np.array(point), np.array(direction), 1.0)
    for i, j in pairs:
        a, b = circles[i], circles[j]
        assert a.k == b.k and a.r == b.r
        assert np.hypot(*(axis.reflect(a.center) - b.center)) < 1e-6
    # The circle drawn on the axis is its own mirror image, centred on the axis, near (120, 80).
    ring = [circles[i] for i in on_axis if abs(circles[i].cy - 80.0) < 3.0]
    assert ring and abs(ring[0].cx - 120.0) < 1.0


def test_every_level_of_a_symmetric_run_is_symmetric(symmetric_run):
    point, direction = record(symmetric_run.final)
    assert len(symmetric_run.levels) >= 1
    for level in symmetric_run.levels:
        assert is_symmetric(level, point, direction)


def test_every_level_of_a_real_symmetric_run_is_symmetric():
    from helpers import DATA

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no junction released
        run = img2logo.abstract(DATA / "clipart-fox.png", symmetry="auto", progress=False)
    point, direction = record(run.final)
    assert run.symmetry.axis.angle == 90.0
    assert len(run.levels) > 5
    assert all(is_symmetric(level, point, direction) for level in run.levels)
    assert run.final.similarity <= run.final.tolerance


def test_a_free_level_is_not_symmetric():
    run = img2logo.abstract(gull(asymmetric=True), kind="drawing", progress=False)
    assert not is_symmetric(run.final, [120.0, 0.0], [0.0, 1.0])


def test_the_result_document_pairs_every_circle(symmetric_run):
    doc = to_document(symmetric_run.final)
    sym = doc["extra"]["symmetry"]
    assert set(sym) == {"point", "direction", "circle_pairs", "on_axis"}
    listed = [i for pair in sym["circle_pairs"] for i in pair] + sym["on_axis"]
    assert sorted(listed) == list(range(len(doc["circles"])))
    json.dumps(doc)  # JSON-safe


def test_the_svg_mirrors_to_its_printed_precision_and_shows_the_axis(symmetric_run):
    svg = to_svg(symmetric_run.final)
    assert re.search(r'<line id="mirror-axis" x1="120(\.\d+)?" y1="0" x2="120(\.\d+)?" y2="240"', svg)
    circles = [
        tuple(float(v) for v in m)
        for m in re.findall(r'<circle id="circle-\d+"[^>]* cx="([-\d.]+)" cy="([-\d.]+)" r="([-\d.]+)"', svg)
    ]
    point, _ = record(symmetric_run.final)
    axis_x = point[0]
    decimals = max(len(v.split(".")[1]) if "." in v else 0 for v in re.findall(r'cx="([-\d.]+)"', svg))
    unit = 10.0**-decimals
    for cx, cy, r in circles:
        mirrored = 2 * axis_x - cx
        assert any(abs(mirrored - x) <= unit and abs(cy - y) <= unit / 2 and r == q for x, y, q in circles)


def test_a_free_run_has_no_symmetry_record():
    run = img2logo.abstract(gull(), kind="drawing", progress=False)
    assert run.symmetry is None
    assert "symmetry" not in to_document(run.final)["extra"]
    assert "mirror-axis" not in to_svg(run.final)


def test_a_lock_mask_is_refused_with_symmetry():
    with pytest.raises(InvalidParameterError, match="lock mask"):
        img2logo.abstract(gull(), symmetry="vertical", lock_mask=np.zeros((240, 240), bool))


# --------------------------------------------------------------------------- command line
def test_cli_symmetry_auto_says_so_and_writes_the_axis(tmp_path, capsys):
    src = tmp_path / "gull.png"
    cv2.imwrite(str(src), gull())
    out = tmp_path / "gull.json"
    assert main([str(src), "--symmetry", "auto", "--json", str(out)]) == 0
    err = capsys.readouterr().err
    assert len([line for line in err.splitlines() if line.startswith("symmetry: ")]) == 1
    doc = json.loads(out.read_text())
    direction = doc["extra"]["symmetry"]["direction"]
    assert direction == [0.0, 1.0] and math.copysign(1.0, direction[0]) == 1.0  # no negative zero


def test_cli_bad_symmetry_is_one_line_and_exit_two(tmp_path, capsys):
    src = tmp_path / "gull.png"
    cv2.imwrite(str(src), gull())
    assert main([str(src), "--symmetry", "sideways", "--json", str(tmp_path / "gull.json")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "symmetry must be" in err and "Traceback" not in err


def test_a_batch_passes_symmetry_on(tmp_path):
    from concurrent.futures import ThreadPoolExecutor

    from img2logo.app.batch.run import run_batch

    src = tmp_path / "gull.png"
    cv2.imwrite(str(src), gull())
    with ThreadPoolExecutor(1) as pool:
        report = run_batch([src], tmp_path / "out", executor=pool, progress=False, symmetry="auto", kind="drawing")
    assert not report.failures
    doc = json.loads((tmp_path / "out" / "gull.json").read_text())
    assert doc["params"]["symmetry"]["mode"] == "auto" and doc["extra"]["symmetry"]["on_axis"]
    # The summary says what was decided, in the table and in the CSV.
    assert report.rows[0].symmetry.startswith("90.0 deg, score ")
    assert "symmetry" in report.summary().splitlines()[0]
    assert report.to_frame()["symmetry"].tolist() == [report.rows[0].symmetry]
    with ThreadPoolExecutor(1) as pool:
        free = run_batch([src], tmp_path / "free", executor=pool, progress=False, kind="drawing")
    assert free.rows[0].symmetry == "" and "symmetry" not in free.summary().splitlines()[0]


def test_the_arc_budget_counts_the_whole_symmetric_logo():
    # The symmetric polar bear is 36 arcs within T: under the budget of 40, though its half has more
    # than 20 groups (the arcs centred on the axis are one arc with their mirror image).
    from helpers import DATA

    bear = DATA.parent / "benchmarks" / "data" / "clipart-polar-bear.png"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = img2logo.abstract(bear, symmetry="vertical", progress=False)
    assert run.symmetry is not None and run.symmetry.axis is not None
    assert run.progression.stopped_because == "tolerance" and len(run.final.arcs) <= 40
    assert run.final.similarity <= run.final.tolerance
