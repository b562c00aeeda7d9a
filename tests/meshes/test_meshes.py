"""Mesh files decoded once (bras_kit.meshes): materials per piece, broken references tolerated,
and the on-disk cache that nothing can fool (links, cut-short, foreign files), bounded in size.

Oracles: the COLLADA files read with xml.etree (triangle counts and diffuse colours per
material), files written by hand (an ASCII STL), and the cache folder's own contents."""

from __future__ import annotations

import os
import site
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from paths import TESTS
from robot_corpus import ROBOTS

from bras_kit import meshes
from bras_kit.meshes import cache

COLLADA = {"c": "http://www.collada.org/2005/11/COLLADASchema"}
DATA = TESTS / "data" / "meshes"


FOOT = ROBOTS / "anymal_b_simple_description" / "meshes" / "foot" / "anymal_foot.dae"
PANDA_LINK0 = ROBOTS / "panda_description" / "meshes" / "visual" / "link0.dae"


@pytest.fixture(autouse=True)
def own_cache(tmp_path, monkeypatch):
    """Each test with an empty cache folder of its own and nothing remembered in memory."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    _forget(monkeypatch)
    monkeypatch.setattr(meshes, "_by_content", {})
    monkeypatch.setattr(meshes, "_disk", True)
    return tmp_path / "xdg" / "bras-kit" / "meshes"


def _triangles_per_material(path: Path) -> dict[str, int]:
    """From the XML: triangle count of each <triangles material=...> (symbols as written)."""
    root = ET.parse(path).getroot()
    counts: dict[str, int] = {}
    for triangles in root.iterfind(".//c:triangles", COLLADA):
        counts[triangles.get("material", "")] = counts.get(triangles.get("material", ""), 0) + int(triangles.get("count"))
    return counts


def _diffuse_colours(path: Path) -> set[tuple[float, ...]]:
    root = ET.parse(path).getroot()
    return {tuple(round(float(v), 3) for v in colour.text.split()[:3])
            for colour in root.iterfind(".//c:effect//c:diffuse/c:color", COLLADA)}


def _stl(path: Path, vertices: np.ndarray, faces: np.ndarray) -> Path:
    rows = ["solid t"]
    for face in faces:
        rows += ["facet normal 0 0 0", "outer loop"]
        rows += [f"vertex {x:.9g} {y:.9g} {z:.9g}" for x, y, z in vertices[face]]
        rows += ["endloop", "endfacet"]
    path.write_text("\n".join(rows + ["endsolid t", ""]))
    return path


def _tetrahedron(tmp_path: Path, name: str = "t.stl", size: float = 1.0) -> Path:
    vertices = np.array([[0, 0, 0], [size, 0, 0], [0, size, 0], [0, 0, size]], dtype=float)
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return _stl(tmp_path / name, vertices, faces)


# --------------------------------------------------------------- decoding


def test_a_collada_file_with_a_missing_texture_gives_all_its_triangles_and_says_what_is_missing():
    mesh = meshes.load_mesh(str(FOOT))
    assert len(mesh.faces) == sum(_triangles_per_material(FOOT).values()) == 4604
    assert any("carbon_uv_texture" in issue.detail for issue in mesh.issues)
    # the piece whose material is missing has no colour of its own: the URDF's applies
    assert np.isnan(mesh.colors).all(axis=1).sum() == 1


def test_each_collada_material_keeps_its_diffuse_colour_and_its_triangles():
    mesh = meshes.load_mesh(str(PANDA_LINK0))
    assert len(mesh.faces) == sum(_triangles_per_material(PANDA_LINK0).values())
    own = {tuple(round(float(c), 3) for c in colour[:3]) for colour in mesh.colors}
    assert own == _diffuse_colours(PANDA_LINK0)  # white, light grey 0.90/0.92/0.93, dark grey 0.25
    assert (0.902, 0.922, 0.929) in own and (0.251, 0.251, 0.251) in own


def test_an_stl_has_no_colour_of_its_own_and_a_mirroring_scale_keeps_it_outward(tmp_path):
    path = _tetrahedron(tmp_path)
    plain = meshes.load_mesh(str(path))
    mirrored = meshes.load_mesh(str(path), (-2.0, 1.0, 1.0))
    assert np.isnan(plain.colors).all()

    def volume(mesh: meshes.MeshData) -> float:
        v = mesh.vertices.astype(float)[mesh.faces]
        return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)

    assert volume(plain) == pytest.approx(1 / 6)
    assert volume(mirrored) == pytest.approx(2 / 6)  # twice as large, still positive: outward
    assert mirrored.vertices[:, 0].min() == pytest.approx(-2.0)


def test_a_file_with_no_triangles_is_refused_with_a_reason(tmp_path):
    empty = tmp_path / "empty.stl"
    empty.write_text("solid t\nendsolid t\n")
    with pytest.raises(meshes.DecodeError):
        meshes.load_mesh(str(empty))


# --------------------------------------------------------------- the cache


def _forget(monkeypatch) -> None:
    """What a new process knows: nothing in memory (the disk cache stays)."""
    monkeypatch.setattr(meshes, "_memory", {})
    monkeypatch.setattr(meshes, "_by_content", {})


def _entry(folder: Path) -> Path:
    entries = [p for p in folder.iterdir() if p.suffix == ".npz"]
    assert len(entries) == 1, entries
    return entries[0]


def _decoding_forbidden(monkeypatch) -> None:
    from bras_kit.meshes import decode

    def refuse(*args, **kwargs):
        raise AssertionError("decoded again although the cache holds the mesh")

    monkeypatch.setattr(decode, "decode", refuse)


def test_a_second_process_reads_the_cache_instead_of_decoding(own_cache, monkeypatch):
    first = meshes.load_mesh(str(PANDA_LINK0))
    assert _entry(own_cache).stat().st_size > first.vertices.nbytes
    _forget(monkeypatch)  # as a new process
    _decoding_forbidden(monkeypatch)
    again = meshes.load_mesh(str(PANDA_LINK0))
    assert np.array_equal(again.vertices, first.vertices) and np.array_equal(again.faces, first.faces)
    assert np.array_equal(again.colors, first.colors, equal_nan=True)


def test_the_cache_key_follows_the_content_and_the_scale_not_the_name(own_cache, tmp_path, monkeypatch):
    meshes.load_mesh(str(_tetrahedron(tmp_path, "a.stl")))
    meshes.load_mesh(str(_tetrahedron(tmp_path, "b.stl")))  # the same bytes under another name
    assert len(list(own_cache.glob("*.npz"))) == 1
    meshes.load_mesh(str(_tetrahedron(tmp_path, "a.stl")), (2.0, 2.0, 2.0))
    meshes.load_mesh(str(_tetrahedron(tmp_path, "c.stl", size=3.0)))
    assert len(list(own_cache.glob("*.npz"))) == 3


@pytest.mark.parametrize("damage", ["cut short", "random bytes", "another key", "indices past the vertices"])
def test_a_damaged_or_foreign_entry_is_ignored_and_written_again(own_cache, monkeypatch, damage):
    good = meshes.load_mesh(str(PANDA_LINK0))
    entry = _entry(own_cache)
    data = entry.read_bytes()
    if damage == "cut short":
        entry.write_bytes(data[: len(data) // 2])
    elif damage == "random bytes":
        entry.write_bytes(os.urandom(4096))
    else:
        with np.load(entry, allow_pickle=False) as archive:
            arrays = {name: archive[name].copy() for name in archive.files}
        if damage == "another key":
            header = bytes(arrays["header"]).decode().replace(entry.stem, "0" * 40)
            arrays["header"] = np.frombuffer(header.encode(), dtype=np.uint8)
        else:
            arrays["faces"][0, 0] = len(arrays["vertices"]) + 5
        with open(entry, "wb") as handle:
            np.savez(handle, **arrays)
    _forget(monkeypatch)
    again = meshes.load_mesh(str(PANDA_LINK0))
    assert np.array_equal(again.faces, good.faces)
    assert again.faces.max() < len(again.vertices)
    _forget(monkeypatch)
    _decoding_forbidden(monkeypatch)  # the entry written again is whole
    assert np.array_equal(meshes.load_mesh(str(PANDA_LINK0)).faces, good.faces)


def test_a_link_in_the_cache_is_never_followed_nor_written_through(own_cache, tmp_path, monkeypatch):
    meshes.load_mesh(str(PANDA_LINK0))
    entry = _entry(own_cache)
    elsewhere = tmp_path / "elsewhere.npz"
    elsewhere.write_bytes(entry.read_bytes())  # a valid entry... behind a link
    entry.unlink()
    entry.symlink_to(elsewhere)
    before = elsewhere.read_bytes()
    _forget(monkeypatch)
    decoded = []
    from bras_kit.meshes import decode

    real = decode.decode
    monkeypatch.setattr(decode, "decode", lambda *a: decoded.append(a) or real(*a))
    meshes.load_mesh(str(PANDA_LINK0))
    assert decoded, "the linked entry was trusted"
    assert not entry.is_symlink() and entry.is_file()  # replaced by an entry of our own
    assert elsewhere.read_bytes() == before  # the link's target untouched


def test_the_cache_drops_the_entries_used_longest_ago_past_its_bound(own_cache, tmp_path, monkeypatch):
    paths = [_tetrahedron(tmp_path, f"t{k}.stl", size=1.0 + k) for k in range(4)]
    meshes.load_mesh(str(paths[0]))
    size = _entry(own_cache).stat().st_size
    monkeypatch.setattr(cache, "MAX_BYTES", int(size * 2.5))  # room for two entries
    for order, path in enumerate(paths[1:], 1):
        for entry in own_cache.glob("*.npz"):  # the entry just written becomes the oldest but one
            if entry.stat().st_mtime > 2_000_000:
                os.utime(entry, (1_000_000 + order, 1_000_000 + order))
        meshes.load_mesh(str(path))
    kept = list(own_cache.glob("*.npz"))
    assert len(kept) == 2
    assert cache.info(str(own_cache)).bytes <= size * 2.5
    _forget(monkeypatch)
    _decoding_forbidden(monkeypatch)
    meshes.load_mesh(str(paths[3]))  # the newest is still there


def test_foreign_files_in_the_cache_folder_are_left_alone_by_the_bound_and_clear(own_cache, tmp_path):
    meshes.load_mesh(str(_tetrahedron(tmp_path)))
    mine = own_cache / "notes.txt"
    mine.write_text("not the cache's")
    info = meshes.cache_info()
    assert info.entries == 1 and info.bytes == _entry(own_cache).stat().st_size
    removed = meshes.clear_cache()
    assert removed.entries == 1
    assert meshes.cache_info().entries == 0
    assert mine.read_text() == "not the cache's"


def test_with_the_disk_cache_off_nothing_is_written(own_cache, tmp_path, monkeypatch):
    monkeypatch.setattr(meshes, "_disk", False)
    meshes.load_mesh(str(_tetrahedron(tmp_path)))
    assert not own_cache.exists() or not list(own_cache.glob("*.npz"))


def test_no_cache_flag_renders_without_touching_the_cache(own_cache, tmp_path, run_cli, monkeypatch):
    monkeypatch.setenv("BRAS_KIT_NO_CACHE", "0")  # the flag sets it for worker processes: undone after
    urdf = tmp_path / "one.urdf"
    stl = _tetrahedron(tmp_path)
    urdf.write_text(f'<robot name="one"><link name="a"><visual><geometry><mesh filename="{stl}"/>'
                    '</geometry></visual></link></robot>')
    code, _, _ = run_cli("render", str(urdf), "-o", str(tmp_path / "a.png"), "--size", "64x48", "--no-cache")
    assert code == 0 and (tmp_path / "a.png").is_file()
    assert not own_cache.exists() or not list(own_cache.glob("*.npz"))
    monkeypatch.setattr(meshes, "_disk", True)
    _forget(monkeypatch)
    code, _, _ = run_cli("render", str(urdf), "-o", str(tmp_path / "b.png"), "--size", "64x48")
    assert code == 0 and len(list(own_cache.glob("*.npz"))) == 1


def test_a_collada_file_in_inches_is_read_in_metres_as_rviz_does():
    """KUKA KR210's link 2 is written in inches (<unit meter="0.0254">) and its URDF gives no
    scale: RViz (assimp) applies the unit. Oracle: the unit and the raw coordinates from the XML."""
    rtb = next(Path(base) / "rtbdata" for base in site.getsitepackages() if (Path(base) / "rtbdata").is_dir())
    path = rtb / "xacro" / "kuka_description" / "kuka_kr210" / "meshes" / "kr210l150" / "visual" / "link_2.dae"
    root = ET.parse(path).getroot()
    unit = float(root.find(".//c:asset/c:unit", COLLADA).get("meter"))
    assert unit == pytest.approx(0.0254)
    mesh = meshes.load_mesh(str(path))
    sources = {source.get("id"): source for source in root.iterfind(".//c:source", COLLADA)}
    raw = []
    for vertices in root.iterfind(".//c:vertices", COLLADA):  # the POSITION input of each mesh
        position = vertices.find("c:input[@semantic='POSITION']", COLLADA)
        array = sources[position.get("source").lstrip("#")].find("c:float_array", COLLADA)
        raw.append(np.array(array.text.split(), dtype=float).reshape(-1, 3))
    assert raw, "the oracle found no positions in the file"
    extent = np.ptp(np.vstack(raw), axis=0).max() * unit  # the file's node matrices are identities
    assert np.ptp(mesh.vertices, axis=0).max() == pytest.approx(extent, rel=1e-3)
    assert 0.5 < np.ptp(mesh.vertices, axis=0).max() < 2.0  # a link of a 2.7 m-reach robot, not 56 m
