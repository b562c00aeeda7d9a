"""Decoded meshes kept on disk, so a mesh file is decoded once per machine, not once per command.

Entries live in ``<cache home>/meshes`` (see :mod:`bras_kit.core.cachedir`), one ``.npz`` of plain
arrays per (file content, scale, loader version), read with ``allow_pickle=False``. Nothing
there is trusted: an entry that is a link, not a regular file, cut short, of another version or
for another key, or whose arrays have the wrong shapes, types or index ranges is ignored and
written again. The folder is bounded: past :data:`MAX_BYTES`, the entries used longest ago go.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import stat
import tempfile
from dataclasses import dataclass

import numpy as np

from ..core.cachedir import cache_home
from .mesh import Issue, MeshData

LOADER_VERSION = 1  # bump when decoding changes what a file gives: older entries are then never read
MAX_BYTES = 512 << 20  # the whole folder
MAX_ENTRY_BYTES = 256 << 20
ENTRY = re.compile(r"^[0-9a-f]{40}\.npz$")
ARRAYS = ("vertices", "faces", "piece_faces", "piece_vertices", "colors", "header")


@dataclass(frozen=True)
class CacheInfo:
    folder: str
    entries: int
    bytes: int


def folder() -> str:
    return os.path.join(cache_home(), "meshes")


def content_key(data: bytes, scale: tuple[float, ...] | None) -> str:
    """The entry name for a file's bytes and scale under this loader version."""
    digest = hashlib.sha256(data).hexdigest()
    label = json.dumps([LOADER_VERSION, digest, None if scale is None else [float(s) for s in scale]])
    return hashlib.sha1(label.encode()).hexdigest()


def read(key: str, where: str | None = None) -> MeshData | None:
    """The entry ``key``, or None when it is absent or not to be trusted (it is then removed)."""
    path = os.path.join(where or folder(), key + ".npz")
    try:
        descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    except OSError:
        return None  # absent, or a link (O_NOFOLLOW refuses it): written again over it
    try:
        info = os.fstat(descriptor)
        if not stat.S_ISREG(info.st_mode) or info.st_size > MAX_ENTRY_BYTES:
            return None
        with os.fdopen(descriptor, "rb") as handle:
            descriptor = -1
            with np.load(handle, allow_pickle=False) as archive:
                arrays = {name: archive[name] for name in ARRAYS}
        mesh = _checked(arrays, key)
    except Exception:  # noqa: BLE001 - cut short, not a zip, wrong arrays: not ours, decode again
        mesh = None
    finally:
        if descriptor >= 0:
            os.close(descriptor)
    if mesh is None:
        _remove(path)
        return None
    try:
        os.utime(path, follow_symlinks=False)  # used now: the last to go when the folder is full
    except OSError:
        pass
    return mesh


def _checked(arrays: dict[str, np.ndarray], key: str) -> MeshData | None:
    header = json.loads(bytes(arrays["header"].astype(np.uint8)).decode("utf-8"))
    if not isinstance(header, dict) or header.get("version") != LOADER_VERSION or header.get("key") != key:
        return None
    vertices, faces = arrays["vertices"], arrays["faces"]
    piece_faces, piece_vertices, colors = arrays["piece_faces"], arrays["piece_vertices"], arrays["colors"]
    if vertices.dtype != np.float32 or vertices.ndim != 2 or vertices.shape[1] != 3:
        return None
    if faces.dtype != np.int32 or faces.ndim != 2 or faces.shape[1] != 3:
        return None
    pieces = len(colors)
    if colors.dtype != np.float32 or colors.shape != (pieces, 4) or pieces == 0:
        return None
    for offsets, total in ((piece_faces, len(faces)), (piece_vertices, len(vertices))):
        if offsets.dtype != np.int64 or offsets.shape != (pieces + 1,) or offsets[0] != 0 \
                or offsets[-1] != total or (np.diff(offsets) < 0).any():
            return None
    if not np.isfinite(vertices).all():
        return None
    known = colors[~np.isnan(colors).any(axis=1)]
    if ((known < 0) | (known > 1)).any():
        return None
    owner = np.repeat(np.arange(pieces), np.diff(piece_faces))  # each face's piece
    low, high = piece_vertices[owner], piece_vertices[owner + 1]
    if len(faces) and ((faces.min(axis=1) < low) | (faces.max(axis=1) >= high)).any():
        return None
    issues = header.get("issues", [])
    if not isinstance(issues, list) or not all(isinstance(i, list) and len(i) == 2 and all(isinstance(s, str) for s in i)
                                               for i in issues):
        return None
    return MeshData(vertices, faces, piece_faces, piece_vertices, colors, tuple(Issue(*i) for i in issues))


def write(key: str, mesh: MeshData, where: str | None = None, max_bytes: int | None = None) -> None:
    """Keep ``mesh`` as entry ``key`` (written aside, then renamed: a reader never sees half of
    it), then drop the oldest entries past ``max_bytes``. A folder that cannot be written is not used."""
    place = where or folder()
    try:
        os.makedirs(place, mode=0o700, exist_ok=True)
        if os.path.islink(place) or not os.path.isdir(place):
            return
        header = json.dumps({"version": LOADER_VERSION, "key": key, "issues": [list(i) for i in mesh.issues]})
        descriptor, temporary = tempfile.mkstemp(dir=place, prefix=".entry-", suffix=".tmp")
        try:
            with os.fdopen(descriptor, "wb") as handle:
                np.savez(handle, vertices=mesh.vertices, faces=mesh.faces, piece_faces=mesh.piece_faces,
                         piece_vertices=mesh.piece_vertices, colors=mesh.colors,
                         header=np.frombuffer(header.encode("utf-8"), dtype=np.uint8))
            os.replace(temporary, os.path.join(place, key + ".npz"))  # replaces a link, never follows it
        except BaseException:
            _remove(temporary)
            raise
    except OSError:
        return
    trim(place, MAX_BYTES if max_bytes is None else max_bytes)


def _entries(place: str) -> list[tuple[float, int, str]]:
    """(last use, size, path) of each entry file in ``place``; links and other files are skipped."""
    out: list[tuple[float, int, str]] = []
    try:
        names = os.listdir(place)
    except OSError:
        return out
    for name in names:
        if not ENTRY.match(name):
            continue
        path = os.path.join(place, name)
        try:
            info = os.lstat(path)
        except OSError:
            continue
        if stat.S_ISREG(info.st_mode):
            out.append((info.st_mtime, info.st_size, path))
    return out


def trim(place: str, max_bytes: int) -> None:
    """Remove the entries used longest ago until the folder holds at most ``max_bytes``."""
    entries = sorted(_entries(place))
    total = sum(size for _, size, _ in entries)
    for _, size, path in entries:
        if total <= max_bytes:
            break
        _remove(path)
        total -= size


def info(where: str | None = None) -> CacheInfo:
    """How many decoded meshes the cache holds and their size in bytes."""
    place = where or folder()
    entries = _entries(place)
    return CacheInfo(place, len(entries), sum(size for _, size, _ in entries))


def clear(where: str | None = None) -> CacheInfo:
    """Remove every decoded mesh (only the cache's own entry files); returns what was removed."""
    removed = info(where)
    for _, _, path in _entries(removed.folder):
        _remove(path)
    return removed


def _remove(path: str) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass
