"""A decoded mesh file as plain arrays: every piece's triangles in one vertex and one face array,
with the colour each piece's own material gives (NaN: none, the URDF's colour applies)."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

Color = tuple[float, float, float, float]


class Issue(NamedTuple):
    """Something the file names that could not be used (``kind``: 'broken-reference'), and what."""

    kind: str
    detail: str


class Piece(NamedTuple):
    """Triangles of one material: ``vertices`` (V, 3) float32, ``faces`` (F, 3) int32 into them."""

    vertices: np.ndarray
    faces: np.ndarray
    color: Color | None


@dataclass(frozen=True)
class MeshData:
    """``vertices`` (V, 3) float32, ``faces`` (F, 3) int32 (piece-local vertex numbers shifted to
    the shared array), ``piece_faces`` (P + 1,) int64 offsets of each piece's faces and
    ``piece_vertices`` (P + 1,) of its vertices, ``colors`` (P, 4) float32 (a NaN row: no material)."""

    vertices: np.ndarray
    faces: np.ndarray
    piece_faces: np.ndarray
    piece_vertices: np.ndarray
    colors: np.ndarray
    issues: tuple[Issue, ...] = field(default=())

    @staticmethod
    def join(pieces: Sequence[Piece], issues: Sequence[Issue] = ()) -> MeshData:
        vertex_counts = [len(p.vertices) for p in pieces]
        vertex_starts = np.concatenate([[0], np.cumsum(vertex_counts)]).astype(np.int64)
        face_starts = np.concatenate([[0], np.cumsum([len(p.faces) for p in pieces])]).astype(np.int64)
        vertices = np.concatenate([np.asarray(p.vertices, np.float32).reshape(-1, 3) for p in pieces]) \
            if pieces else np.zeros((0, 3), np.float32)
        faces = np.concatenate([np.asarray(p.faces, np.int64).reshape(-1, 3) + start
                                for p, start in zip(pieces, vertex_starts)]).astype(np.int32) \
            if pieces else np.zeros((0, 3), np.int32)
        colors = np.array([p.color if p.color is not None else (np.nan,) * 4 for p in pieces],
                          dtype=np.float32).reshape(-1, 4)
        return MeshData(vertices, faces, face_starts, vertex_starts, colors, tuple(issues))

    def __len__(self) -> int:
        return len(self.colors)

    def pieces(self) -> Iterator[Piece]:
        """Each piece with its own vertices and faces numbered from 0."""
        for k in range(len(self.colors)):
            first, last = int(self.piece_vertices[k]), int(self.piece_vertices[k + 1])
            faces = self.faces[self.piece_faces[k]:self.piece_faces[k + 1]] - first
            color = self.colors[k]
            yield Piece(self.vertices[first:last], faces,
                        None if np.isnan(color).any() else tuple(float(c) for c in color))  # type: ignore[arg-type]

    def freeze(self) -> MeshData:
        for array in (self.vertices, self.faces, self.piece_faces, self.piece_vertices, self.colors):
            array.flags.writeable = False
        return self

    @property
    def nbytes(self) -> int:
        return sum(a.nbytes for a in (self.vertices, self.faces, self.piece_faces, self.piece_vertices, self.colors))
