"""The robot as coloured triangle meshes fixed to its links, plus the ground grid and TF axes.

Backends receive this description and only move parts by their link's transform, so what
is drawn is decided once, here, from the model (no XML is read again). Vertices are kept in
the link frame with the visual's origin and scale already applied.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..core.errors import ModelError, XacroError
from ..core.message import M
from ..kinematics.frames import TFTree, origin_matrix
from ..model.robot import Robot, Visual
from ._memo import BoundedMemo

DEFAULT_COLOR = (0.7, 0.7, 0.7, 1.0)  # a visual with no material, as RViz shows it
GRID_COLOR = (0.78, 0.78, 0.78)
AXIS_COLORS = ((1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0))  # x y z
CYLINDER_SECTIONS = 32


@dataclass
class Part:
    """One coloured mesh moving with link ``tree.links[link]``; ``unlit`` ones keep their pure colour."""

    link: int
    vertices: np.ndarray  # (V, 3) in the link frame
    faces: np.ndarray  # (F, 3) vertex indices, counter-clockwise seen from outside
    color: tuple[float, float, float, float]  # sRGB, 0..1
    unlit: bool = False
    label: str = ""
    bounds: np.ndarray | None = field(default=None, repr=False, compare=False)  # (2, 3) low, high of vertices


@dataclass
class Grid:
    """Ground lines in the world frame: ``segments`` has shape (S, 2, 3)."""

    segments: np.ndarray
    color: tuple[float, float, float] = GRID_COLOR


@dataclass
class Scene:
    tree: TFTree
    parts: list[Part]
    grid: Grid | None


def resolve_mesh_path(filename: str, robot: Robot, package_paths: Sequence[str] = (),
                      line: int | None = None) -> str:
    """The file a mesh ``filename`` names: ``package://pkg/...``, ``file://...``, or relative to the URDF."""
    return mesh_source(filename, robot, package_paths, line)[0]


def mesh_source(filename: str, robot: Robot, package_paths: Sequence[str] = (),
                line: int | None = None) -> tuple[str, tuple[str, ...] | None]:
    """The file a mesh ``filename`` names (see :func:`resolve_mesh_path`) and the folders it is
    read beneath: for a learner's robot (``robot.roots``), its own folders and the package
    ``package://`` names, through the one reader (a link out of them, a pipe, a device: refused,
    and the mesh drawn as a stand-in); None for the user's own file (any regular file)."""
    from ..model.package_paths import find_package, package_roots

    roots = robot.roots
    if filename.startswith("package://"):
        package, _, rest = filename[len("package://"):].partition("/")
        searched = list(package_paths)
        if robot.path and os.path.exists(robot.path):
            # a URDF inside its package (pkg/urdf/x.urdf) finds its own meshes
            searched.append(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(robot.path)))))
        try:
            folder = find_package(package, package_roots(searched))
        except XacroError:
            raise ModelError(M("mesh '{file}': package '{package}' not found", file=filename, package=package),
                             path=robot.path, line=line, element="mesh",
                             hint=M("pass --package-path DIR, a folder holding {package}/ (with its package.xml)",
                                    package=package)) from None
        path = os.path.join(folder, rest)
        if roots is not None and folder not in roots:
            roots = (*roots, folder)
    elif filename.startswith("file://"):
        path = filename[len("file://"):]
    else:
        base = os.path.dirname(os.path.abspath(robot.path)) if robot.path and os.path.exists(robot.path) else os.getcwd()
        path = os.path.join(base, filename)
    path = os.path.abspath(path)
    if roots is not None:
        from ..trust.beneath import Outside, open_any_beneath
        from ..trust.learner_files import refusal

        try:
            os.close(open_any_beneath(roots, path)[0])
        except Outside as exc:
            if exc.kind != "missing":
                raise ModelError(M("refused to read mesh {path}: {reason}", path=path, reason=refusal(exc.kind)),
                                 path=robot.path, line=line, element="mesh",
                                 hint=M("keep the meshes inside the robot's package")) from None
    if not os.path.isfile(path):
        raise ModelError(M("mesh file not found: {path}", path=path), path=robot.path, line=line, element="mesh",
                         hint=M("check the filename, or pass --package-path for package:// names"))
    if os.path.getsize(path) > MAX_MESH_BYTES:
        raise ModelError(M("mesh file {path} is larger than {most} MiB", path=path, most=MAX_MESH_BYTES >> 20),
                         path=robot.path, line=line, element="mesh", hint=M("simplify the mesh (fewer triangles)"))
    return path, roots


