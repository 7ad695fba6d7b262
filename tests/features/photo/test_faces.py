"""Tests of img2logo.features.photo.faces: frontal faces in a portrait, none in texture."""

from __future__ import annotations

import numpy as np
from helpers import textured_photo

from img2logo import load_image
from img2logo.features.photo.subject import find_subject


def test_faces_are_found_in_a_portrait_and_not_in_texture():
    from skimage import data

    from img2logo.features.photo.faces import find_faces

    img = load_image(data.astronaut())  # ships with scikit-image, as does the cascade
    faces = find_faces(img)
    assert len(faces) == 1
    x, y, w, h = faces[0]
    assert 150 < x + w / 2 < 280 and 60 < y + h / 2 < 170  # the face, not the patch or the helmet
    subject = find_subject(img)
    assert len(subject.faces) == 1  # searched in the subject's box only: the same face, to a few px
    assert np.abs(np.subtract(subject.faces[0], faces[0])).max() <= 6
    assert "1 face(s) kept with their features" in subject.description
    rgb, _ = textured_photo([(170, 120, 80, 60, (0.95, 0.75, 0.2))])
    assert find_faces(load_image(rgb)) == ()
    assert find_subject(load_image(rgb)).faces == ()
