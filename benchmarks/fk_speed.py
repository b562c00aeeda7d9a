"""Forward-kinematics poses per second on the tutorial arm: bras-kit batched and single vs yourdfpy.

Run: python benchmarks/fk_speed.py [--poses N]
Prints one table; the figures are for the whole transform set (every link) of each pose.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

import numpy as np

from bras_kit.kinematics.frames import fk, fk_batch, tf_tree
from bras_kit.model.authoring import arm, arm_urdf


def best_of(repeats: int, func) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--chunk", type=int, default=100_000)
    args = parser.parse_args()

    tree = tf_tree(arm())
    rng = np.random.default_rng(0)
    q = rng.uniform(-1.5, 1.5, size=(args.poses, len(tree.dof)))

    def batched() -> None:
        for start in range(0, args.poses, args.chunk):
            fk_batch(tree, q[start:start + args.chunk])

    t_batch = best_of(3, batched)
    singles = 20_000
    configs = [dict(zip(tree.dof, row)) for row in q[:singles]]
    t_single = best_of(3, lambda: [fk(tree, c) for c in configs])

    import yourdfpy

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bras.urdf")
        with open(path, "w") as handle:
            handle.write(arm_urdf())
        model = yourdfpy.URDF.load(path, build_scene_graph=True, load_meshes=False)
    peer_poses = 5_000
    links = list(tree.links)

    def peer() -> None:
        for row in q[:peer_poses]:
            model.update_cfg(row)
            for link in links:
                model.get_transform(link)

    t_peer = best_of(3, peer)
    # same answer check (avant_bras of the last pose)
    ours = fk(tree, dict(zip(tree.dof, q[peer_poses - 1])))["avant_bras"]
    assert np.allclose(ours, model.get_transform("avant_bras"), atol=1e-12), "peer disagrees"

    rows = [
        (f"bras-kit fk_batch (chunks of {args.chunk})", args.poses / t_batch),
        ("bras-kit fk (one pose per call)", singles / t_single),
        ("yourdfpy update_cfg + get_transform", peer_poses / t_peer),
    ]
    print(f"FK, tutorial arm ({len(tree.links)} links, {len(tree.dof)} joints), all links per pose")
    print(f"{'method':45s} {'poses/s':>14s}")
    for name, rate in rows:
        print(f"{name:45s} {rate:14,.0f}")
    print(f"batched / yourdfpy: {rows[0][1] / rows[2][1]:,.0f}x")


if __name__ == "__main__":
    main()