class TriangleMesh(NamedTuple):
    """Triangles in a link frame: ``vertices`` (V, 3) float, ``faces`` (F, 3) int, counter-clockwise
    seen from outside (what :func:`visual_mesh` returns; trimesh is loaded only for mesh files)."""

    vertices: np.ndarray
    faces: np.ndarray

    def transformed(self, matrix: np.ndarray) -> TriangleMesh:
        return TriangleMesh(self.vertices @ matrix[:3, :3].T + matrix[:3, 3], self.faces)


def box_mesh(extents: Sequence[float]) -> TriangleMesh:
    """A box centred on the origin: 8 corners, 12 outward triangles."""
    half = np.abs(np.asarray(extents, dtype=float)) / 2.0
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float) * half
    # corner index = 4*x + 2*y + z (0 for -, 1 for +); two triangles per side, outward
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5],   # -x, +x
                      [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],   # -y, +y
                      [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]],  # -z, +z
                     dtype=np.int64)
    return TriangleMesh(corners, faces)


def cylinder_mesh(radius: float, length: float, sections: int = CYLINDER_SECTIONS) -> TriangleMesh:
    """A closed cylinder along z, centred on the origin: a ring of sides and two fans."""
    angles = np.linspace(0.0, 2.0 * math.pi, sections, endpoint=False)
    ring = np.column_stack([radius * np.cos(angles), radius * np.sin(angles)])
    half = length / 2.0
    vertices = np.vstack([np.column_stack([ring, np.full(sections, -half)]),
                          np.column_stack([ring, np.full(sections, half)]),
                          [[0.0, 0.0, -half], [0.0, 0.0, half]]])
    i = np.arange(sections)
    j = (i + 1) % sections
    bottom, top = 2 * sections, 2 * sections + 1
    faces = np.vstack([np.column_stack([i, j, j + sections]), np.column_stack([i, j + sections, i + sections]),
                       np.column_stack([np.full(sections, bottom), j, i]),
                       np.column_stack([np.full(sections, top), i + sections, j + sections])])
    return TriangleMesh(vertices, faces.astype(np.int64))


