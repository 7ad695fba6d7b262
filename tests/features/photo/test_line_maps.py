"""Tests of img2logo.features.photo.line_maps: colour lines gated by the lightness edges and the drawn lines."""

from __future__ import annotations

import numpy as np


def _maps(colour, edges, lightness_step, colour_step):
    from img2logo.features.photo.line_maps import LineMaps

    shape = colour.shape
    return LineMaps(
        np.zeros(shape, bool),
        colour,
        edges,
        np.broadcast_to(np.float32(lightness_step), shape).copy() * edges,
        np.broadcast_to(np.float32(colour_step), shape).copy(),
    )


def test_a_colour_line_beside_an_undrawn_lightness_edge_is_kept_only_if_its_step_is_the_stronger():
    from img2logo.features.photo.line_maps import new_colour_lines

    # A 60 px colour line (row 50, 3 px thick) and, 3 px beside it, a 16 px lightness edge that is
    # not drawn (too short): a pink nose's top on tan fur beside a faint stroke of lightness.
    colour = np.zeros((100, 120), bool)
    colour[49:52, 30:90] = True
    edges = np.zeros_like(colour)
    edges[53:56, 50:66] = True
    nothing = np.zeros_like(colour)
    kept = new_colour_lines(_maps(colour, edges, 0.1, 0.2), nothing)
    assert np.array_equal(kept, colour)  # the colour step is the stronger: the edge is one of colour
    # A stronger lightness step there: the colour line is that edge's tint (a petal's shading),
    # left out within the gate of it, kept beyond.
    tint = new_colour_lines(_maps(colour, edges, 0.3, 0.2), nothing)
    assert not tint[50, 50:66].any()
    assert tint[50, 30:35].all() and tint[50, 85:90].all()


def test_a_colour_line_is_gated_by_the_drawn_lines_and_drawn_back_to_the_line_it_meets():
    from img2logo.features.photo.line_maps import new_colour_lines

    drawn = np.zeros((100, 140), bool)
    drawn[:, 20] = True  # a drawn lightness line, both its sides lightness edges (cols 17-23)
    edges = np.zeros_like(drawn)
    edges[:, 17:24] = True
    colour = np.zeros_like(drawn)
    colour[50, 21:120] = True  # a colour line that leaves it at a right angle ...
    colour[:, 26] = True  # ... and one beside it, all along: the same edge again
    out = new_colour_lines(_maps(colour, edges, 0.5, 0.2), drawn)
    assert out[50, 23:120].all()  # whole, back to the line it meets (its sides: join_line_ends links)
    assert out[:, 26].sum() <= 3  # the doubled edge is not drawn (but where the first line crosses it)
    # A colour line that runs only beside the drawn line is left out whole.
    beside = np.zeros_like(drawn)
    beside[:, 26] = True
    assert not new_colour_lines(_maps(beside, edges, 0.5, 0.2), drawn).any()
