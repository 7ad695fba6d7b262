"""Tracing a 1-px skeleton into nodes and ordered pixel chains, and pruning it.

Private to the package: :mod:`img2logo.features.preprocessing` prunes spurs with it and
joins line ends that stop short of another line (:func:`join_line_ends`, for
every kind of input), and :mod:`img2logo.segment_graph` builds the segment
graph from it.

A skeleton pixel is classified by its *crossing number*, the number of
background-to-line transitions met walking once round its 8 neighbours. Counting
neighbours instead would call the corner pixels of every diagonal staircase a
junction (a thinning artefact that reads as dozens of false junctions); the
crossing number is 2 on such a staircase, 1 at a line end, >= 3 where lines branch.
Touching node pixels are clustered into one node.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._compat import nonzero
from .._compiled import kernels
from ..geometry.primitives import polyline_length

# The 8 neighbours in circular order: N, NE, E, SE, S, SW, W, NW (row, column).
RING = ((-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1))


_EIGHT = np.ones((3, 3), dtype=bool)


@dataclass
class PixelGraph:
    """Mutable working graph of a skeleton (private).

    ``nodes[n]`` is a position (x, y) in px; ``node_pixels[n]`` the (row, col)
    pixels of its cluster; ``chains[c]`` an ordered (m, 2) array of (row, col)
    pixels strictly between its two end nodes ``ends[c]``, from ``ends[c][0]``
    to ``ends[c][1]`` (m may be 0 when the two nodes touch).
    """

    nodes: list[np.ndarray] = field(default_factory=list)
    node_pixels: list[np.ndarray] = field(default_factory=list)
    chains: list[np.ndarray] = field(default_factory=list)
    ends: list[tuple[int, int]] = field(default_factory=list)
    #: Line pixels of nodes dissolved into a chain: still drawn by rasterize().
    loose_pixels: list[np.ndarray] = field(default_factory=list)

    def add_node(self, xy: np.ndarray, pixels: np.ndarray) -> int:
        self.nodes.append(np.asarray(xy, dtype=np.float64))
        self.node_pixels.append(np.asarray(pixels, dtype=np.int64).reshape(-1, 2))
        return len(self.nodes) - 1

    def valence(self) -> np.ndarray:
        v = np.zeros(len(self.nodes), dtype=np.int64)
        for a, b in self.ends:
            v[a] += 1
            v[b] += 1
        return v

    def polyline(self, c: int) -> np.ndarray:
        """Chain ``c`` as (x, y) points, px, from its start node to its end node."""
        a, b = self.ends[c]
        inner = self.chains[c][:, ::-1].astype(np.float64) + 0.5
        return np.vstack([self.nodes[a][None], inner, self.nodes[b][None]])

    def length(self, c: int) -> float:
        return polyline_length(self.polyline(c))


# Every pixel's 8 neighbours as one byte (bit k: RING[k] is set), and the crossing number
# and neighbour count of each of the 256 bytes.
_CODE_WEIGHTS = np.zeros((3, 3), dtype=np.float32)


for _k, (_dr, _dc) in enumerate(RING):
    _CODE_WEIGHTS[1 + _dr, 1 + _dc] = 1 << _k


_BITS = (np.arange(256)[:, None] >> np.arange(8)) & 1


_CROSSINGS = np.sum((_BITS == 0) & (np.roll(_BITS, -1, axis=1) == 1), axis=1).astype(np.uint8)


_COUNTS = _BITS.sum(axis=1).astype(np.uint8)


def classify(skel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Crossing number and neighbour count of every pixel of ``skel`` (H, W) bool: two (H, W) uint8.

    The 8 neighbours are coded as one byte by OpenCV's correlation with the
    weights 1, 2, ..., 128 (exact in float32, outside the image 0), and the two
    numbers read from 256-entry tables (a tenth of the time of the 8 shifted copies).
    """
    import cv2

    src = np.ascontiguousarray(skel, dtype=bool).view(np.uint8)
    code = cv2.filter2D(src, cv2.CV_32F, _CODE_WEIGHTS, borderType=cv2.BORDER_CONSTANT).astype(np.uint8)
    return cv2.LUT(code, _CROSSINGS), cv2.LUT(code, _COUNTS)


