"""Tests of img2logo.export.plotting: figures in the image pixel frame, y down."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np
import pytest
from helpers import small_graph
from matplotlib.collections import LineCollection
from matplotlib.image import AxesImage
from matplotlib.patches import Circle as CirclePatch

from img2logo.constants import PHI
from img2logo.errors import InvalidImageError, InvalidParameterError
from img2logo.export import plotting
from img2logo.export.constants import MIN_STROKE_WIDTH
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.primitives import Arc, Circle
from img2logo.segment_graph import SegmentGraph

W, H = 120, 90


pytestmark = pytest.mark.usefixtures("close_figures")


def make_abstraction() -> Abstraction:
    a = Circle(50.0, 45.0, PHI ** (7 + 0.3), 7)
    b = Circle(90.0, 30.0, PHI ** (5 + 0.3), 5)
    arcs = (Arc(a, -2.0, 1.5), Arc(b, 0.0, -2.0 * math.pi), Arc(a, 1.0, -0.5))
    return Abstraction(
        level=1,
        arcs=arcs,
        arc_segments=((0,), (1,), (2,)),
        junctions=np.array([arcs[0].end, arcs[2].start]),
        junction_arcs=((0,), (2,)),
        similarity=0.1,
        bias=0.3,
        tolerance=1.0,
        width=W,
        height=H,
    )


def assert_image_frame(ax, width, height):
    assert ax.get_xlim() == (0.0, width)
    assert ax.get_ylim() == (height, 0.0)  # y down
    assert ax.yaxis_inverted()
    assert ax.get_aspect() == 1.0
    assert not ax.axison


def test_default_stroke_width():
    assert plotting.default_stroke_width(512, 256) == pytest.approx(4.0)
    assert plotting.default_stroke_width(20, 14) == MIN_STROKE_WIDTH


def test_plot_abstraction_frame_and_arcs():
    a = make_abstraction()
    ax = plotting.plot_abstraction(a)
    assert_image_frame(ax, W, H)
    (collection,) = [c for c in ax.collections if isinstance(c, LineCollection)]
    lines = collection.get_segments()
    assert len(lines) == len(a.arcs)
    for arc, line in zip(a.arcs, lines, strict=True):
        np.testing.assert_allclose(np.abs(arc.circle.distance(line)), 0.0, atol=1e-9)
        np.testing.assert_allclose(line[0], arc.start, atol=1e-9)
        np.testing.assert_allclose(line[-1], arc.end, atol=1e-9)
        assert np.max(np.hypot(*np.diff(line, axis=0).T)) <= 0.5 + 1e-9
    assert collection.get_capstyle() == "round"
    assert not ax.patches and not ax.lines and not ax.images


def test_plot_abstraction_options():
    a = make_abstraction()
    _, ax = plt.subplots()
    image = np.zeros((H, W, 4), dtype=np.uint8)
    image[..., 3] = 255
    out = plotting.plot_abstraction(
        a, ax, image=image, show_circles=True, show_junctions=True, color="#123456", linewidth=3.0
    )
    assert out is ax
    assert_image_frame(ax, W, H)
    circles = [p for p in ax.patches if isinstance(p, CirclePatch)]
    assert sorted((p.center, p.radius) for p in circles) == sorted(((c.cx, c.cy), c.r) for c in a.circles)
    (junctions,) = ax.lines
    np.testing.assert_array_equal(np.column_stack(junctions.get_data()), a.junctions)
    (im,) = ax.images
    assert isinstance(im, AxesImage)
    assert im.get_extent() == [0.0, W, H, 0.0]
    (collection,) = ax.collections
    assert mcolors.to_hex(collection.get_colors()[0]) == "#123456"
    assert collection.get_linewidths()[0] == 3.0


def test_plot_abstraction_rejects_bad_input():
    a = make_abstraction()
    with pytest.raises(InvalidParameterError, match="abstraction must be an Abstraction"):
        plotting.plot_abstraction("nope")
    with pytest.raises(InvalidParameterError, match="linewidth must be > 0"):
        plotting.plot_abstraction(a, linewidth=0)
    with pytest.raises(InvalidImageError, match=r"image must be 90 x 120 px"):
        plotting.plot_abstraction(a, image=np.zeros((W, H)))
    with pytest.raises(InvalidImageError, match=r"image must have shape \(H, W\) or \(H, W, C\) with C in 1..4"):
        plotting.plot_abstraction(a, image=np.zeros((H, W, 5)))
    with pytest.raises(InvalidParameterError, match=r"image_fade must be in \[0, 1\]"):
        plotting.plot_abstraction(a, image=np.zeros((H, W)), image_fade=2.0)


def test_background_conversion():
    a = make_abstraction()

    def drawn(image, fade=0.6):  # the faded image plot_abstraction draws, (H, W, 3) in [0, 1]
        ax = plotting.plot_abstraction(a, image=image, image_fade=fade)
        array = np.asarray(ax.images[0].get_array())
        plt.close(ax.figure)
        return array

    rgb = drawn(np.zeros((H, W), dtype=np.uint8), fade=0.6)
    assert rgb.shape == (H, W, 3)
    np.testing.assert_allclose(rgb, 0.6)
    np.testing.assert_allclose(drawn(np.ones((H, W), dtype=bool), fade=0.0), 1.0)
    rgba = np.zeros((H, W, 4))
    rgba[..., 3] = 0.0  # fully transparent -> white
    np.testing.assert_allclose(drawn(rgba, fade=0.0), 1.0)
    grey16 = np.full((H, W), 65535, dtype=np.uint16)
    np.testing.assert_allclose(drawn(grey16, fade=0.0), 1.0)
    # Grey + alpha, read as an input image is (img2logo.images.loading.composite_on_white).
    grey_alpha = np.zeros((H, W, 2))
    grey_alpha[0, :, 1] = 1.0  # top row opaque black, the others transparent -> white
    np.testing.assert_allclose(drawn(grey_alpha, fade=0.0)[:2, 0], [[0, 0, 0], [1, 1, 1]])
    with pytest.raises(InvalidImageError, match="image contains NaN or infinite values"):
        drawn(np.full((H, W), np.nan))
    with pytest.raises(InvalidImageError, match=r"float images must have values in \[0, 1\], got \[2, 2\]"):
        drawn(np.full((H, W), 2.0))


def test_plot_segment_graph():
    g = small_graph()
    ax = plotting.plot_segment_graph(g, image=np.ones((14, 20)))
    assert_image_frame(ax, 20, 14)
    (collection,) = ax.collections
    assert len(collection.get_segments()) == g.n_segments
    tab10 = matplotlib.colormaps["tab10"]
    np.testing.assert_allclose(collection.get_colors(), [tab10(i % 10) for i in range(g.n_segments)])
    labels = {line.get_label(): np.column_stack(line.get_data()) for line in ax.lines}
    assert set(labels) == {"end point (valence 1)", "split point (valence 2)", "junction (valence \u2265 3)"}
    np.testing.assert_array_equal(labels["junction (valence \u2265 3)"], [[10.5, 2.5]])
    np.testing.assert_array_equal(labels["split point (valence 2)"], [[10.5, 10.5]])
    np.testing.assert_array_equal(labels["end point (valence 1)"], [[2.5, 2.5], [2.5, 10.5], [17.5, 9.5]])
    # Deterministic colours: a second plot gives the same.
    again = plotting.plot_segment_graph(g, show_junctions=False)
    np.testing.assert_array_equal(again.collections[0].get_colors(), collection.get_colors())
    assert not again.lines


def test_plot_segment_graph_cycles_colours():
    n = 12
    pts = np.array([[i + 0.5, 0.5] for i in range(n + 1)])
    segments = tuple(pts[i : i + 2] for i in range(n))
    g = SegmentGraph(segments, pts, np.array([[i, i + 1] for i in range(n)]), width=n + 1, height=2)
    colors = plotting.plot_segment_graph(g).collections[0].get_colors()
    np.testing.assert_array_equal(colors[10], colors[0])
    assert not np.array_equal(colors[1], colors[0])
    with pytest.raises(InvalidParameterError, match="cmap must be the name of a matplotlib colormap"):
        plotting.plot_segment_graph(g, cmap="no-such-map")
    with pytest.raises(InvalidParameterError, match="graph must be a SegmentGraph"):
        plotting.plot_segment_graph(make_abstraction())


def test_plot_circles():
    circles = [Circle(10.0, 20.0, 5.0, 1), Circle(30.0, 25.0, 8.0, 2)]
    ax = plotting.plot_circles(circles, show_centers=True)
    assert len(ax.patches) == 2
    assert ax.yaxis_inverted() and not ax.axison
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    assert x0 < 5.0 and x1 > 38.0 and y0 > 33.0 and y1 < 15.0
    (centres,) = ax.lines
    np.testing.assert_array_equal(np.column_stack(centres.get_data()), [[10.0, 20.0], [30.0, 25.0]])
    framed = plotting.plot_circles(circles, width=64, height=48)
    assert_image_frame(framed, 64, 48)
    # On axes already in the image frame (y down), circles do not flip it back.
    ax2 = plotting.plot_abstraction(make_abstraction())
    plotting.plot_circles(circles, ax2)
    assert ax2.get_ylim() == (H, 0.0)
    with pytest.raises(InvalidParameterError, match="width and height must be given together"):
        plotting.plot_circles(circles, width=10)
    with pytest.raises(InvalidParameterError, match=r"circles\[0\] must be a Circle"):
        plotting.plot_circles([(1, 2, 3)])