def sphere_mesh(radius: float, subdivisions: int = 2) -> TriangleMesh:
    """An icosphere: the icosahedron with each triangle split in four ``subdivisions`` times."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [np.array(v, dtype=float) for v in (
        (-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
        (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1))]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    def middle(a: int, b: int, middles: dict[tuple[int, int], int]) -> int:
        key = (min(a, b), max(a, b))
        if key not in middles:
            middles[key] = len(vertices)
            vertices.append((vertices[a] + vertices[b]) / 2.0)
        return middles[key]

    for _ in range(subdivisions):
        middles: dict[tuple[int, int], int] = {}
        split = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b, middles), middle(b, c, middles), middle(c, a, middles)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    points = np.array(vertices)
    points *= radius / np.linalg.norm(points, axis=1, keepdims=True)
    return TriangleMesh(points, np.array(faces, dtype=np.int64))


def rod_mesh(radius: float, end: np.ndarray, sections: int = 12) -> TriangleMesh:
    """A cylinder from the origin to ``end``."""
    length = float(np.linalg.norm(end))
    rod = cylinder_mesh(radius, length, sections)
    axis = np.asarray(end, dtype=float) / length
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, axis)
    x /= np.linalg.norm(x)
    matrix = np.eye(4)
    matrix[:3, :3] = np.column_stack([x, np.cross(axis, x), axis])
    matrix[:3, 3] = axis * length / 2.0
    return rod.transformed(matrix)


def mesh_file_data(path: str, robot: Robot, line: int | None = None, scale: Sequence[float] | None = None,
                   roots: tuple[str, ...] | None = None):
    """The decoded triangles and materials of a mesh file (:func:`bras_kit.meshes.load_mesh`:
    decoded once, then from the cache), as a :class:`bras_kit.meshes.MeshData`; ``roots`` as
    :func:`mesh_source` gives them."""
    from ..meshes import DecodeError, load_mesh

    try:
        return load_mesh(path, scale, roots)
    except DecodeError as exc:
        if exc.reason == "no triangles":
            raise ModelError(M("mesh {path} holds no triangles", path=path), path=robot.path, line=line,
                             element="mesh", hint=M("export the mesh as triangles (STL, OBJ or DAE)")) from None
        raise ModelError(M("cannot read mesh {path}: {reason}", path=path, reason=exc.reason), path=robot.path,
                         line=line, element="mesh", hint=M("give an STL, OBJ or DAE file")) from None


def _primitive_mesh(g) -> TriangleMesh | None:
    if g.kind == "box" and g.size is not None:
        return box_mesh(g.size)
    if g.kind == "cylinder" and g.radius and g.length:
        return cylinder_mesh(abs(g.radius), abs(g.length))
    if g.kind == "sphere" and g.radius:
        return sphere_mesh(abs(g.radius))
    return None


class PlacedPiece(NamedTuple):
    """One material's triangles of a visual, in the link frame: read-only arrays, and the
    (2, 3) low and high corners of its vertices."""

    mesh: TriangleMesh
    color: tuple[float, float, float, float] | None
    bounds: np.ndarray


PLACED_MEMORY_BYTES = 128 << 20  # placed mesh pieces kept in this process (a class of the same robot)
_placed = BoundedMemo(PLACED_MEMORY_BYTES)  # (id of MeshData, xyz, rpy) -> (that MeshData, its pieces)


def _placed_visual(robot: Robot, visual: Visual, package_paths: Sequence[str] = ()):
    """The visual's shape in the link frame as :class:`PlacedPiece` s, and the mesh file's issues
    (what it names but could not be used); ``([], ())`` when it has no usable shape. A mesh file's
    pieces placed at one origin are computed once per process: :func:`bras_kit.meshes.load_mesh` gives the same decoded
    object for the same bytes and scale (whatever the path), so a class of learners handing in
    the same meshes at the same origins share them. Primitives are built each time (cheap)."""
    g = visual.geometry
    if g is None:
        return [], ()
    placed = origin_matrix(visual.origin.xyz, visual.origin.rpy)
    if not (g.kind == "mesh" and g.filename):
        mesh = _primitive_mesh(g)
        return ([] if mesh is None else [_piece(mesh.transformed(placed), None)]), ()
    path, roots = mesh_source(g.filename, robot, package_paths, g.line)
    data = mesh_file_data(path, robot, g.line, g.scale, roots)
    key = (id(data), tuple(float(v) for v in visual.origin.xyz), tuple(float(v) for v in visual.origin.rpy))
    kept = _placed.get(key)
    if kept is not None and kept[0] is data:  # the entry holds ``data``: its id cannot have been reused
        return kept[1], data.issues
    pieces = [_piece(TriangleMesh(np.asarray(p.vertices, dtype=float), np.asarray(p.faces, dtype=np.int64))
                     .transformed(placed), p.color) for p in data.pieces()]
    _placed.put(key, (data, pieces), sum(p.mesh.vertices.nbytes + p.mesh.faces.nbytes for p in pieces))
    return pieces, data.issues


def _piece(mesh: TriangleMesh, color: tuple[float, float, float, float] | None) -> PlacedPiece:
    vertices = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    for array in (vertices, faces):
        array.flags.writeable = False  # shared between scenes: nobody may change them in place
    bounds = _bounds(vertices) if len(vertices) else np.zeros((2, 3))
    bounds.flags.writeable = False
    return PlacedPiece(TriangleMesh(vertices, faces), color, bounds)


def visual_mesh(robot: Robot, visual: Visual, package_paths: Sequence[str] = ()) -> TriangleMesh | None:
    """The visual's shape as a :class:`TriangleMesh` in the link frame, or None when it has no usable shape."""
    g = visual.geometry
    if g is None:
        return None
    if g.kind == "mesh" and g.filename:
        path, roots = mesh_source(g.filename, robot, package_paths, g.line)
        data = mesh_file_data(path, robot, g.line, g.scale, roots)
        mesh = TriangleMesh(np.asarray(data.vertices, dtype=float), np.asarray(data.faces, dtype=np.int64))
    else:
        mesh = _primitive_mesh(g)  # type: ignore[assignment]
        if mesh is None:
            return None
    return mesh.transformed(origin_matrix(visual.origin.xyz, visual.origin.rpy))


