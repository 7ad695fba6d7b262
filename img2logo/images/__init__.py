"""Images in: loading and decoding, colour (CIELAB), pixel operations (labels, distances, thinning)."""
