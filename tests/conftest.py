"""Shared fixtures: synthetic images whose segment graphs are known, and the data folder."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest

DATA = Path(__file__).resolve().parents[1] / "data"


def blank(size: int = 200) -> np.ndarray:
    """A white RGB uint8 canvas of size x size px."""
    return np.full((size, size, 3), 255, np.uint8)


def drawing(shape: str, thickness: int = 3, size: int = 200) -> np.ndarray:
    """A black-on-white line drawing of a known shape, RGB uint8."""
    im = blank(size)
    black = (0, 0, 0)
    if shape == "circle":
        cv2.circle(im, (100, 100), 60, black, thickness)
    elif shape == "Y":
        for end in ((100, 180), (40, 40), (160, 40)):
            cv2.line(im, (100, 100), end, black, thickness)
    elif shape == "X":
        cv2.line(im, (30, 30), (170, 170), black, thickness)
        cv2.line(im, (30, 170), (170, 30), black, thickness)
    elif shape == "two":
        cv2.line(im, (30, 30), (90, 170), black, thickness)
        cv2.line(im, (120, 30), (170, 170), black, thickness)
    elif shape == "square":
        cv2.rectangle(im, (40, 40), (160, 160), black, thickness)
    elif shape == "spiral":
        t = np.linspace(0.0, 4.0 * np.pi, 400)
        r = (10.0 + 12.0 * t) / 1.5
        pts = np.column_stack([100 + r * np.cos(t), 100 + r * np.sin(t)]).round().astype(np.int32)
        cv2.polylines(im, [pts], False, black, thickness)
    else:
        raise ValueError(shape)
    return im


def two_discs(size: int = 200) -> np.ndarray:
    """Clip art: a red and a blue disc overlapping on white, RGB uint8."""
    im = blank(size)
    cv2.circle(im, (80, 100), 45, (220, 40, 40), -1, lineType=cv2.LINE_AA)
    cv2.circle(im, (130, 100), 45, (40, 90, 220), -1, lineType=cv2.LINE_AA)
    return im


def small_graph():
    """A hand-built segment graph: 5 nodes of valence 1, 3, 2, 1, 1; 4 segments; 20 x 14 px."""
    from img2logo.segment_graph import SegmentGraph

    nodes = np.array([[2.5, 2.5], [10.5, 2.5], [10.5, 10.5], [2.5, 10.5], [17.5, 9.5]])
    segments = (
        np.array([[x + 0.5, 2.5] for x in range(2, 11)]),
        np.array([[10.5, y + 0.5] for y in range(2, 11)]),
        np.array([[10.5 + t, 2.5 + t] for t in range(8)]),
        np.array([[x + 0.5, 10.5] for x in range(10, 1, -1)]),
    )
    ends = np.array([[0, 1], [1, 2], [1, 4], [2, 3]])
    return SegmentGraph(segments=segments, junctions=nodes, ends=ends, width=20, height=14)


@pytest.fixture
def data_dir() -> Path:
    return DATA
