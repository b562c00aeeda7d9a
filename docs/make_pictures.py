"""Draw the pictures of the documentation site with the library (not the CLI).

    python docs/make_pictures.py              # into docs/img/
    python docs/make_pictures.py --out DIR    # somewhere else (the tests do this)

The pictures are small (about 0.6 MB together) and kept in git, so `mkdocs build` needs no
rendering; rerun this script when the arm, the renderer or the diagrams change. They are drawn
from the same calls the lessons make, at sizes fit for a web page.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
POSES = [{}, {"epaule": 0.8}, {"epaule": -0.5, "coude": 1.5}, {"epaule": 1.2, "coude": -2.0}]


def poses(path: Path) -> None:
    """The tutorial arm at four poses, with its frame axes (lesson 3)."""
    from bras_kit import arm
    from bras_kit.render import render_pose, save_png

    robot = arm()
    row = [render_pose(robot, pose, size=(240, 240), tf=True) for pose in POSES]
    save_png(np.hstack(row), path)


def frames(path: Path) -> None:
    """The frame tree at a pose, like view_frames (lesson 2)."""
    from bras_kit import arm
    from bras_kit.diagrams import frame_diagram

    frame_diagram(arm(), {"epaule": 0.5, "coude": -0.8}, path=path)


def motion_gif(path: Path) -> None:
    """The tutorial's sine motion, one period of the elbow, 10 pictures a second (lesson 5)."""
    from bras_kit import arm
    from bras_kit.motion import sample, tutorial_motion
    from bras_kit.render import render_motion, save_gif

    robot = arm()
    states = sample(tutorial_motion(robot), duration=9.0, rate=10.0)
    save_gif(render_motion(robot, states, size=(320, 240), progress=False), path, fps=10)


def angles(path: Path) -> None:
    """Joint angles against their limits and the tip's path (lesson 5)."""
    from bras_kit import arm
    from bras_kit.diagrams import plot_motion
    from bras_kit.motion import sample, tutorial_motion

    robot = arm()
    plot_motion(robot, sample(tutorial_motion(robot), duration=10.0), path=path)


def wrist(path: Path) -> None:
    """The arm with the exercise's wrist joint 'poignet' (lesson 6)."""
    from bras_kit import arm
    from bras_kit.render import render_pose, save_png

    save_png(render_pose(arm(wrist=True), {"epaule": 0.5, "coude": 0.9, "poignet": 1.0},
                         size=(320, 320), view="front", tf=True), path)


def reach(path: Path) -> None:
    """Both elbow solutions of the inverse kinematics for one target (lesson 9)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from bras_kit import arm, fk, tf_tree
    from bras_kit.ik import ik_2r

    robot = arm()
    tree = tf_tree(robot)
    target = (0.6, 0.0, 0.7)
    result = ik_2r(robot, target)
    fig, ax = plt.subplots(figsize=(4.5, 4.5))
    for solution, colour in zip(result.solutions, ("tab:blue", "tab:orange")):
        poses = fk(tree, solution.joints)
        tip = poses["avant_bras"] @ [0, 0, 0.5, 1]
        points = [(0, 0), (poses["bras"][0, 3], poses["bras"][2, 3]),
                  (poses["avant_bras"][0, 3], poses["avant_bras"][2, 3]), (tip[0], tip[2])]
        xs, zs = zip(*points)
        ax.plot(xs, zs, "o-", lw=4, color=colour, label=f"elbow {solution.elbow}")
    ax.plot(target[0], target[2], "k*", ms=15, label="target")
    ax.add_patch(plt.Circle((0, 0.05), 1.1, fill=False, ls=":", color="grey"))
    ax.set_aspect("equal")
    ax.set_xlim(-1.2, 1.2)
    ax.set_ylim(-0.6, 1.3)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.legend(loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


PICTURES: dict[str, Callable[[Path], None]] = {
    "poses.png": poses,
    "frames.png": frames,
    "bras.gif": motion_gif,
    "angles.png": angles,
    "wrist.png": wrist,
    "reach.png": reach,
}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=HERE / "img", help="folder for the pictures")
    parser.add_argument("names", nargs="*", metavar="NAME",
                        help="only these pictures (default: all): " + ", ".join(PICTURES))
    args = parser.parse_args(argv)
    unknown = [name for name in args.names if name not in PICTURES]
    if unknown:
        parser.error(f"unknown picture {unknown[0]!r}; choose from " + ", ".join(PICTURES))
    args.out.mkdir(parents=True, exist_ok=True)
    for name in args.names or PICTURES:
        path = args.out / name
        PICTURES[name](path)
        print(f"wrote {path} ({path.stat().st_size // 1024} KB)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
