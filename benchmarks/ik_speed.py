"""Inverse kinematics speed and success: bras-kit against ikpy on the same targets.

    python benchmarks/ik_speed.py [--targets 1000] [--seed 2024] [--repeats 3]

Targets are tip positions of random joint configurations within the limits of the tutorial
arm with its wrist (``poignet``; the tip 0.15 m up the wrist link), so every one is reachable.
Both solvers start from the zero pose and place the tip only (position). A solve succeeds when
the tip, computed by bras-kit's forward kinematics from the returned joints, is within 1e-4 m
of the target and every joint is within its limits: the same criterion for both.

Timing: the targets are cut in chunks of 50; each pass runs every solver on every chunk in
turn, and a chunk's time is its best over the passes, so a burst of other work on the machine
hits all solvers alike and is filtered out. The closed-form solver of the two-joint arm is
timed per call and batched.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import warnings

import numpy as np

from bras_kit.ik import ik_2r, ik_2r_batch, planar_two_link, solve_ik, tip_positions
from bras_kit.kinematics.frames import tf_tree
from bras_kit.model.authoring import arm, arm_urdf

SUCCESS = 1e-4  # m
TIP = (0.0, 0.0, 0.15)
CHUNK = 50


def random_configs(tree, count: int, seed: int) -> np.ndarray:
    lower = np.array([j.bounds()[0] for j in tree.dof_joints()])
    upper = np.array([j.bounds()[1] for j in tree.dof_joints()])
    return np.random.default_rng(seed).uniform(lower, upper, size=(count, len(tree.dof)))


def score(tree, q: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position errors and success flags (error below SUCCESS and joints within limits)."""
    lower = np.array([j.bounds()[0] for j in tree.dof_joints()])
    upper = np.array([j.bounds()[1] for j in tree.dof_joints()])
    errors = np.linalg.norm(tip_positions(tree, q) - targets, axis=1)
    inside = np.all((q >= lower - 1e-9) & (q <= upper + 1e-9), axis=1)
    return errors, (errors < SUCCESS) & inside


def race(solvers: dict, targets: np.ndarray, repeats: int) -> dict[str, tuple[list, float]]:
    """Each solver's answers and time (sum over chunks of the best pass), solvers interleaved."""
    for solve in solvers.values():
        solve(targets[0])  # warm-up
    chunks = [targets[i:i + CHUNK] for i in range(0, len(targets), CHUNK)]
    best = {name: [float("inf")] * len(chunks) for name in solvers}
    answers: dict[str, list] = {name: [None] * len(chunks) for name in solvers}
    for _ in range(repeats):
        for c, chunk in enumerate(chunks):
            for name, solve in solvers.items():
                start = time.perf_counter()
                out = [solve(t) for t in chunk]
                best[name][c] = min(best[name][c], time.perf_counter() - start)
                answers[name][c] = out
    return {name: ([a for chunk in answers[name] for a in chunk], sum(best[name])) for name in solvers}


def ikpy_chain(path: str):  # type: ignore[no-untyped-def]
    from ikpy.chain import Chain

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return Chain.from_urdf_file(path, base_elements=["base"], last_link_vector=list(TIP),
                                    active_links_mask=[False, True, True, True, False])


HEADER = f"{'':46s} {'solves/s':>12s} {'speed':>7s} {'success':>9s} {'median err':>11s} {'max err':>10s}"


