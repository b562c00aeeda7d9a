"""BK4xx: shapes, mesh files and colours.

Mesh paths are resolved the way ROS tools do, without fetching anything: ``package://pkg/...``
through the package folders (``--package-path``, ``BRAS_KIT_PACKAGE_PATH``, ROS variables),
``file://`` and plain paths relative to the checked file. Other URLs are never downloaded.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator

from ..core.errors import BrasKitError
from ..findings.registry import ERROR, WARNING, Hit, hit, rule
from ..model.package_paths import find_package, package_roots
from ..model.robot import Collision, Geometry, Link, Visual
from .context import Context
from .solids import number

PACKAGE_SCHEME = "package://"
FILE_SCHEME = "file://"


def _shapes(link: Link) -> Iterator[Visual | Collision]:
    yield from link.visuals
    yield from link.collisions


def _kind(element: Visual | Collision) -> str:
    return "visual" if isinstance(element, Visual) else "collision"


@rule("BK400", "geometry-missing", ERROR)
def geometry_missing(ctx: Context) -> Iterator[Hit]:
    for link in ctx.robot.links:
        for element in _shapes(link):
            if element.geometry is None:
                yield hit("link", link.name, element.line, "absent", link=link.name, tag=_kind(element))
    for issue in ctx.issues("unknown_geometry"):
        owner, name = ctx.owner(issue)
        yield hit(owner, name, issue.line, "unknown" if issue.value else "empty", link=name,
                  tag=issue.value)


def _bad_sizes(geometry: Geometry) -> Iterator[tuple[str, object]]:
    def bad(values: tuple[float, ...] | None) -> bool:
        return values is not None and any(math.isfinite(v) and v <= 0 for v in values)

    if geometry.kind == "box" and bad(geometry.size):
        yield "size", geometry.size
    elif geometry.kind in ("cylinder", "sphere"):
        for attribute in ("radius", "length") if geometry.kind == "cylinder" else ("radius",):
            value = getattr(geometry, attribute)
            if value is not None and bad((value,)):
                yield attribute, value
    elif geometry.kind == "mesh" and geometry.scale is not None and any(v == 0 for v in geometry.scale):
        yield "scale", geometry.scale


@rule("BK401", "size-not-positive", ERROR)
def size_not_positive(ctx: Context) -> Iterator[Hit]:
    for link in ctx.robot.links:
        for element in _shapes(link):
            geometry = element.geometry
            if geometry is None:
                continue
            for attribute, value in _bad_sizes(geometry):
                variant = "scale" if attribute == "scale" else ""
                yield hit("link", link.name, geometry.line or element.line, variant, link=link.name,
                          tag=geometry.kind, attribute=attribute, value=value, where=_kind(element))


class MeshResolver:
    """Turns mesh URIs into local paths, remembering packages and files already looked up."""

    def __init__(self, folder: str | None, package_paths: tuple[str, ...] | list[str]) -> None:
        self.folder = folder
        self.roots = package_roots(package_paths)
        self.packages: dict[str, str | None] = {}
        self.results: dict[str, tuple[str, str]] = {}

    def resolve(self, uri: str) -> tuple[str, str]:
        """("ok" or "missing", local path), ("no-package", package name) or ("remote", URL)."""
        if uri not in self.results:
            self.results[uri] = self._resolve(uri)
        return self.results[uri]

    def _package(self, name: str) -> str | None:
        if name not in self.packages:
            try:
                self.packages[name] = find_package(name, self.roots)
            except BrasKitError:
                self.packages[name] = None
        return self.packages[name]

    def _resolve(self, uri: str) -> tuple[str, str]:
        if uri.startswith(PACKAGE_SCHEME):
            package, _, rest = uri[len(PACKAGE_SCHEME):].partition("/")
            folder = self._package(package)
            if folder is None:
                return "no-package", package
            path = os.path.join(folder, rest)
        elif uri.startswith(FILE_SCHEME):
            path = uri[len(FILE_SCHEME):]
        elif "://" in uri:
            return "remote", uri
        else:
            path = os.path.join(self.folder, uri) if self.folder and not os.path.isabs(uri) else uri
        path = os.path.normpath(path)
        return ("ok" if os.path.isfile(path) else "missing"), path


def _meshes(ctx: Context) -> Iterator[tuple[Link, Geometry, tuple[str, str]]]:
    resolver: MeshResolver | None = None
    for link in ctx.robot.links:
        for element in _shapes(link):
            geometry = element.geometry
            if geometry is None or geometry.kind != "mesh" or not geometry.filename:
                continue
            if resolver is None:
                resolver = MeshResolver(ctx.folder, list(ctx.package_paths))
            yield link, geometry, resolver.resolve(geometry.filename)


@rule("BK402", "mesh-file-missing", ERROR)
def mesh_file_missing(ctx: Context) -> Iterator[Hit]:
    for link, geometry, (status, path) in _meshes(ctx):
        if status == "missing":
            yield hit("link", link.name, geometry.line, link=link.name, filename=geometry.filename, path=path)


@rule("BK403", "package-not-found", WARNING)
def package_not_found(ctx: Context) -> Iterator[Hit]:
    for link, geometry, (status, package) in _meshes(ctx):
        if status == "no-package":
            yield hit("link", link.name, geometry.line, link=link.name, filename=geometry.filename,
                      package=package)


@rule("BK404", "mesh-url-not-fetched", WARNING)
def mesh_url_not_fetched(ctx: Context) -> Iterator[Hit]:
    for link, geometry, (status, url) in _meshes(ctx):
        if status == "remote":
            yield hit("link", link.name, geometry.line, link=link.name, url=url)


def _all_materials(ctx: Context) -> Iterator[tuple[str, str | None, object]]:
    for material in ctx.robot.materials:
        yield "material", material.name, material
    for link in ctx.robot.links:
        for visual in link.visuals:
            if visual.material is not None:
                yield "link", link.name, visual.material


@rule("BK405", "colour-out-of-range", WARNING)
def colour_out_of_range(ctx: Context) -> Iterator[Hit]:
    for element, name, material in _all_materials(ctx):
        rgba = getattr(material, "rgba", None)
        if rgba is None or not all(math.isfinite(v) for v in rgba) or all(0.0 <= v <= 1.0 for v in rgba):
            continue
        scaled = all(0.0 <= v <= 255.0 and v.is_integer() for v in rgba[:3]) and 0.0 <= rgba[3] <= 255.0
        if scaled:  # written as 0..255 bytes: divide by 255 (alpha too, when it was a byte)
            fixed = [v / 255.0 for v in rgba[:3]] + [rgba[3] / 255.0 if rgba[3] > 1 else rgba[3]]
        else:
            fixed = [min(max(v, 0.0), 1.0) for v in rgba]
        yield hit(element, name, getattr(material, "line", None), "255" if scaled else "",
                  material=getattr(material, "name", None) or "", rgba=rgba,
                  fixed=" ".join(number(round(v, 3)) for v in fixed))


@rule("BK406", "material-undefined", WARNING)
def material_undefined(ctx: Context) -> Iterator[Hit]:
    for link in ctx.robot.links:
        for visual in link.visuals:
            m = visual.material
            if m is None or not m.name or m.rgba is not None or m.texture or m.name in ctx.materials:
                continue
            yield hit("link", link.name, m.line or visual.line, link=link.name, material=m.name)
