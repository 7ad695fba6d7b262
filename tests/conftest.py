"""Shared fixtures (the helpers the tests share are in ``helpers.py``)."""

from __future__ import annotations

from pathlib import Path

import pytest
from helpers import DATA, two_discs


@pytest.fixture
def data_dir() -> Path:
    return DATA


@pytest.fixture(scope="module")
def discs_result():
    """The two-disc clip art (:func:`two_discs`) made into a logo, once per module."""
    import img2logo

    return img2logo.abstract(two_discs())


@pytest.fixture
def close_figures():
    """Closes every matplotlib figure the test left open (pyplot keeps them, and they add up)."""
    yield
    import matplotlib.pyplot as plt

    plt.close("all")
