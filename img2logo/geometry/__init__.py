"""Geometry values: circles, arcs, the abstraction, the golden ladder, the mirror axis, SVG path data, circle fits."""
