"""Mesh files turned into triangles with their own colours: COLLADA through pycollada (walking the
scene ourselves, so a broken reference costs only what it names), every other format through
trimesh. Heavy libraries are imported here only, when a file is really decoded."""

from __future__ import annotations

import io
import os
from collections.abc import Callable, Iterator, Sequence
from typing import Any, cast

import numpy as np

from .mesh import Issue, MeshData, Piece

TEXTURE_SAMPLES = 4096  # texture colours looked up per piece to find its mean colour
MAX_FACE_COLOURS = 64  # a file colouring its faces with more colours is drawn in their mean colour
MAX_AUX_BYTES = 64 << 20  # a texture or a material file a mesh names


class DecodeError(Exception):
    """A mesh file that cannot be read as triangles; ``reason`` says why, in English for the log."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


def decode(path: str, scale: Sequence[float] | None, data: bytes,
           roots: tuple[str, ...] | None = None) -> MeshData:
    """The triangles of the file at ``path`` (STL, OBJ, DAE, PLY, GLB...), scaled by ``scale``,
    each piece with the colour its file gives (None: no material of its own). ``data``: the
    file's bytes, read once by :func:`bras_kit.meshes.read_mesh_file` (never read again by path); ``roots``: the
    folders the files it names (an OBJ's .mtl, textures) are read beneath, by the one reader."""
    if path.lower().endswith(".dae"):
        pieces, issues = _collada(path, data, roots)
    else:
        pieces, issues = _trimesh(path, data, roots)
    pieces = [p for p in pieces if len(p.faces)]
    if not pieces:
        raise DecodeError("no triangles")
    if scale is not None:
        factors = np.asarray(scale, dtype=np.float64)
        mirrored = bool(np.prod(factors) < 0)  # a mirror turns the triangles inside out: wind them back
        pieces = [Piece((p.vertices * factors).astype(np.float32), p.faces[:, ::-1].copy() if mirrored else p.faces,
                        p.color) for p in pieces]
    return MeshData.join(pieces, issues)


# --- COLLADA -----------------------------------------------------------------------------------


def _aux_reader(path: str, roots: tuple[str, ...] | None) -> Callable[[str], bytes]:
    """A file the mesh names (a texture, a material file), relative to the mesh's folder: through
    the one reader beneath ``roots``, or any regular file of the user's own robot (``roots`` None)."""
    from ..trust.learner_files import read_bytes

    folder = os.path.dirname(os.path.abspath(path))

    def read(name: str) -> bytes:
        full = os.path.normpath(os.path.join(folder, name.strip()))
        return read_bytes(full, roots if roots is not None else ("/",), limit=MAX_AUX_BYTES)
    return read


def _collada(path: str, data: bytes, roots: tuple[str, ...] | None = None) -> tuple[list[Piece], list[Issue]]:
    import collada
    from collada import common

    try:
        document = collada.Collada(io.BytesIO(data), ignore=[common.DaeBrokenRefError, common.DaeUnsupportedError,
                                                             common.DaeIncompleteError],
                                   aux_file_loader=_aux_reader(path, roots))
    except Exception as exc:  # noqa: BLE001 - pycollada and lxml raise many kinds for a bad file
        raise DecodeError(f"{type(exc).__name__}: {exc}".rstrip(": ")) from None
    issues = [Issue("broken-reference", str(getattr(error, "msg", "") or error)) for error in document.errors
              if isinstance(error, common.DaeBrokenRefError)]
    unit = float(document.assetInfo.unitmeter or 1.0) if document.assetInfo is not None else 1.0
    root = np.eye(4) * np.array([unit, unit, unit, 1.0])
    pieces: list[Piece] = []
    scene = document.scene
    if scene is not None:
        for node in scene.nodes:
            pieces += _collada_node(document, node, root, path, 0)
    if not pieces:  # no scene, or one that instances nothing we read (a skin): the geometries as they are
        for geometry in document.geometries:
            pieces += _collada_geometry(document, geometry, root, {}, path)
    return pieces, issues


def _collada_node(document: Any, node: Any, parent: np.ndarray, path: str, depth: int) -> list[Piece]:
    """The pieces under one scene node. Its ``instance_geometry`` elements are read from the
    XML (not from pycollada's bound objects), so a geometry whose material is missing is kept."""
    from collada import common, scene

    if depth > 64:  # a node instancing itself
        return []
    matrix = parent @ np.asarray(getattr(node, "matrix", np.eye(4)), dtype=np.float64)
    pieces: list[Piece] = []
    xml = getattr(node, "xmlnode", None)
    if xml is not None:
        for instance in xml.findall(common.tag("instance_geometry")):
            geometry = _by_url(document.geometries, instance.get("url"))
            if geometry is None:
                continue
            symbols = {bound.get("symbol"): (bound.get("target") or "").lstrip("#")
                       for bound in instance.iter(common.tag("instance_material"))}
            pieces += _collada_geometry(document, geometry, matrix, symbols, path)
    for child in getattr(node, "children", []):
        if isinstance(child, scene.Node):
            pieces += _collada_node(document, child, matrix, path, depth + 1)
        elif isinstance(child, scene.NodeNode) and child.node is not None:
            pieces += _collada_node(document, child.node, matrix, path, depth + 1)
    return pieces


def _by_url(items: Any, url: str | None) -> Any:
    if not url or not url.startswith("#"):
        return None
    try:
        return items.get(url[1:])
    except Exception:  # noqa: BLE001
        return None


def _collada_geometry(document: Any, geometry: Any, matrix: np.ndarray, symbols: dict[str | None, str],
                      path: str) -> list[Piece]:
    from collada import lineset, polygons, polylist, triangleset

    pieces = []
    for primitive in geometry.primitives:
        if isinstance(primitive, (polylist.Polylist, polygons.Polygons)):
            primitive = primitive.triangleset()
        if not isinstance(primitive, triangleset.TriangleSet) or isinstance(primitive, lineset.LineSet):
            continue
        if primitive.vertex is None or primitive.vertex_index is None or not len(primitive.vertex_index):
            continue
        points = np.asarray(primitive.vertex, dtype=np.float64).reshape(-1, 3)
        faces = np.asarray(primitive.vertex_index, dtype=np.int64).reshape(-1, 3)
        if faces.min() < 0 or faces.max() >= len(points):
            continue  # indices past the vertices: a malformed primitive, left out
        points = points @ matrix[:3, :3].T + matrix[:3, 3]
        if np.linalg.det(matrix[:3, :3]) < 0:
            faces = faces[:, ::-1]
        material = _by_url(document.materials, "#" + symbols.get(primitive.material, primitive.material or ""))
        color = _collada_color(material, primitive, path)
        used, faces = np.unique(faces, return_inverse=True)
        pieces.append(Piece(points[used].astype(np.float32), faces.reshape(-1, 3).astype(np.int32), color))
    return pieces


def _collada_color(material: Any, primitive: Any, path: str) -> tuple[float, float, float, float] | None:
    """The diffuse colour of a COLLADA material; a texture gives the mean colour of the texels the
    triangles use; None when there is no material or its texture cannot be read."""
    effect = getattr(material, "effect", None)
    diffuse = getattr(effect, "diffuse", None)
    if isinstance(diffuse, tuple) and len(diffuse) >= 3:
        rgba = [float(c) for c in diffuse[:4]] + [1.0] * (4 - len(diffuse[:4]))
        return tuple(float(np.clip(c, 0.0, 1.0)) for c in rgba)  # type: ignore[return-value]
    if diffuse is not None and hasattr(diffuse, "sampler"):
        try:
            image = diffuse.sampler.surface.image.pilimage
        except Exception:  # noqa: BLE001 - a missing or unreadable image: no colour of its own
            image = None
        if image is None:
            return None
        uv = None
        if getattr(primitive, "texcoordset", None) and getattr(primitive, "texcoord_indexset", None):
            uv = np.asarray(primitive.texcoordset[0])[np.asarray(primitive.texcoord_indexset[0]).reshape(-1)]
        return _texture_mean(image, uv)
    return None


def _texture_mean(image: Any, uv: np.ndarray | None) -> tuple[float, float, float, float]:
    """The mean colour (sRGB, 0..1) of ``image`` at texture coordinates ``uv`` (all of it without)."""
    pixels = np.asarray(image.convert("RGB"), dtype=np.float64) / 255.0
    if uv is None or not len(uv):
        rgb = pixels.reshape(-1, 3).mean(axis=0)
    else:
        picks = uv[np.linspace(0, len(uv) - 1, min(len(uv), TEXTURE_SAMPLES)).astype(int)] % 1.0
        height, width = pixels.shape[:2]
        columns = np.minimum((picks[:, 0] * width).astype(int), width - 1)
        rows = np.minimum(((1.0 - picks[:, 1]) * height).astype(int), height - 1)
        rgb = pixels[rows, columns].mean(axis=0)
    return (float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0)


# --- trimesh (STL, OBJ, PLY, GLB...) ------------------------------------------------------------


class _BeneathResolver:
    """trimesh's resolver (``get``: the bytes of a file a mesh names) reading through the one
    reader, relative to the mesh's folder: never a link out of ``roots``, never a pipe."""

    def __init__(self, path: str, roots: tuple[str, ...] | None) -> None:
        self.path, self.roots = path, roots
        self._read = _aux_reader(path, roots)

    def get(self, name: str) -> bytes:
        from ..trust.beneath import Outside

        try:
            return self._read(name)
        except Outside:
            raise FileNotFoundError(name) from None

    def __getitem__(self, name: str) -> bytes:
        return self.get(name)

    def namespaced(self, namespace: str) -> _BeneathResolver:
        return _BeneathResolver(os.path.join(os.path.dirname(self.path), namespace, "_"), self.roots)

    def keys(self) -> list[str]:
        return []


def _trimesh(path: str, data: bytes, roots: tuple[str, ...] | None = None) -> tuple[list[Piece], list[Issue]]:
    import trimesh

    try:
        loaded = trimesh.load(io.BytesIO(data), file_type=os.path.splitext(path)[1].lstrip(".").lower(),
                              resolver=cast(Any, _BeneathResolver(path, roots)))  # duck-typed: get, namespaced
    except Exception as exc:  # noqa: BLE001 - trimesh raises many kinds for a bad file
        raise DecodeError(f"{type(exc).__name__}: {exc}".rstrip(": ")) from None
    meshes = loaded.dump() if isinstance(loaded, trimesh.Scene) else [loaded]
    pieces: list[Piece] = []
    for mesh in meshes:
        if not isinstance(mesh, trimesh.Trimesh) or not len(mesh.faces):
            continue
        pieces += list(_trimesh_pieces(mesh))
    return pieces, []


def _trimesh_pieces(mesh: Any) -> Iterator[Piece]:
    vertices = np.asarray(mesh.vertices, dtype=np.float32)
    faces = np.asarray(mesh.faces, dtype=np.int32)
    visual = mesh.visual
    kind = getattr(visual, "kind", None)
    if kind == "texture":
        material = getattr(visual, "material", None)
        image = getattr(material, "image", None) or getattr(material, "baseColorTexture", None)
        if image is not None and getattr(visual, "uv", None) is not None and len(visual.uv):
            yield Piece(vertices, faces, _texture_mean(image, np.asarray(visual.uv)[faces.reshape(-1)]))
            return
        color = _material_color(material)
        yield Piece(vertices, faces, color)
        return
    if kind in ("face", "vertex"):
        if kind == "face":
            colours = np.asarray(visual.face_colors, dtype=np.float64)[:, :4] / 255.0
        else:
            colours = (np.asarray(visual.vertex_colors, dtype=np.float64)[:, :4] / 255.0)[faces].mean(axis=1)
        unique, groups = np.unique(np.round(colours, 3), axis=0, return_inverse=True)
        groups = groups.reshape(-1)
        if len(unique) > MAX_FACE_COLOURS:
            yield Piece(vertices, faces, tuple(float(c) for c in colours.mean(axis=0)))  # type: ignore[arg-type]
            return
        for number, colour in enumerate(unique):
            chosen = faces[groups == number]
            used, inverse = np.unique(chosen, return_inverse=True)
            yield Piece(vertices[used], inverse.reshape(-1, 3).astype(np.int32),
                        tuple(float(c) for c in colour))  # type: ignore[arg-type]
        return
    yield Piece(vertices, faces, None)


def _material_color(material: Any) -> tuple[float, float, float, float] | None:
    """A trimesh material's own colour: a PBR base colour or a simple diffuse one, else None."""
    if material is None:
        return None
    for name in ("baseColorFactor", "diffuse"):
        value = getattr(material, name, None)
        if value is not None:
            rgba = np.asarray(value, dtype=np.float64).reshape(-1)[:4]
            if rgba.max(initial=0.0) > 1.0:
                rgba = rgba / 255.0
            if len(rgba) == 3:
                rgba = np.append(rgba, 1.0)
            return tuple(float(c) for c in np.clip(rgba, 0.0, 1.0))  # type: ignore[return-value]
    return None


