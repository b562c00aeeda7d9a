"""Inverse kinematics speed and success: bras-kit against ikpy on the same targets.

    python benchmarks/ik_speed.py [--targets 1000] [--seed 2024]

Targets are tip positions of random joint configurations within the limits of the tutorial
arm with its wrist (``poignet``; the tip 0.15 m up the wrist link), so every one is reachable.
Both solvers start from the zero pose and place the tip only (position). A solve succeeds when
the tip, computed by bras-kit's forward kinematics from the returned joints, is within 1e-4 m
of the target and every joint is within its limits: the same criterion for both.
The closed-form solver of the two-joint arm is timed per call and batched.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings

import numpy as np

from bras_kit.authoring import arm, arm_urdf
from bras_kit.ik import ik_2r, ik_2r_batch, planar_two_link, serial_chain, solve_chain, solve_ik, tip_positions
from bras_kit.kinematics import tf_tree

SUCCESS = 1e-4  # m
TIP = (0.0, 0.0, 0.15)


def random_targets(tree, count: int, seed: int) -> np.ndarray:
    lower = np.array([j.bounds()[0] for j in tree.dof_joints()])
    upper = np.array([j.bounds()[1] for j in tree.dof_joints()])
    q = np.random.default_rng(seed).uniform(lower, upper, size=(count, len(tree.dof)))
    return tip_positions(tree, q)


def score(tree, q: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position errors and success flags (error below SUCCESS and joints within limits)."""
    lower = np.array([j.bounds()[0] for j in tree.dof_joints()])
    upper = np.array([j.bounds()[1] for j in tree.dof_joints()])
    errors = np.linalg.norm(tip_positions(tree, q) - targets, axis=1)
    inside = np.all((q >= lower - 1e-9) & (q <= upper + 1e-9), axis=1)
    return errors, (errors < SUCCESS) & inside


def timed(function, targets):  # type: ignore[no-untyped-def]
    function(targets[0])  # warm-up
    start = time.perf_counter()
    out = [function(t) for t in targets]
    return out, time.perf_counter() - start


def ikpy_chain(path: str):  # type: ignore[no-untyped-def]
    from ikpy.chain import Chain

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return Chain.from_urdf_file(path, base_elements=["base"], last_link_vector=list(TIP),
                                    active_links_mask=[False, True, True, True, False])


def row(name: str, count: int, seconds: float, errors: np.ndarray | None, ok: np.ndarray | None,
        reference: float | None = None) -> None:
    rate = count / seconds
    speed = f"{rate / reference:6.1f}x" if reference else "      "
    if errors is None:
        print(f"{name:44s} {rate:12,.0f} {speed}")
        return
    print(f"{name:44s} {rate:12,.0f} {speed} {100 * ok.mean():8.1f}% {np.median(errors):11.1e} {errors.max():10.1e}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=2024)
    args = parser.parse_args()

    wrist = tf_tree(arm(wrist=True))
    targets = random_targets(wrist, args.targets, args.seed)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "bras_poignet.urdf")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(arm_urdf(wrist=True))
        chain_ikpy = ikpy_chain(path)

    # the two models agree on where the tip is
    q = np.random.default_rng(1).uniform(-1, 1, size=(20, 3))
    ikpy_tips = np.array([chain_ikpy.forward_kinematics([0.0, *c, 0.0])[:3, 3] for c in q])
    agreement = np.abs(ikpy_tips - tip_positions(wrist, q)).max()

    print(f"{args.targets} reachable targets of the wrist arm (3 revolute joints, position only), seed {args.seed}")
    print(f"ikpy and bras-kit forward kinematics agree to {agreement:.1e} m; success: error < {SUCCESS:g} m within limits")
    print()
    print(f"{'solver':44s} {'solves/s':>12s} {'speed':>7s} {'success':>9s} {'median err':>11s} {'max err':>10s}")

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out, seconds = timed(lambda t: chain_ikpy.inverse_kinematics(t), targets)
    q_ikpy = np.array([o[1:4] for o in out])
    errors, ok = score(wrist, q_ikpy, targets)
    reference = args.targets / seconds
    row("ikpy Chain.inverse_kinematics", args.targets, seconds, errors, ok)

    out, seconds = timed(lambda t: solve_ik(wrist, t), targets)
    q_ours = np.array([[r.joints[n] for n in wrist.dof] for r in out])
    errors, ok = score(wrist, q_ours, targets)
    row("bras-kit solve_ik (8 seeds in one batch)", args.targets, seconds, errors, ok, reference)

    chain = serial_chain(wrist)
    out, seconds = timed(lambda t: solve_chain(chain, t), targets)
    q_ours = np.array([[r.joints[n] for n in wrist.dof] for r in out])
    errors, ok = score(wrist, q_ours, targets)
    row("bras-kit solve_chain (chain compiled once)", args.targets, seconds, errors, ok, reference)

    out, seconds = timed(lambda t: solve_chain(chain, t, seeds=1), targets)
    q_ours = np.array([[r.joints[n] for n in wrist.dof] for r in out])
    errors, ok = score(wrist, q_ours, targets)
    row("bras-kit solve_chain, 1 seed (+ restarts)", args.targets, seconds, errors, ok, reference)

    print()
    tutorial = tf_tree(arm())
    shape = planar_two_link(tutorial)
    targets_2r = tip_positions(tutorial, np.random.default_rng(args.seed).uniform(
        [-1.57, -2.0], [1.57, 2.0], size=(args.targets, 2)))
    out, seconds = timed(lambda t: ik_2r(tutorial, t), targets_2r)
    q_2r = np.array([[r.joints[n] for n in tutorial.dof] for r in out])
    errors = np.linalg.norm(tip_positions(tutorial, q_2r) - targets_2r, axis=1)
    ok = np.array([r.reachable for r in out]) & (errors < SUCCESS)
    print(f"{'closed form, tutorial arm (2 joints)':44s} {'solves/s':>12s} {'':7s} {'success':>9s} {'median err':>11s} {'max err':>10s}")
    row("bras-kit ik_2r (one call per target)", args.targets, seconds, errors, ok)
    for count in (args.targets, 1_000_000):
        many = np.resize(targets_2r, (count, 3))
        ik_2r_batch(shape, many[:10])
        start = time.perf_counter()
        q_batch, reached = ik_2r_batch(shape, many, "up")
        seconds = time.perf_counter() - start
        down, _ = ik_2r_batch(shape, many, "down")
        best = np.minimum(np.linalg.norm(tip_positions(tutorial, q_batch) - many, axis=1),
                          np.linalg.norm(tip_positions(tutorial, down) - many, axis=1))
        row(f"bras-kit ik_2r_batch ({count:,} targets at once)", count, seconds, best, reached & (best < SUCCESS))


if __name__ == "__main__":
    main()