def trace(skel: np.ndarray) -> PixelGraph:
    """Trace a 1-px skeleton (H, W) bool into a :class:`PixelGraph`.

    Node pixels are line ends (crossing number 1) and branch pixels (crossing
    number >= 3) with their line neighbours; each 8-connected cluster of them is
    one node at the cluster's centroid. Every 8-connected run of the other pixels is ordered by a shortest
    path between the nodes it touches, which steps over the redundant corner
    pixels that thinning leaves. A run touching no node is a closed loop: it gets
    one node on the loop, so it becomes a chain from that node back to itself.
    """
    skel = np.asarray(skel, dtype=bool)
    crossings, count = classify(skel)
    skel = skel & (count > 0)  # isolated pixels are specks, not lines
    # A junction's node takes in its line neighbours too: otherwise the branches
    # stay 8-connected to each other around a single junction pixel.
    import cv2

    branch = cv2.dilate((skel & (crossings >= 3)).astype(np.uint8), _EIGHT.astype(np.uint8)) > 0
    node_mask = skel & ((crossings == 1) | branch)
    graph = PixelGraph()

    # The line's pixels once, in raster order; the nodes' and the chains' are among them.
    line_rows, line_cols = nonzero(skel)
    on_node = node_mask[line_rows, line_cols]
    rr, cc = line_rows[on_node], line_cols[on_node]  # where node_lab > 0
    node_lab = _sparse_label(node_mask, rr, cc)
    n_nodes = int(node_lab.max())
    if n_nodes:
        order = np.argsort(node_lab[rr, cc], kind="stable")
        rr, cc = rr[order], cc[order]
        splits = np.cumsum(np.bincount(node_lab[rr, cc], minlength=n_nodes + 1))[:-1]
        for pix in np.split(np.column_stack([rr, cc]), splits[1:]):
            graph.add_node(pix.mean(axis=0)[::-1] + 0.5, pix)

    chain_mask = skel & ~node_mask
    rows, cols = line_rows[~on_node], line_cols[~on_node]  # np.nonzero(chain_mask)
    if len(rows) == 0:
        return graph
    index = np.full(skel.shape, -1, dtype=np.int64)
    index[rows, cols] = np.arange(len(rows))
    comp_lab = _sparse_label(chain_mask, rows, cols)
    n_comp = int(comp_lab.max())
    comp_of = comp_lab[rows, cols] - 1

    # Weighted 8-neighbour adjacency of chain pixels, and their contacts with nodes.
    h, w = skel.shape
    src, dst, wts, c_pix, c_node = [], [], [], [], []
    for dr, dc in RING:
        r2, c2 = rows + dr, cols + dc
        inside = (r2 >= 0) & (r2 < h) & (c2 >= 0) & (c2 < w)
        i = np.flatnonzero(inside)
        j = index[r2[i], c2[i]]
        keep = j >= 0
        src.append(i[keep])
        dst.append(j[keep])
        wts.append(np.full(keep.sum(), np.hypot(dr, dc)))
        lab = node_lab[r2[i], c2[i]]
        touch = lab > 0
        c_pix.append(i[touch])
        c_node.append(lab[touch] - 1)
    # The pixels renumbered run by run (each run a block, raster order within it):
    # every edge stays within its run, so a run's graph is a slice of the whole.
    by_run = np.argsort(comp_of, kind="stable")
    renumber = np.empty(len(rows), dtype=np.int64)
    renumber[by_run] = np.arange(len(rows))
    src_, dst_ = renumber[np.concatenate(src)], renumber[np.concatenate(dst)]
    adj = _Graph.from_edges(src_, dst_, np.concatenate(wts), len(rows))
    block = np.concatenate([[0], np.cumsum(np.bincount(comp_of, minlength=n_comp))])
    contact_pix = np.concatenate(c_pix)
    contact_node = np.concatenate(c_node)

    contacts: list[dict[int, set[int]]] = [{} for _ in range(n_comp)]
    run_of = comp_of.tolist()
    for p, n in zip(contact_pix.tolist(), contact_node.tolist(), strict=True):
        contacts[run_of[p]].setdefault(n, set()).add(p)

    pixels = np.column_stack([rows, cols])
    place = renumber.tolist()  # a pixel's place in its run's block: place[g] - the block's start
    bounds = block.tolist()
    for comp in range(n_comp):
        a, b = bounds[comp], bounds[comp + 1]
        ends = _contact_groups(contacts[comp], pixels, place, a)
        _trace_component(graph, adj.block(a, b), by_run[a:b], pixels, ends)
    return graph


