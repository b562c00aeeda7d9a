"""No module that reads a learner's files goes around the one reader: an AST walk of each such
module finds every call that opens, lists or copies by path (``open``, ``os.listdir``,
``os.scandir``, ``os.walk``, ``glob``, ``shutil.copy*``, ``Path.read_text``/``read_bytes``/
``write_text``/``write_bytes``/``iterdir``/``glob``/``rglob``, ``os.open`` without ``dir_fd``).
Each call left is listed here with why it is not a learner's file; a new one fails the test.

The oracle is the list of Python's path-taking file APIs (the os, shutil, glob, pathlib and
builtins documentation), not the modules under test.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import bras_kit

PACKAGE = Path(bras_kit.__file__).parent

# the modules that read, list or write files on a learner's behalf (the exercise track, the
# package model of validate, build's install tree, the submissions' progress for grade)
MODULES = ["exercises/__init__.py", "exercises/progress.py", "exercises/manifest.py", "exercises/checks.py",
           "exercises/watch.py", "grade/exercises.py", "ros/package.py", "ros/build.py",
           "validate/__init__.py", "grade/worker.py",
           # the robot's own files: includes, meshes (and the files they name), a workspace's crawl, a watch
           "model/authoring.py", "model/xacro.py", "model/xacro_walls.py", "model/xacro_files.py", "model/xmlio.py",
           "meshes/__init__.py", "meshes/decode.py", "render/scene.py", "physics/mjcf.py", "ros/workspace.py",
           "view/watch.py"]

BY_PATH = {"open", "io.open", "os.listdir", "os.scandir", "os.walk", "os.fwalk", "glob.glob", "glob.iglob",
           "shutil.copy", "shutil.copy2", "shutil.copyfile", "shutil.copytree", "shutil.move"}
PATH_METHODS = {"read_text", "read_bytes", "write_text", "write_bytes", "iterdir", "glob", "rglob", "open"}

# (module, function): why the call is not a read of a learner's file
ALLOWED = {
    ("ros/build.py", "_clear_prefix"): "lists bras-kit's own install prefix, after checking it is no link",
    ("ros/build.py", "_find_packages"): "setuptools' find_packages, run in the contained child as setup.py's own",
    ("model/authoring.py", "_expand_template"): "bras-kit's own template and its cache of the expansion",
    # a file the user named (``validate FILE``, ``view FILE``): read by its path; with roots (a package's
    # robot, a submission, a folder's files) the same functions go through learner_files first
    ("model/xacro_files.py", "_read_limited"): "the user's own file when no roots are given (read_beneath else)",
    ("model/xmlio.py", "read_bytes"): "the user's own file when no roots are given (read_beneath else)",
}


def _name(node: ast.expr) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f"{_name(node.value)}.{node.attr}"
    if isinstance(node, ast.Call):
        return f"{_name(node.func)}()"
    return ""


def calls_by_path(source: str) -> list[tuple[str, int, str]]:
    """(function, line, call) of each call that reaches a file by its path."""
    found = []
    tree = ast.parse(source)
    for function in [n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]:
        for node in ast.walk(function):
            if not isinstance(node, ast.Call):
                continue
            name = _name(node.func)
            keywords = {k.arg for k in node.keywords}
            if name in BY_PATH and not (name == "os.scandir" and node.args and not isinstance(node.args[0],
                                                                                             ast.Constant)
                                        and "fd" in ast.unparse(node.args[0])):
                found.append((function.name, node.lineno, name))
            elif name == "os.open" and "dir_fd" not in keywords:
                found.append((function.name, node.lineno, name))
            elif isinstance(node.func, ast.Attribute) and node.func.attr in PATH_METHODS and not name.startswith(
                    ("os.", "json.", "yaml.", "zenoh.", "tarfile.", "gzip.", "bz2.", "lzma.", "self.")):
                found.append((function.name, node.lineno, name))
    return sorted(set(found), key=lambda item: item[1])


@pytest.mark.parametrize("module", MODULES)
def test_no_learner_file_is_read_around_the_reader(module):
    source = (PACKAGE / module).read_text(encoding="utf-8")
    left = [(fn, line, call) for fn, line, call in calls_by_path(source) if (module, fn) not in ALLOWED]
    assert left == [], f"{module}: read through bras_kit.trust.learner_files instead: {left}"


def test_the_walk_finds_each_kind_of_call():
    """The detector itself, on calls written here (each must be found, the descriptor ones not)."""
    source = '''
def f(path, fd):
    open(path)
    os.listdir(path)
    os.walk(path)
    shutil.copyfile(path, "x")
    Path(path).read_text()
    path.iterdir()
    glob.glob("*")
    os.open(path, 0)
    os.open("x", 0, dir_fd=fd)
    os.scandir(fd)
'''
    assert [call for _fn, _line, call in calls_by_path(source)] == [
        "open", "os.listdir", "os.walk", "shutil.copyfile", "Path().read_text", "path.iterdir", "glob.glob", "os.open"]