PLACEHOLDER_COLOR = (0.9, 0.05, 0.05, 1.0)
PLACEHOLDER_SIDE = 0.05  # metres: the stand-in of a mesh with no collision shape either
MAX_MESH_BYTES = 256 << 20


def placeholder_mesh(robot: Robot, link, visual: Visual) -> TriangleMesh:
    """What stands for a mesh that cannot be read: the link's first primitive collision shape,
    else a small cube at the visual's origin."""
    for collision in link.collisions:
        g = collision.geometry
        if g is not None and g.kind in ("box", "cylinder", "sphere"):
            mesh = visual_mesh(robot, Visual(collision.origin, g))
            if mesh is not None:
                return mesh
    return box_mesh([PLACEHOLDER_SIDE] * 3).transformed(origin_matrix(visual.origin.xyz, visual.origin.rpy))


def robot_parts(tree: TFTree, package_paths: Sequence[str] = (), lang: str | None = None) -> list[Part]:
    """A :class:`Part` per drawable piece of every link's visuals. Colours follow RViz: a mesh's
    own materials win; the URDF ``<material>`` colours primitives, meshes with no material (STL)
    and the pieces of a mesh without one; grey when neither says. What a mesh file names but
    cannot be used (a missing texture) is said once per file, and the rest drawn."""
    from ..core.i18n import say

    robot = tree.robot
    parts = []
    warned: set[str | None] = set()
    for index, name in enumerate(tree.links):
        link = robot.link(name)
        if link is None:
            continue
        for number, visual in enumerate(link.visuals, 1):
            color = robot.material_rgba(visual) or DEFAULT_COLOR
            try:
                pieces, issues = _placed_visual(robot, visual, package_paths)
            except ModelError as exc:  # draw what can be drawn: a red stand-in, one warning per file
                pieces, issues = [_piece(placeholder_mesh(robot, link, visual), PLACEHOLDER_COLOR)], ()
                if str(exc.message) not in warned:
                    warned.add(str(exc.message))
                    print(f"{say(M('warning'), lang)}: " + say(M("{problem}; drawn as a red stand-in (link '{link}')",
                                                                 problem=exc.message, link=name), lang), file=sys.stderr)
            filename = visual.geometry.filename if visual.geometry is not None else None
            if issues and filename not in warned:
                warned.add(str(filename))
                print(f"{say(M('warning'), lang)}: " + say(M(
                    "mesh {file} names what it does not hold ({details}); the rest of it is drawn",
                    file=filename, details=sorted({i.detail for i in issues})), lang), file=sys.stderr)
            for piece in pieces:
                rgba = piece.color if piece.color is not None else color
                rgba = tuple(float(c) for c in rgba)
                parts.append(Part(index, piece.mesh.vertices, piece.mesh.faces, rgba,
                                  label=f"{name} visual {number}", bounds=piece.bounds))
    return parts


