"""Feature lines (paper Sec. 4): the kind of an image, and the lines of drawings, clip art and photos.

In every module of the package, arrays are indexed (row, column); points are
(x, y) = (column + 0.5, row + 0.5) in px, x to the right, y downwards
(``contract/README.md``).
"""
