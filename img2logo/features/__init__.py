"""Feature lines (paper Sec. 4): the kind of an image, and the lines of drawings, clip art and photos."""