COLLISION_COLOR = (0.35, 0.63, 0.35, 1.0)  # green-grey, as the viewer draws collision shapes


def collision_parts(tree: TFTree, package_paths: Sequence[str] = (), opacity: float = 1.0) -> list[Part]:
    """A :class:`Part` per drawable ``<collision>`` of every link (RViz's "Collision Enabled"),
    in one colour; an unreadable collision mesh is drawn as the visuals' red stand-in."""
    robot = tree.robot
    parts = []
    for index, name in enumerate(tree.links):
        link = robot.link(name)
        for number, collision in enumerate(link.collisions if link is not None else [], 1):
            shape = Visual(collision.origin, collision.geometry)
            color = (*COLLISION_COLOR[:3], opacity)
            try:
                mesh = visual_mesh(robot, shape, package_paths)
            except ModelError:
                mesh, color = placeholder_mesh(robot, link, shape), PLACEHOLDER_COLOR
            if mesh is None:
                continue
            parts.append(Part(index, np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64),
                              color, label=f"{name} collision {number}"))
    return parts


def triad_parts(tree: TFTree, length: float) -> list[Part]:
    """Red, green and blue rods along each link's x, y and z axes (RViz's TF display). Every
    link's triad shares the same read-only arrays, kept for the next scene with this length."""
    rods = _triad(float(length))
    return [Part(i, v, f, c, unlit=True, label=f"{name} axes", bounds=b)
            for i, name in enumerate(tree.links) for v, f, c, b in rods]


TRIADS_KEPT = 16
_triads: dict[float, list[tuple[np.ndarray, np.ndarray, tuple[float, float, float, float], np.ndarray]]] = {}


def _triad(length: float) -> list[tuple[np.ndarray, np.ndarray, tuple[float, float, float, float], np.ndarray]]:
    rods = _triads.get(length)
    if rods is None:
        radius = length / 22.0
        rods = []
        for axis, color in zip(np.eye(3), AXIS_COLORS):
            piece = _piece(rod_mesh(radius, axis * length), color)
            rods.append((piece.mesh.vertices, piece.mesh.faces, color, piece.bounds))
        if len(_triads) >= TRIADS_KEPT:
            _triads.clear()
        _triads[length] = rods
    return rods


def part_corners(parts: Sequence[Part]) -> np.ndarray:
    """The 8 corners of each part's box in its link frame: shape (P, 8, 3)."""
    if not parts:
        return np.zeros((0, 8, 3))
    bounds = np.stack([p.bounds if p.bounds is not None else _bounds(p.vertices) for p in parts])  # (P, 2, 3)
    pick = np.array([[i, j, m] for i in (0, 1) for j in (0, 1) for m in (0, 1)])  # (8, 3): low or high per axis
    return np.ascontiguousarray(bounds[:, pick, np.arange(3)])  # einsum sums a C-ordered array as before


def _bounds(vertices: np.ndarray) -> np.ndarray:
    return np.stack([vertices.min(axis=0), vertices.max(axis=0)])


def world_points(parts: Sequence[Part], transforms: np.ndarray, corners: np.ndarray | None = None) -> np.ndarray:
    """Corners of every part over every pose (``transforms``: (N, L, 4, 4)) in the world: (M, 3).
    ``corners``: the parts' :func:`part_corners`, when already known."""
    if not parts:
        return np.zeros((1, 3))
    if corners is None:
        corners = part_corners(parts)  # (P, 8, 3)
    links = np.array([p.link for p in parts])
    chosen = transforms[:, links]  # (N, P, 4, 4)
    rot, pos = chosen[..., :3, :3], chosen[..., :3, 3]
    points = np.einsum("npij,pkj->npki", rot, corners) + pos[:, :, None, :]
    return points.reshape(-1, 3)


