"""``bras-kit build --symlink-install`` where the workspace is not as colcon left it (the layout itself
is compared with the real colcon's in test_build_colcon_oracle.py)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import colcon_compare

PKG = "bras_description"


def _build(workspace: Path, *extra: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "bras_kit", "build", str(workspace), *extra], cwd=workspace,
                          capture_output=True, text=True, timeout=120)


def test_a_link_planted_as_build_is_never_built_through(tmp_path: Path) -> None:
    workspace = colcon_compare.make_workspace(tmp_path / "ws", "tutorial")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (workspace / "build").symlink_to(elsewhere)
    done = _build(workspace, "--symlink-install")
    assert done.returncode == 1
    assert "Traceback" not in done.stdout + done.stderr
    assert f"{workspace / 'build'} already exists and is not an install folder colcon made" in done.stdout
    assert done.stdout.count(f"Failed   <<< {PKG}") == 1
    assert list(elsewhere.iterdir()) == []


def test_a_file_where_build_pkg_goes_stops_the_build(tmp_path: Path) -> None:
    workspace = colcon_compare.make_workspace(tmp_path, "tutorial")
    (workspace / "build").mkdir()
    (workspace / "build" / PKG).write_text("mine\n")
    done = _build(workspace, "--symlink-install")
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert (workspace / "build" / PKG).read_text() == "mine\n"


def test_symlink_then_copy_then_symlink_again_each_leaves_its_own_tree(tmp_path: Path) -> None:
    workspace = colcon_compare.make_workspace(tmp_path, "tutorial")
    urdf = workspace / "install" / PKG / "share" / PKG / "urdf" / "bras.urdf"
    module = workspace / "install" / PKG / "lib" / f"python{sys.version_info[0]}.{sys.version_info[1]}" \
        / "site-packages" / PKG / "publie.py"
    for extra, linked in (("--symlink-install",), True), ((), False), (("--symlink-install",), True):
        done = _build(workspace, *extra)
        assert done.returncode == 0, done.stdout + done.stderr
        assert urdf.is_symlink() is linked
        assert module.exists() is not linked  # the modules are copied, or found through the egg-link
        assert urdf.read_text() == colcon_compare.colcon_corpus.URDF
    assert os.readlink(workspace / "build" / PKG / "urdf" / "bras.urdf") == str(
        workspace / "src" / PKG / "urdf" / "bras.urdf")