def _sparse_label(mask: np.ndarray, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """The 8-connected components of a sparse ``mask`` whose set pixels are (rows, cols), in raster order.

    :func:`img2logo.images.ndimage.components` ``(mask, connectivity=2)``'s numbers, int64, by
    :func:`img2logo._compiled.front.sparse_label_kernel` over those pixels alone.
    """
    out = np.zeros(mask.shape, dtype=np.int64)
    if len(rows):
        out[rows, cols] = kernels.sparse_label_kernel(rows, cols, mask.shape[0], mask.shape[1])
    return out


@dataclass(frozen=True)
class _Graph:
    """A weighted directed graph in CSR form: node i's edges go to ``indices[indptr[i]:indptr[i + 1]]``."""

    indptr: np.ndarray  # (N + 1,) int64
    indices: np.ndarray  # (E,) int64, ascending within a node's edges
    weights: np.ndarray  # (E,) float64, px

    @classmethod
    def from_edges(cls, src: np.ndarray, dst: np.ndarray, weights: np.ndarray, n: int) -> _Graph:
        order = np.lexsort((dst, src))
        indptr = np.concatenate([[0], np.cumsum(np.bincount(src, minlength=n))]).astype(np.int64)
        return cls(indptr, np.ascontiguousarray(dst[order], dtype=np.int64), np.ascontiguousarray(weights[order]))

    @property
    def n(self) -> int:
        return len(self.indptr) - 1

    def neighbours(self, i: int) -> np.ndarray:
        return self.indices[self.indptr[i] : self.indptr[i + 1]]

    def block(self, a: int, b: int) -> _Graph:
        """The subgraph of nodes a..b-1, renumbered from 0 (no edge may leave it)."""
        lo, hi = self.indptr[a], self.indptr[b]
        return _Graph(self.indptr[a : b + 1] - lo, self.indices[lo:hi] - a, self.weights[lo:hi])

    def without(self, node: int) -> _Graph:
        """The same nodes without the edges to and from ``node``."""
        src = np.repeat(np.arange(self.n), np.diff(self.indptr))
        keep = (src != node) & (self.indices != node)
        indptr = np.concatenate([[0], np.cumsum(np.bincount(src[keep], minlength=self.n))]).astype(np.int64)
        return _Graph(indptr, self.indices[keep], self.weights[keep])


def _dijkstra(graph: _Graph, sources: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """Distances (N,) from the nearest source and predecessors (N,), -9999 for none.

    ``scipy.sparse.csgraph.dijkstra(graph, indices=sources, min_only=True,
    return_predecessors=True)`` to the bit, the same path among equally short
    ones (the tests compare the two), without importing ``scipy.sparse`` (its
    array-API layer and ``csgraph`` cost a run about 0.25 s of CPU): the compiled
    kernel :func:`img2logo._compiled.graph.dijkstra_kernel`.
    """
    from .._compiled import kernels

    dist = np.empty(graph.n)
    pred = np.empty(graph.n, dtype=np.int64)
    kernels.dijkstra_kernel(graph.indptr, graph.indices, graph.weights, np.asarray(sources, dtype=np.int64), dist, pred)
    return dist, pred


def _contact_groups(
    node_contacts: dict[int, set[int]], pixels: np.ndarray, place: list[int], start: int
) -> list[tuple[int, list[int]]]:
    """Group a run's node contacts into ends: (node, local pixel indices).

    Pixel ``g`` of the run is its pixel ``place[g] - start``. A node touching
    the run in two separate places (a loop from a junction back to itself)
    gives two ends.
    """
    groups = []
    for node, contact in sorted(node_contacts.items()):
        pix = sorted(contact)
        pts = pixels[pix].tolist()  # as Python ints: a few pixels, numpy's scalar steps cost more
        lab = list(range(len(pix)))
        for a in range(len(pix)):  # tiny groups: a quadratic union is fine
            for b in range(a + 1, len(pix)):
                if max(abs(pts[a][0] - pts[b][0]), abs(pts[a][1] - pts[b][1])) <= 1:
                    old, new = lab[b], lab[a]
                    lab = [new if x == old else x for x in lab]
        for g in sorted(set(lab)):
            groups.append((node, [place[pix[k]] - start for k in range(len(pix)) if lab[k] == g]))
    return groups


def _shortest_path(sub: _Graph, sources: list[int], targets: list[int]) -> list[int]:
    dist, pred_ = _dijkstra(sub, sources)
    t = min(targets, key=lambda k: dist[k])
    pred = pred_.tolist()  # followed as Python ints: numpy's scalar indexing per pixel was most of the time
    path = [t]
    while pred[path[-1]] >= 0:
        path.append(pred[path[-1]])
    return path[::-1]


def _trace_component(
    graph: PixelGraph,
    sub: _Graph,
    idx: np.ndarray,
    pixels: np.ndarray,
    ends: list[tuple[int, list[int]]],
) -> None:
    """Turn one run of chain pixels into chains of ``graph`` (see :func:`trace`)."""
    pix = pixels[idx]
    if not ends:
        # Closed loop: cut it open next to its first pixel, which becomes a node.
        start = 0
        nbrs = sub.neighbours(start)
        if len(nbrs) == 0:
            return
        cut = sub.without(start)
        rest = _shortest_path(cut, [int(nbrs[0])], [int(n) for n in nbrs[1:]] or [int(nbrs[0])])
        node = graph.add_node(pix[start][::-1] + 0.5, pix[start][None])
        graph.chains.append(pix[rest])
        graph.ends.append((node, node))
        return
    if len(ends) == 1:
        # A run leaving one node and ending in a blob: end it at its farthest pixel.
        node, src = ends[0]
        dist = _dijkstra(sub, src)[0]
        far = int(np.argmax(np.where(np.isfinite(dist), dist, -1)))
        path = _shortest_path(sub, src, [far])
        tip = graph.add_node(pix[far][::-1] + 0.5, pix[far][None])
        graph.chains.append(pix[path[:-1]])
        graph.ends.append((node, tip))
        return
    if len(ends) == 2:
        (na, sa), (nb, sb) = ends
        graph.chains.append(pix[_shortest_path(sub, sa, sb)])
        graph.ends.append((na, nb))
        return
    # Three or more ends on one run (a branch the crossing number missed): a new
    # junction at the pixel with the smallest total path length to all ends.
    dist = np.vstack([_dijkstra(sub, s)[0] for _, s in ends])
    hub = int(np.argmin(dist.sum(axis=0)))
    centre = graph.add_node(pix[hub][::-1] + 0.5, pix[hub][None])
    for node, src in ends:
        path = _shortest_path(sub, [hub], src)
        graph.chains.append(pix[path[1:]])
        graph.ends.append((centre, node))


def prune(
    graph: PixelGraph,
    *,
    spur_length: float,
    min_length: float,
    junction_merge: float,
    radius: np.ndarray | None = None,
) -> list[np.ndarray]:
    """Clean a traced graph in place; return the (row, col) pixels of removed chains.

    Repeats until nothing changes: drops side spurs shorter than ``spur_length``
    (a chain from a free end to a junction; at a fork where every branch but one
    is a spur the longest spur stays, so a line end is not eaten away). With
    ``radius`` (an (H, W) map of the stroke's half width, px: the ink's distance
    transform) a spur is judged by the ink it adds: the medial axis of a thick
    stroke grows a branch towards every corner and square end, whose tip is a
    small disc inside the junction's large one. A branch of length L whose tip
    has half width r_tip reaches L + r_tip from a junction of half width r_j, so
    it sticks out of the stroke by L + r_tip - r_j, and it is a spur when that is
    below ``spur_length`` (for a thin line, r_tip = r_j: the same test). Isolated
    chains and closed loops shorter than ``min_length``, loops hanging on a line
    shorter than ``spur_length``; contracts chains shorter than ``junction_merge`` between two
    junctions into one junction (a thick "X" thins to two "Y"s and a bridge);
    joins the two chains at every node of valence 2.
    """
    removed: list[np.ndarray] = []
    changed = True
    while changed:
        changed = False
        val = graph.valence()
        lengths = [graph.length(c) for c in range(len(graph.chains))]
        limit = _half_widths(graph, radius)
        drop: set[int] = set()
        spurs_at: dict[int, list[int]] = {}
        for c, (a, b) in enumerate(graph.ends):
            if a == b:
                # A tiny loop on a line (a hole in a thick stroke), or a speck.
                if (val[a] > 2 and lengths[c] < spur_length) or (val[a] == 2 and lengths[c] < min_length):
                    drop.add(c)
                continue
            if val[a] == 1 and val[b] == 1 and lengths[c] < min_length:
                drop.add(c)
            elif val[a] == 1 and val[b] >= 3 and lengths[c] < spur_length + max(0.0, limit[b] - limit[a]):
                spurs_at.setdefault(b, []).append(c)
            elif val[b] == 1 and val[a] >= 3 and lengths[c] < spur_length + max(0.0, limit[a] - limit[b]):
                spurs_at.setdefault(a, []).append(c)
        for node, spurs in spurs_at.items():
            spurs.sort(key=lambda c: lengths[c])
            keep = max(0, 2 - (val[node] - len(spurs)))  # keep the line going through
            drop.update(spurs[: len(spurs) - keep] if keep else spurs)
        if drop:
            removed.extend(graph.chains[c] for c in drop)
            _remove_chains(graph, drop)
            changed = True
            continue
        if _contract_short_bridges(graph, junction_merge):
            changed = True
            continue
        if _join_valence_two(graph):
            changed = True
    _drop_unused_nodes(graph)
    return removed


def _half_widths(graph: PixelGraph, radius: np.ndarray | None) -> np.ndarray:
    """The stroke's half width at each node, px (``radius`` there; zeros without it)."""
    if radius is None or not len(graph.nodes):
        return np.zeros(len(graph.nodes))
    xy = np.array(graph.nodes)
    h, w = radius.shape
    rows = np.clip(np.floor(xy[:, 1]).astype(int), 0, h - 1)
    cols = np.clip(np.floor(xy[:, 0]).astype(int), 0, w - 1)
    return radius[rows, cols].astype(np.float64)


def _remove_chains(graph: PixelGraph, drop: set[int]) -> None:
    graph.chains = [ch for c, ch in enumerate(graph.chains) if c not in drop]
    graph.ends = [e for c, e in enumerate(graph.ends) if c not in drop]


def _contract_short_bridges(graph: PixelGraph, junction_merge: float) -> bool:
    val = graph.valence()
    for c, (a, b) in enumerate(graph.ends):
        if a != b and val[a] >= 3 and val[b] >= 3 and graph.length(c) < junction_merge:
            # Merge node b into node a at the bridge's midpoint; the bridge's pixels
            # become part of the node's cluster.
            graph.nodes[a] = (graph.nodes[a] + graph.nodes[b]) / 2.0
            graph.node_pixels[a] = np.vstack([graph.node_pixels[a], graph.node_pixels[b], graph.chains[c]])
            _remove_chains(graph, {c})
            graph.ends = [(a if x == b else x, a if y == b else y) for x, y in graph.ends]
            return True
    return False


def _join_valence_two(graph: PixelGraph) -> bool:
    val = graph.valence()
    for node in np.flatnonzero(val == 2):
        at = [c for c, (a, b) in enumerate(graph.ends) if node in (a, b)]
        if len(at) != 2:
            continue  # a loop through this node alone: keep the node on it
        c1, c2 = at
        # Orient c1 to end at the node and c2 to start there, then concatenate.
        ch1, (a1, b1) = graph.chains[c1], graph.ends[c1]
        if a1 == node:
            ch1, (a1, b1) = ch1[::-1], (b1, a1)
        ch2, (a2, b2) = graph.chains[c2], graph.ends[c2]
        if b2 == node:
            ch2, (a2, b2) = ch2[::-1], (b2, a2)
        cluster = graph.node_pixels[node]
        graph.loose_pixels.append(cluster)
        joined = np.vstack([ch1, _bridge(ch1, ch2, cluster), ch2])
        _remove_chains(graph, {c1, c2})
        graph.chains.append(joined)
        graph.ends.append((a1, b2))
        return True
    return False


def _bridge(ch1: np.ndarray, ch2: np.ndarray, cluster: np.ndarray) -> np.ndarray:
    """Pixels of ``cluster`` leading from the end of ``ch1`` to the start of ``ch2``.

    A greedy walk over 8-neighbours, each step the cluster pixel nearest the
    target: clusters are a few pixels, so this stays short and gap-free.
    """
    if len(ch1) == 0 or len(ch2) == 0:
        return cluster[:1]
    here, target = ch1[-1], ch2[0]
    path: list[np.ndarray] = []
    left = [p for p in cluster if not (np.array_equal(p, here) or np.array_equal(p, target))]
    while np.max(np.abs(here - target)) > 1 and left:
        steps = [p for p in left if np.max(np.abs(p - here)) <= 1]
        if not steps:
            break
        here = min(steps, key=lambda p: float(np.hypot(*(p - target))))
        left = [p for p in left if not np.array_equal(p, here)]
        path.append(here)
    return np.array(path, dtype=np.int64).reshape(-1, 2)


def _drop_unused_nodes(graph: PixelGraph) -> None:
    val = graph.valence()
    keep = np.flatnonzero(val > 0)
    remap = {int(old): new for new, old in enumerate(keep)}
    graph.nodes = [graph.nodes[k] for k in keep]
    graph.node_pixels = [graph.node_pixels[k] for k in keep]
    graph.ends = [(remap[a], remap[b]) for a, b in graph.ends]


def rasterize(graph: PixelGraph, shape: tuple[int, int]) -> np.ndarray:
    """The pixels of a traced graph as an (H, W) bool map."""
    out = np.zeros(shape, dtype=bool)
    for pix in [*graph.chains, *graph.node_pixels, *graph.loose_pixels]:
        if len(pix):
            out[pix[:, 0], pix[:, 1]] = True
    return out
