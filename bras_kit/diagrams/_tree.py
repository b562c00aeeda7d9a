"""Children and depths from a parent-index list (parents before children), without recursion."""

from __future__ import annotations

from collections.abc import Sequence


def children_of(parent: Sequence[int]) -> list[list[int]]:
    """Children of each node, in index order; requires parents to come before children."""
    out: list[list[int]] = [[] for _ in parent]
    for i, p in enumerate(parent):
        if p >= 0:
            if p >= i:
                raise ValueError("nodes must be in topological order (each parent before its children)")
            out[p].append(i)
    return out


def depths_of(parent: Sequence[int]) -> list[int]:
    depth = [0] * len(parent)
    for i, p in enumerate(parent):
        if p >= 0:
            depth[i] = depth[p] + 1
    return depth
