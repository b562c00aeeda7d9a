"""Mesh files decoded once: triangles and the colours of their own materials, for the renderer,
the viewer, grading pictures and the MuJoCo model alike.

:func:`load_mesh` answers from memory (a file read earlier in this process), then from the
disk cache (:mod:`bras_kit.meshes.cache`), and only then decodes the file (pycollada for
COLLADA, trimesh for the rest). :func:`cache_info` and :func:`clear_cache` show and empty the
disk cache; :func:`set_disk_cache` (the ``--no-cache`` flag) turns it off for the process.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

from . import cache
from .cache import CacheInfo
from .decode import DecodeError
from .mesh import Color, Issue, MeshData, Piece

__all__ = ["CacheInfo", "Color", "DecodeError", "Issue", "MeshData", "Piece", "cache_info", "clear_cache",
           "load_mesh", "set_disk_cache"]

MEMORY_BYTES = 256 << 20  # decoded meshes (and the bytes of their files) kept in this process
_memory: dict[tuple[str, int, int, tuple[float, ...] | None], MeshData] = {}
_by_content: dict[str, MeshData] = {}
_by_bytes: dict[tuple[int, tuple[float, ...] | None], list[tuple[bytes, str]]] = {}  # file bytes -> content key
_disk = os.environ.get("BRAS_KIT_NO_CACHE", "") in ("", "0")


def set_disk_cache(enabled: bool) -> None:
    """Use the disk cache of decoded meshes (the default), or neither read nor write it."""
    global _disk
    _disk = enabled


def disk_cache_enabled() -> bool:
    return _disk


def load_mesh(path: str, scale: Sequence[float] | None = None, roots: tuple[str, ...] | None = None) -> MeshData:
    """The decoded triangles of the mesh file ``path`` times ``scale``. Raises :class:`DecodeError`
    for a file that holds no triangles or cannot be read; ``issues`` lists what the file names
    but could not be used (a missing texture...), the rest being drawn. The file is read once,
    and decoded from those bytes; with ``roots`` (a learner's robot), through the one reader
    beneath them (:mod:`bras_kit.trust.learner_files`), as are the files it names."""
    scale_key = None if scale is None or tuple(float(s) for s in scale) == (1.0, 1.0, 1.0) \
        else tuple(float(s) for s in scale)
    memo = None
    if roots is None:  # the user's own file: remembered by path; a learner's is read each time through
        try:           # the reader (a path met before may lead elsewhere now: another learner's file)
            status = os.stat(path)
            memo = (os.path.realpath(path), status.st_mtime_ns, status.st_size, scale_key)
        except OSError as exc:
            raise DecodeError(exc.strerror or str(exc)) from None
        mesh = _memory.get(memo)
        if mesh is not None:
            return mesh
    data = read_mesh_file(path, roots)
    key = _known_key(data, scale_key)
    if key is None:
        key = cache.content_key(data, scale_key)
    mesh = _by_content.get(key)  # the same bytes at another path (a class of learners' copies)
    if mesh is None and _disk:
        mesh = cache.read(key)
    if mesh is None:
        from .decode import decode

        mesh = decode(path, scale_key, data, roots)
        if _disk:
            cache.write(key, mesh)
    mesh.freeze()
    kept = sum(m.nbytes for m in _by_content.values()) + sum(len(b) for same in _by_bytes.values() for b, _ in same)
    if kept + mesh.nbytes + len(data) > MEMORY_BYTES:
        _memory.clear()
        _by_content.clear()
        _by_bytes.clear()
    if memo is not None:
        _memory[memo] = mesh
    if key not in _by_content:
        _by_content[key] = mesh
        _by_bytes.setdefault((len(data), scale_key), []).append((data, key))
    return mesh


def read_mesh_file(path: str, roots: tuple[str, ...] | None = None) -> bytes:
    """The mesh file's bytes (at most 256 MiB, a regular file, never waiting on a pipe): beneath
    ``roots`` by the one reader, else any regular file (the user's own robot)."""
    from ..trust.beneath import Outside
    from ..trust.learner_files import MAX_COPY_BYTES, read_bytes

    try:
        return read_bytes(os.path.abspath(path), roots if roots is not None else ("/",), limit=MAX_COPY_BYTES)
    except Outside as exc:
        raise DecodeError(exc.strerror or str(exc)) from None


def _known_key(data: bytes, scale: tuple[float, ...] | None) -> str | None:
    """The content key of bytes equal to those of a file read earlier in this process (a copy
    of it handed in by another learner): comparing them costs far less than hashing them."""
    for seen, key in _by_bytes.get((len(data), scale), ()):
        if seen == data:
            return key
    return None


def cache_info() -> CacheInfo:
    """The disk cache's folder, number of decoded meshes and size in bytes."""
    return cache.info()


def clear_cache() -> CacheInfo:
    """Empty the disk cache of decoded meshes (and this process's memory of them); returns what went."""
    _memory.clear()
    _by_content.clear()
    _by_bytes.clear()
    return cache.clear()
