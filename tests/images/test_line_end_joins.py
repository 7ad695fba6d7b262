"""Tests of img2logo.images.line_ends (its joins and spurs: tests/features/photo/test_lines.py)."""

from __future__ import annotations

import numpy as np
from helpers import random_masks
from scipy.spatial import cKDTree

from img2logo.images.line_ends import join_line_ends, pixels_within
from img2logo.images.ndimage import skeletonize
from img2logo.images.skeleton import classify


def test_pixels_within_are_a_k_d_trees_ball_query() -> None:
    """The line pixels an end looks at are those scipy's k-d tree finds, in raster order."""
    compared = 0
    for mask in random_masks(150, 4):
        skel = skeletonize(mask)
        pixels = np.argwhere(skel)
        if len(pixels) == 0:
            continue
        tree = cKDTree(pixels)
        ends = np.argwhere(skel & (classify(skel)[1] == 1))
        probes = np.concatenate((ends, [[0, 0], [skel.shape[0] - 1, skel.shape[1] - 1]]))
        for distance in (6.0, 3.5, 1.0, 0.5):
            for r, c in probes:
                got = pixels_within(skel, (int(r), int(c)), distance)
                expected = sorted(tuple(int(v) for v in pixels[k]) for k in tree.query_ball_point((r, c), distance))
                assert got == expected
                compared += 1
    assert compared > 1000


def test_a_line_end_with_equally_near_pixels_joins_the_one_it_points_at() -> None:
    skel = np.zeros((30, 40), bool)
    skel[10, 0:11] = True  # a line along +x, ending at (10, 10)
    skel[5:25, 15] = True  # a line across x = 15: (10, 15) is 5 px straight ahead ...
    skel[13, 14] = skel[14, 13] = False  # (nothing else within 5 px but the column)
    joined = join_line_ends(skel, 6.0)
    assert joined[10, 11:15].all()  # ... joined straight on
    # Two pixels 5 px away: the one the line turns less towards is joined.
    skel = np.zeros((30, 40), bool)
    skel[10, 0:11] = True
    skel[14, 13] = skel[13, 14] = True  # both 5 px from (10, 10); (13, 14) turns less from +x
    joined = join_line_ends(skel, 6.0)
    assert joined[11, 11] and joined[12, 12] and joined[12, 13]  # the run to (13, 14) ...
    assert not joined[13, 12]  # ... not the one to (14, 13)
