"""img2logo.images.ndimage against scipy.ndimage (its filters: tests/features/photo/test_subject.py)."""

import numpy as np


def test_boxes_distances_and_a_far_corner_are_scipys():
    from scipy import ndimage

    from img2logo.images.ndimage import bounding_slices, distance

    rng = np.random.default_rng(8)
    for _ in range(60):
        h, w = (int(v) for v in rng.integers(1, 50, 2))
        labels = rng.integers(0, 6, (h, w)) * (rng.random((h, w)) < 0.3)
        assert bounding_slices(labels) == ndimage.find_objects(labels)
        mask = rng.random((h, w)) < rng.uniform(0.2, 1.0)
        got = distance(mask)
        assert got.dtype == np.float64 and np.array_equal(got, ndimage.distance_transform_edt(mask))
    far = np.ones((300, 200), dtype=bool)
    far[0, 0] = False  # one corner: distances across the whole image
    assert np.array_equal(distance(far), ndimage.distance_transform_edt(far))
