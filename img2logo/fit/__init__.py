"""The golden arcs (paper Sec. 5): arc extraction, constrained fits, the progressive merge loop, tangency, symmetry."""
