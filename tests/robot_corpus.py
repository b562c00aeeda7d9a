"""Where the real robot descriptions of the dev extra live (example-robot-data, rtb-data) and the
pybullet_data copy under tests/data: the corpus the mesh, validator, render and Gazebo tests share."""

from __future__ import annotations

import site
from pathlib import Path


def _share() -> Path:
    for base in map(Path, site.getsitepackages()):
        if (base / "cmeel.prefix" / "share" / "example-robot-data").is_dir():
            return base / "cmeel.prefix" / "share"
    raise AssertionError("example-robot-data (the dev extra) is needed for these tests")


def _packages() -> tuple[dict[str, Path], list[str]]:
    trees, roots = {}, []
    for base in map(Path, site.getsitepackages()):
        if (base / "cmeel.prefix" / "share" / "example-robot-data").is_dir():
            trees["example-robot-data"] = base / "cmeel.prefix" / "share" / "example-robot-data"
            roots.append(str(base / "cmeel.prefix" / "share"))
        if (base / "rtbdata").is_dir():
            rtb = base / "rtbdata"
            trees["rtb-data"] = rtb
            roots += [str(rtb / "xacro"), str(rtb / "xacro" / "kuka_description"),
                      str(rtb / "armer_xarm" / "data" / "xacro"), str(rtb / "meshes"), str(rtb)]
    trees["pybullet_data"] = Path(__file__).parent / "data" / "real_robots" / "pybullet_data"
    return trees, roots


SHARE = _share()  # example-robot-data's share folder (a package path: package://X/ is SHARE/X/)
ROBOTS = SHARE / "example-robot-data" / "robots"
TREES, ROOTS = _packages()  # package name -> its tree; the package paths their files need