def floor_height(parts: Sequence[Part], transforms: np.ndarray, corners: np.ndarray | None = None) -> float:
    """Where the ground is: the bottom of what never moves (the base), else z = 0 or below the lowest point."""
    if corners is None:
        corners = part_corners(parts)
    links = np.array([p.link for p in parts], dtype=np.int64)
    still = np.isclose(transforms, transforms[:1], rtol=1e-5, atol=1e-9).all(axis=(0, 2, 3))  # per link, as allclose
    static = still[links] if len(links) else np.zeros(0, dtype=bool)
    if static.any():
        chosen = [p for p, keep in zip(parts, static) if keep]
        return float(world_points(chosen, transforms[:1], corners[static])[:, 2].min())
    return min(0.0, float(world_points(parts, transforms, corners)[:, 2].min()))


def _nice_step(span: float) -> float:
    """1, 2 or 5 times a power of ten, close to ``span``."""
    exponent = math.floor(math.log10(span))
    for factor in (1.0, 2.0, 5.0, 10.0):
        if factor * 10 ** exponent >= span:
            return factor * 10 ** exponent
    return 10.0 ** (exponent + 1)  # pragma: no cover - the loop always returns


def ground_grid(points: np.ndarray, floor: float) -> Grid:
    """A square grid centred on the world origin, wide enough for every point's footprint."""
    reach = float(np.abs(points[:, :2]).max()) if len(points) else 0.0
    reach = max(reach * 1.25, 0.1)
    step = _nice_step(reach / 5.0)
    half = math.ceil(reach / step) * step
    ticks = np.arange(-half, half + step / 2, step)
    segments = []
    for v in ticks:
        segments.append([(v, -half, floor), (v, half, floor)])
        segments.append([(-half, v, floor), (half, v, floor)])
    return Grid(np.asarray(segments, dtype=float))


TARGET_COLOR = (0.85, 0.1, 0.55, 1.0)  # magenta: no segment, axis or grid has it


def target_parts(targets: Sequence[Sequence[float]], size: float) -> list[Part]:
    """A small magenta ball at each world point (the root link's frame is the world)."""
    ball = sphere_mesh(size)
    return [Part(0, ball.vertices + np.asarray(point, dtype=float)[:3], ball.faces, TARGET_COLOR, unlit=True,
                 label="target") for point in targets]


def build_scene(tree: TFTree, fit_transforms: np.ndarray, *, tf: bool = False, grid: bool = True,
                package_paths: Sequence[str] = (), targets: Sequence[Sequence[float]] = (),
                geometry: str = "visual") -> tuple[Scene, np.ndarray]:
    """The scene and the world points the camera must keep in view (every part over ``fit_transforms``).
    ``geometry``: draw the links' visuals, their collision shapes, or both (collisions see-through)."""
    parts = robot_parts(tree, package_paths) if geometry != "collision" else []
    if geometry != "visual":
        parts = parts + collision_parts(tree, package_paths, 0.5 if geometry == "both" else 1.0)
    corners = part_corners(parts)
    points = world_points(parts, fit_transforms, corners)
    if len(targets):
        extent = float(np.ptp(points, axis=0).max()) if len(parts) else 0.5
        extra = target_parts(targets, max(0.025 * extent, 0.01))
        parts, corners = parts + extra, np.concatenate([corners, part_corners(extra)])
        points = world_points(parts, fit_transforms, corners)
    if tf:
        extent = float(np.ptp(points, axis=0).max()) if len(parts) else 0.0
        extra = triad_parts(tree, max(0.18 * extent, 0.05))
        parts, corners = parts + extra, np.concatenate([corners, part_corners(extra)])
        points = world_points(parts, fit_transforms, corners)
    ground = None
    if grid:
        ground = ground_grid(points, floor_height(parts, fit_transforms, corners) if parts else 0.0)
    return Scene(tree, parts, ground), points
