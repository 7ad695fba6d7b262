"""The graph kernels against scipy, the oracle they replace (scipy is imported by the tests only)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from helpers import modules_loaded

from img2logo._compiled import kernels
from img2logo.fit.constrained_sqp import SparseKKT, solve_kkt
from img2logo.images import skeleton as _skeleton

ROOT = Path(__file__).resolve().parents[2]


def _pixel_graph(seed: int) -> tuple[_skeleton._Graph, object]:
    """The 8-neighbour graph (weights 1 and sqrt 2) of random pixels: many equally short paths."""
    from scipy import sparse

    rng = np.random.default_rng(seed)
    h, w = rng.integers(3, 16, 2)
    mask = rng.random((h, w)) < 0.6
    mask[0, 0] = True
    rows, cols = np.nonzero(mask)
    index = np.full(mask.shape, -1)
    index[rows, cols] = np.arange(len(rows))
    src, dst, wts = [], [], []
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            if dr == dc == 0:
                continue
            r2, c2 = rows + dr, cols + dc
            i = np.flatnonzero((r2 >= 0) & (r2 < h) & (c2 >= 0) & (c2 < w))
            j = index[r2[i], c2[i]]
            src.append(i[j >= 0])
            dst.append(j[j >= 0])
            wts.append(np.full(int((j >= 0).sum()), np.hypot(dr, dc)))
    src, dst, wts = np.concatenate(src), np.concatenate(dst), np.concatenate(wts)
    n = len(rows)
    return _skeleton._Graph.from_edges(src, dst, wts, n), sparse.csr_matrix((wts, (src, dst)), shape=(n, n))


def _dijkstra_reference(graph, sources: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """The Dijkstra kernel's oracle in Python: nearest node first, the larger index first among equal ones (scipy's)."""
    import heapq

    dist = [math.inf] * graph.n
    pred = [-9999] * graph.n
    heap = []
    for s in sources:
        dist[s] = 0.0
        heapq.heappush(heap, (0.0, -s))
    indptr, indices, weights = graph.indptr.tolist(), graph.indices.tolist(), graph.weights.tolist()
    while heap:
        d, v = heapq.heappop(heap)
        v = -v
        if dist[v] < d:
            continue
        for e in range(indptr[v], indptr[v + 1]):
            j, nd = indices[e], d + weights[e]
            if dist[j] > nd:
                dist[j] = nd
                pred[j] = v
                heapq.heappush(heap, (nd, -j))
    return np.array(dist), np.array(pred, dtype=np.int64)


@pytest.mark.parametrize("seed", range(40))
def test_dijkstra_is_scipys_to_the_bit(seed):
    from scipy.sparse import csgraph

    graph, oracle = _pixel_graph(seed)
    rng = np.random.default_rng(seed + 1000)
    sources = [int(s) for s in rng.choice(graph.n, size=min(graph.n, int(rng.integers(1, 4))), replace=False)]
    want_dist, want_pred, _ = csgraph.dijkstra(oracle, indices=sources, min_only=True, return_predecessors=True)
    for dist, pred in (_skeleton._dijkstra(graph, sources), _dijkstra_reference(graph, sources)):
        np.testing.assert_array_equal(dist, want_dist)
        np.testing.assert_array_equal(pred, want_pred)


def test_a_graph_without_one_nodes_edges_and_a_block():
    graph, oracle = _pixel_graph(3)
    cut = graph.without(0)
    assert len(cut.neighbours(0)) == 0
    assert 0 not in cut.indices
    assert cut.indptr[-1] == graph.indptr[-1] - 2 * len(graph.neighbours(0))
    whole = graph.block(0, graph.n)
    np.testing.assert_array_equal(whole.indices, graph.indices)
    np.testing.assert_array_equal(graph.neighbours(0), np.sort(oracle[0].indices))


def _random_system(seed: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A sparse symmetric indefinite system with repeated entries (summed), like a KKT matrix."""
    rng = np.random.default_rng(seed)
    m = 3 * n
    rows = np.concatenate([rng.integers(0, n, m), np.arange(n)])
    cols = np.concatenate([np.clip(rows[:m] + rng.integers(-8, 9, m), 0, n - 1), np.arange(n)])
    vals = np.concatenate([rng.normal(size=m), rng.normal(size=n) * 3])
    rows, cols, vals = np.concatenate([rows, cols]), np.concatenate([cols, rows]), np.concatenate([vals, vals])
    return rows.astype(np.int64), cols.astype(np.int64), vals, rng.normal(size=n)


@pytest.mark.parametrize(("seed", "n"), [(0, 3), (1, 40), (2, 300), (3, 700)])
def test_banded_solve_matches_lapack(seed, n):
    rows, cols, vals, rhs = _random_system(seed, n)
    dense = SparseKKT(vals, rows, cols, n).toarray()
    x = np.empty(n)
    assert kernels.banded_solve_kernel(rows, cols, vals, rhs, x) == 0
    np.testing.assert_allclose(x, np.linalg.solve(dense, rhs), rtol=1e-9, atol=1e-9 * np.abs(x).max())


def test_banded_solve_refuses_a_singular_matrix():
    rows = np.array([0, 0, 1, 1], dtype=np.int64)
    cols = np.array([0, 1, 0, 1], dtype=np.int64)
    x = np.empty(2)
    assert kernels.banded_solve_kernel(rows, cols, np.array([1.0, 2.0, 2.0, 4.0]), np.ones(2), x) == 1


@pytest.mark.parametrize("reduced", [False, True])
def test_sparse_kkt_solve_matches_superlu(reduced):
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import splu

    n, m = 120, 80
    rows, cols, vals, _ = _random_system(7, n + m)
    mat = SparseKKT(vals, rows, cols, n + m)
    rng = np.random.default_rng(8)
    g, c = rng.normal(size=n), rng.normal(size=m)
    keep = np.setdiff1d(np.arange(n + m), [3, 4, 50]) if reduced else None
    dx, lam, curvature = solve_kkt(mat, 1e-9, g, c, keep)
    full = csc_matrix((vals, (rows, cols)), shape=(n + m, n + m))
    rhs = np.concatenate([-g, -c])
    if keep is None:
        want = splu(full).solve(rhs)
    else:
        want = np.zeros(n + m)
        want[keep] = splu(full[keep][:, keep].tocsc()).solve(rhs[keep])
    np.testing.assert_allclose(np.concatenate([dx, lam]), want, rtol=1e-9, atol=1e-9 * np.abs(want).max())
    assert np.isfinite(curvature)


def test_sparse_kkt_solve_without_compiled_kernels(monkeypatch):
    monkeypatch.setattr(kernels, "usable", lambda: False)
    rows, cols, vals, rhs = _random_system(9, 90)
    dx, lam, _ = solve_kkt(SparseKKT(vals, rows, cols, 90), 1e-9, -rhs[:60], -rhs[60:])
    want = np.linalg.solve(SparseKKT(vals, rows, cols, 90).toarray(), rhs)
    np.testing.assert_allclose(np.concatenate([dx, lam]), want)


def test_a_clip_art_run_imports_no_scipy_and_no_scikit_image_package(tmp_path):
    code = (
        "import sys\n"
        "from img2logo.app.cli import main\n"
        f"main([{str(ROOT / 'data' / 'clipart-fish.png')!r}, '--svg', {str(tmp_path / 'fish.svg')!r}, '-q'])\n"
    )
    assert modules_loaded(code, "scipy", "skimage") == []
