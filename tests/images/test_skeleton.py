"""The skeleton's stand-ins for scipy and scikit-image give their numbers (the oracles, imported by the tests only)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from img2logo.images import skeleton as _skeleton

DATA = Path(__file__).resolve().parents[2] / "data"


def test_line_is_skimages_pixel_for_pixel():
    from skimage.draw import line as oracle

    ends = [*np.random.default_rng(0).integers(-12, 40, (3000, 4)).tolist(), [3, 3, 3, 3], [0, 0, 5, 5]]
    for r0, c0, r1, c1 in ends:
        got, want = _skeleton.line(r0, c0, r1, c1), oracle(r0, c0, r1, c1)
        for g, w in zip(got, want, strict=True):
            assert g.dtype == w.dtype
            np.testing.assert_array_equal(g, w)


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
    skel = _skeleton.skeletonize(np.array(lines))
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


def test_label_kernel_is_opencvs_labelling_renumbered(monkeypatch):
    # The compiled union-find labelling and OpenCV's (the path without the kernels): the same labels.
    from img2logo._compiled import kernels

    rng = np.random.default_rng(6)
    images = []
    for _ in range(40):
        h, w = (int(v) for v in rng.integers(1, 40, 2))
        images.append(rng.random((h, w)) < rng.uniform(0.1, 0.9))
        images.append(rng.integers(-1, 4, (h, w)))
    cases = [(im, c, b) for im in images for c in (1, 2) for b in ((0,) if im.dtype == bool else (-1, 0))]
    compiled = [_skeleton.label(im, connectivity=c, background=b) for im, c, b in cases]
    monkeypatch.setattr(kernels, "CACHED", False)
    for (im, c, b), got in zip(cases, compiled, strict=True):
        want = _skeleton.label(im, connectivity=c, background=b)
        assert got.dtype == want.dtype and np.array_equal(got, want)


def test_unique_is_numpys():
    from img2logo.images.skeleton import unique

    rng = np.random.default_rng(5)
    for n in (0, 1, 2, 7, 100):
        for dtype in (np.int32, np.int64):
            values = rng.integers(-5, 6, n).astype(dtype)
            got, want = unique(values), np.unique(values)
            assert got.dtype == want.dtype and np.array_equal(got, want)
    assert np.array_equal(unique(np.array([[3, 1], [1, 3]])), [1, 3])


def test_compiled_boxes_distances_and_set_pixels_match_the_references(monkeypatch):
    # bounding_slices, distance_to_background (Meijster's exact transform against OpenCV's
    # precise one) and nonzero: the compiled paths give what the references give.
    from img2logo._compiled import kernels

    rng = np.random.default_rng(8)
    labels, masks = [], []
    for _ in range(60):
        h, w = (int(v) for v in rng.integers(1, 50, 2))
        labels.append(rng.integers(0, 6, (h, w)) * (rng.random((h, w)) < 0.3))
        mask = rng.random((h, w)) < rng.uniform(0.2, 1.0)
        mask.flat[int(rng.integers(mask.size))] = False  # a background pixel
        masks.append(mask)
    far = np.ones((300, 200), dtype=bool)
    far[0, 0] = False  # one corner: distances across the whole image
    masks.append(far)
    boxes = [_skeleton.bounding_slices(lab) for lab in labels]
    dists = [_skeleton.distance_to_background(m) for m in masks]
    monkeypatch.setattr(kernels, "CACHED", False)
    assert boxes == [_skeleton.bounding_slices(lab) for lab in labels]
    for m, d in zip(masks, dists, strict=True):
        assert d.dtype == np.float64 and np.array_equal(d, _skeleton.distance_to_background(m))
        got, want = _skeleton.nonzero(m), np.nonzero(m)
        assert all(g.dtype == np.int64 and np.array_equal(g, v) for g, v in zip(got, want, strict=True))


def test_sparse_labels_are_labels():
    # trace labels its node and chain pixels alone (compiled): label's numbers for the mask.
    rng = np.random.default_rng(9)
    for _ in range(60):
        h, w = (int(v) for v in rng.integers(1, 50, 2))
        mask = rng.random((h, w)) < rng.uniform(0.02, 0.6)
        rows, cols = _skeleton.nonzero(mask)
        got = _skeleton._sparse_label(mask, rows, cols)
        assert np.array_equal(got, _skeleton.label(mask, connectivity=2))
