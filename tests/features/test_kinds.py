"""Tests of img2logo.features.kinds: outlined shapes (closed outlines round the paper) are a clip art's."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from helpers import DATA

from img2logo import detect_kind


def _bubble(tail: bool = False, dot: bool = False, width: int = 18) -> np.ndarray:
    """A thought bubble: an ellipse and two small circles drawn by outlines ``width`` px wide, filled white."""
    im = np.full((400, 400, 3), 255, np.uint8)
    cv2.ellipse(im, (190, 160), (140, 100), 0, 0, 360, (0, 0, 0), width, cv2.LINE_AA)
    cv2.circle(im, (300, 300), 24, (0, 0, 0), 2 * width // 3, cv2.LINE_AA)
    cv2.circle(im, (345, 355), 14, (0, 0, 0), width // 2, cv2.LINE_AA)
    if tail:  # a stroke running off the outline: a balloon's string
        cv2.line(im, (190, 260), (150, 390), (0, 0, 0), width // 2, cv2.LINE_AA)
    if dot:  # ink inside an outline: a face's eye
        cv2.circle(im, (150, 140), 10, (0, 0, 0), -1, cv2.LINE_AA)
    return im


def test_a_fill_with_an_outline_like_a_thought_bubble_is_a_clip_art():
    """Known answer: shapes filled white and drawn by their 18 px outlines alone are outlined shapes."""
    from img2logo.features.kinds import outline_band_width

    kind, reason = detect_kind(_bubble())
    assert kind == "clipart", reason
    assert "closed outlines" in reason
    assert abs(outline_band_width(_bubble()[:, :, 0] < 128) - 16.0) <= 3.0  # the three bands' mean width


@pytest.mark.parametrize(("tail", "dot"), [(True, False), (False, True)])
def test_outlines_with_a_stroke_running_off_or_ink_inside_are_a_drawing(tail, dot):
    """A stroke that leaves an outline (a string) or ink inside one (an eye) is a line drawing's."""
    from img2logo.features.kinds import outline_band_width

    kind, reason = detect_kind(_bubble(tail=tail, dot=dot))
    assert kind == "drawing", reason
    assert outline_band_width(_bubble(tail=tail, dot=dot)[:, :, 0] < 128) is None


def test_thin_closed_outlines_are_still_a_drawing():
    """Outlines no wider than one drawn once (CLIPART_OUTLINE_WIDTH): their centre line stands for both edges."""
    kind, reason = detect_kind(_bubble(width=9))
    assert kind == "drawing", reason


def test_the_openclipart_thought_bubble_is_a_clip_art_and_keeps_its_silhouette():
    """Openclipart's thought bubble (a white fill with a black outline), read as a drawing before: its
    logo followed the stroke's centre line, 9 px inside the silhouette (sil6 0.09)."""
    import warnings

    from img2logo import abstract
    from img2logo.quality import logo_points, silhouette_recall

    folder = DATA.parent / "benchmarks" / "data" / "openclipart"
    kind, reason = detect_kind(folder / "clipart-thought.png")
    assert kind == "clipart", reason
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = abstract(folder / "clipart-thought.png", progress=False)
    mask = cv2.imread(str(folder / "clipart-thought.silhouette.png"), cv2.IMREAD_GRAYSCALE) > 127
    assert silhouette_recall(logo_points(result.final), mask) >= 0.95
