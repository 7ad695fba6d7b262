"""The kit's figure layout (img2logo.experiments.layout): panel grids, image panels, windows and their marks."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np
import pytest
from helpers import small_graph
from matplotlib.collections import LineCollection

from img2logo.experiments import layout

W, H = 120, 90


pytestmark = pytest.mark.usefixtures("close_figures")


def test_panel_grid_sizes_the_figure_by_its_panels():
    fig, axes = layout.panel_grid(2, 3, 2.5, extra_height=0.4)
    assert axes.shape == (2, 3)
    assert tuple(fig.get_size_inches()) == pytest.approx((7.5, 5.4))
    fig, axes = layout.panel_grid(0, 2, 3.0, height_ratio=0.5, width=10.0, width_ratios=[1.0, 3.0])
    assert axes.shape == (1, 2)  # at least one row
    assert tuple(fig.get_size_inches()) == pytest.approx((10.0, 1.5))
    fig.canvas.draw()
    narrow, wide = (ax.get_position().width for ax in axes[0])
    assert wide > 2.5 * narrow


def test_show_image_covers_the_pixel_frame_and_thickens_lines():
    lines = np.zeros((H, W), dtype=bool)
    lines[40, 10:100] = True
    _, ax = plt.subplots()
    layout.show_image(ax, lines, thicken=True)
    (shown,) = ax.get_images()
    assert shown.get_extent() == [0, W, H, 0]
    assert not ax.axison
    assert int((~shown.get_array()).sum()) == int(lines.sum()) * 3 + 2  # 1 px -> 3 px wide, ends 1 px longer


def test_draw_segment_groups_colours_each_group():
    g = small_graph()
    _, ax = plt.subplots()
    groups = [[0], list(range(1, g.n_segments))]
    layout.draw_segment_groups(ax, g, groups, ["#ff0000", "#0000ff"])
    (lc,) = [c for c in ax.collections if isinstance(c, LineCollection)]
    colors = [mcolors.to_hex(c) for c in lc.get_colors()]
    assert colors == ["#ff0000"] + ["#0000ff"] * (g.n_segments - 1)
    assert ax.get_xlim() == (0.0, g.width) and ax.get_ylim() == (g.height, 0.0)
    with pytest.raises(ValueError):
        layout.draw_segment_groups(ax, g, groups, ["#ff0000"])


def test_frame_bounds_and_mark_window():
    _, ax = plt.subplots()
    layout.frame_bounds(ax, np.array([[20.0, 30.0], [70.0, 40.0]]), W, H)
    assert ax.get_xlim() == pytest.approx((14.0, 76.0))  # 0.08 * 50 + 2 px either side
    assert ax.get_ylim() == pytest.approx((46.0, 24.0))  # y down
    layout.mark_window(ax, (10.0, 20.0, 50.0, 60.0), "zoom")
    (box,) = ax.patches
    assert (box.get_x(), box.get_y(), box.get_width(), box.get_height()) == (10.0, 20.0, 40.0, 40.0)
    assert [t.get_text() for t in ax.texts] == ["zoom"]


def test_emptiest_corner_avoids_the_drawing():
    # points in the bottom right of a 100 x 100 px image (y down): the inset goes top right (axes fraction, y up)
    assert layout.emptiest_corner(np.array([[90.0, 90.0], [95.0, 80.0]]), 100, 100, 0.3) == (0.7, 0.7)
    assert layout.emptiest_corner(np.zeros((0, 2)), 100, 100, 0.3) == (0.7, 0.0)
