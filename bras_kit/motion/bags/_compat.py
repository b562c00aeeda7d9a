"""The one patch bras-kit applies to ``rosbags``: MCAP chunks decompressed within their declared size.

``rosbags.rosbag2.storage_mcap.DECOMPRESSORS`` maps a chunk's compression ("zstd", "lz4") to a
function ``(data, declared_size) -> bytes``. rosbags' own functions decompress everything and
compare sizes afterwards, so a chunk of a few KiB that expands to gigabytes (a decompression
bomb) fills the memory first. The replacements stop one byte past the declared size (which
:mod:`.reader` has already capped), and rosbags' own size check then refuses the chunk; bytes
left over after the compressed frame (a compressed length that lies) are refused too.

Checked against rosbags 0.11.9 (the range pinned in pyproject.toml); ``tests/motion/test_bags.py``
fails if the table disappears or changes its keys.
"""

from __future__ import annotations

from typing import Any

PATCHED_KEYS = ("", "lz4", "zstd")


def _zstd(data: bytes, size: int) -> bytes:
    try:
        from compression import zstd  # Python 3.14+
    except ImportError:
        from backports import zstd

    decompressor = zstd.ZstdDecompressor()
    out = bytes(decompressor.decompress(data, max_length=size + 1))
    if decompressor.eof and decompressor.unused_data:
        raise ValueError("the chunk's compressed length is longer than its compressed data")
    return out


def _lz4(data: bytes, size: int) -> bytes:
    import lz4.frame

    decompressor = lz4.frame.LZ4FrameDecompressor()
    out = bytes(decompressor.decompress(data, max_length=size + 1))
    if decompressor.eof and decompressor.unused_data:
        raise ValueError("the chunk's compressed length is longer than its compressed data")
    return out


def bounded_decompression() -> None:
    """Install the bounded decompressors in rosbags' MCAP reader (idempotent)."""
    from rosbags.rosbag2 import storage_mcap

    table: dict[str, Any] = storage_mcap.DECOMPRESSORS
    table["zstd"] = _zstd
    table["lz4"] = _lz4
