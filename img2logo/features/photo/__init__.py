"""Photos (paper Sec. 4, beyond it): the subject, its outline, its inner lines and its dark dots.

A rectangle (a subject's, a face's box) is (x, y, w, h) in px, x the column and y
the row of its top-left corner; arrays and points as in :mod:`img2logo.features`.
"""
