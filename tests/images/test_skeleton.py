"""The skeleton's tracing gives scipy's shortest paths (the oracle, imported by the tests only)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from img2logo.images import skeleton as _skeleton
from img2logo.images.ndimage import components, skeletonize

DATA = Path(__file__).resolve().parents[2] / "data"


def _scipy_dijkstra(graph, sources):
    from scipy import sparse
    from scipy.sparse import csgraph

    n = graph.n
    csr = sparse.csr_matrix((graph.weights, graph.indices, graph.indptr), shape=(n, n))
    dist, pred, _ = csgraph.dijkstra(csr, indices=sources, min_only=True, return_predecessors=True)
    return dist, pred.astype(np.int64)


@pytest.mark.parametrize("name", ["clipart-fish", "clipart-cat", "drawing-rabbit", "drawing-snail", "photo-flower"])
def test_trace_is_the_same_as_with_scipys_dijkstra(monkeypatch, name):
    from img2logo.features.preprocessing import extract_feature_lines, load_image

    lines = extract_feature_lines(load_image(DATA / f"{name}.png")).lines
    skel = skeletonize(np.array(lines))
    ours = _skeleton.trace(skel)
    monkeypatch.setattr(_skeleton, "_dijkstra", _scipy_dijkstra)
    theirs = _skeleton.trace(skel)
    assert ours.ends == theirs.ends
    assert len(ours.chains) == len(theirs.chains) > 0
    for a, b in zip(ours.chains, theirs.chains, strict=True):
        np.testing.assert_array_equal(a, b)
    for a, b in zip(ours.nodes, theirs.nodes, strict=True):
        np.testing.assert_array_equal(a, b)


def test_a_closed_loop_and_a_blob_are_traced_as_with_scipy(monkeypatch):
    import cv2

    img = np.zeros((40, 60), dtype=np.uint8)
    cv2.circle(img, (15, 20), 10, 1, 1)  # a closed loop: cut open at a node of its own
    img[5:12, 35:42] = 1  # a blob at the end of a line
    img[12:30, 38] = 1
    skel = img.astype(bool)
    ours = _skeleton.trace(skel)
    monkeypatch.setattr(_skeleton, "_dijkstra", _scipy_dijkstra)
    theirs = _skeleton.trace(skel)
    assert ours.ends == theirs.ends
    assert any(a == b for a, b in ours.ends)  # the loop
    for a, b in zip(ours.chains, theirs.chains, strict=True):
        np.testing.assert_array_equal(a, b)


def test_sparse_labels_are_labels():
    # trace labels its node and chain pixels alone (compiled): label's numbers for the mask.
    rng = np.random.default_rng(9)
    for _ in range(60):
        h, w = (int(v) for v in rng.integers(1, 50, 2))
        mask = rng.random((h, w)) < rng.uniform(0.02, 0.6)
        rows, cols = np.nonzero(mask)
        got = _skeleton._sparse_label(mask, rows, cols)
        assert np.array_equal(got, components(mask, connectivity=2))
