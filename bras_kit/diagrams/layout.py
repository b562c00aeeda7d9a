"""Tidy tree layout: rows by depth, each parent centred over its children, no overlaps."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from ._tree import children_of, depths_of


@dataclass(frozen=True)
class TreeLayout:
    """Horizontal centres and rows of a drawn tree, in the units of the widths given."""

    x: tuple[float, ...]
    depth: tuple[int, ...]
    width: float  # total width, from 0


def tidy_layout(parent: Sequence[int], widths: Sequence[float] | None = None, gap: float = 1.0) -> TreeLayout:
    """Place a tree in rows: depth = row, siblings left to right, each parent centred over its children.

    ``parent[i]`` is node i's parent index (-1 for the root), parents listed before children;
    ``widths`` are the nodes' box widths (default 1). Reingold-Tilford style: each subtree is
    pushed right just enough that, row by row, its left outline clears the right outline of its
    elder siblings by ``gap``; the parent then sits at the midpoint of its first and last child.
    Outlines are shared lists (deepest row first) with lazy offsets, so a merge costs the height
    of the shallower subtree: linear time overall, and no recursion (a 10,000-link chain is fine).
    """
    n = len(parent)
    if n == 0:
        return TreeLayout((), (), 0.0)
    w = [1.0] * n if widths is None else [float(v) for v in widths]
    if len(w) != n:
        raise ValueError("one width per node expected")
    if parent[0] >= 0 or any(p < 0 for p in parent[1:]):
        raise ValueError("expected one root, listed first")
    children = children_of(parent)
    rel = [0.0] * n  # centre relative to the parent's centre
    # outline of each subtree: rows deepest first; true position = stored + offset (relative to the root)
    left_rows: list[list[float]] = [[] for _ in range(n)]
    right_rows: list[list[float]] = [[] for _ in range(n)]
    left_off = [0.0] * n
    right_off = [0.0] * n
    for v in range(n - 1, -1, -1):  # children before parents
        half = w[v] / 2
        kids = children[v]
        if not kids:
            left_rows[v], right_rows[v] = [-half], [half]
            continue
        first = kids[0]
        lrows, loff, rrows, roff = left_rows[first], left_off[first], right_rows[first], right_off[first]
        positions = [0.0]  # children's centres, relative to the first child
        for child in kids[1:]:
            clrows, crrows = left_rows[child], right_rows[child]
            common = min(len(rrows), len(clrows))
            shift = max(rrows[-1 - d] + roff - clrows[-1 - d] - left_off[child] + gap for d in range(common))
            positions.append(shift)
            cloff, croff = left_off[child] + shift, right_off[child] + shift
            if len(crrows) >= len(rrows):  # the new child reaches every row of its elders
                rrows, roff = crrows, croff
            else:
                for d in range(len(crrows)):
                    rrows[-1 - d] = crrows[-1 - d] + croff - roff
            if len(clrows) > len(lrows):  # rows below the elders are outlined by the new child
                for d in range(len(lrows)):
                    clrows[-1 - d] = lrows[-1 - d] + loff - cloff
                lrows, loff = clrows, cloff
            left_rows[child] = right_rows[child] = []  # merged: release
        middle = (positions[0] + positions[-1]) / 2
        for child, position in zip(kids, positions):
            rel[child] = position - middle
        loff -= middle
        roff -= middle
        lrows.append(-half - loff)
        rrows.append(half - roff)
        left_rows[v], left_off[v], right_rows[v], right_off[v] = lrows, loff, rrows, roff
        left_rows[first] = right_rows[first] = []
    x = [0.0] * n
    for v in range(1, n):
        x[v] = x[parent[v]] + rel[v]
    low = min(x[v] - w[v] / 2 for v in range(n))
    high = max(x[v] + w[v] / 2 for v in range(n))
    return TreeLayout(tuple(c - low for c in x), tuple(depths_of(parent)), high - low)