def row(name: str, count: int, seconds: float, errors: np.ndarray, ok: np.ndarray,
        reference: float | None = None) -> None:
    rate = count / seconds
    speed = f"{rate / reference:6.1f}x" if reference else ""
    print(f"{name:46s} {rate:12,.0f} {speed:>7s} {100 * ok.mean():8.1f}% {np.median(errors):11.1e} {errors.max():10.1e}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=2024)
    parser.add_argument("--repeats", type=int, default=3, help="passes over the targets; each chunk's best counts")
    args = parser.parse_args()

    wrist = tf_tree(arm(wrist=True))
    targets = tip_positions(wrist, random_configs(wrist, args.targets, args.seed))
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "bras_poignet.urdf")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(arm_urdf(wrist=True))
        chain_ikpy = ikpy_chain(path)
    q = np.random.default_rng(1).uniform(-1, 1, size=(20, 3))
    ikpy_tips = np.array([chain_ikpy.forward_kinematics([0.0, *c, 0.0])[:3, 3] for c in q])
    agreement = np.abs(ikpy_tips - tip_positions(wrist, q)).max()

    print(f"{args.targets} reachable targets of the wrist arm (3 revolute joints, position only), seed {args.seed}")
    print(f"best of {args.repeats} passes per chunk of {CHUNK}; load average {os.getloadavg()[0]:.1f} on "
          f"{os.cpu_count()} CPUs; ikpy and bras-kit forward kinematics agree to {agreement:.1e} m")
    print(f"success: tip error < {SUCCESS:g} m with every joint within its limits")
    print()
    print("numeric, wrist arm" + HEADER[len("numeric, wrist arm"):])

    def ikpy_solve(target):  # type: ignore[no-untyped-def]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return chain_ikpy.inverse_kinematics(target)

    results = race({
        "ikpy": ikpy_solve,
        "bras-kit": lambda t: solve_ik(wrist, t),
        "bras-kit one descent": lambda t: solve_ik(wrist, t, seeds=1),
    }, targets, args.repeats)
    out, seconds = results["ikpy"]
    errors, ok = score(wrist, np.array([o[1:4] for o in out]), targets)
    reference = args.targets / seconds
    row("ikpy Chain.inverse_kinematics", args.targets, seconds, errors, ok)
    for name, label in (("bras-kit", "bras-kit solve_ik (restarts when stuck)"),
                        ("bras-kit one descent", "bras-kit solve_ik, one descent (seeds=1)")):
        out, seconds = results[name]
        errors, ok = score(wrist, np.array([[r.joints[n] for n in wrist.dof] for r in out]), targets)
        row(label, args.targets, seconds, errors, ok, reference)
        iterations = [r.iterations for r in out]
    print(f"  one descent: {np.mean(iterations):.1f} iterations on average, {max(iterations)} at most")

    print()
    print("closed form, tutorial arm" + HEADER[len("closed form, tutorial arm"):])
    tutorial = tf_tree(arm())
    shape = planar_two_link(tutorial)
    targets_2r = tip_positions(tutorial, random_configs(tutorial, args.targets, args.seed))
    results = race({"ik_2r": lambda t: ik_2r(tutorial, t)}, targets_2r, args.repeats)
    out, seconds = results["ik_2r"]
    errors = np.linalg.norm(tip_positions(tutorial, np.array([[r.joints[n] for n in tutorial.dof] for r in out]))
                            - targets_2r, axis=1)
    row("bras-kit ik_2r (one call per target)", args.targets, seconds, errors,
        np.array([r.reachable for r in out]) & (errors < SUCCESS))
    for count in (args.targets, 200_000):
        many = np.resize(targets_2r, (count, 3))
        ik_2r_batch(shape, many[:10])
        seconds = float("inf")
        for _ in range(args.repeats):
            start = time.perf_counter()
            q_up, reached = ik_2r_batch(shape, many, "up")
            seconds = min(seconds, time.perf_counter() - start)
        q_down, _ = ik_2r_batch(shape, many, "down")
        # limits aside: one of the two elbows is the configuration the target came from
        best = np.minimum(np.linalg.norm(tip_positions(tutorial, q_up) - many, axis=1),
                          np.linalg.norm(tip_positions(tutorial, q_down) - many, axis=1))
        row(f"bras-kit ik_2r_batch ({count:,} at once)", count, seconds, best, reached & (best < SUCCESS))


if __name__ == "__main__":
    main()
