"""Inverse kinematics: joint values that put the tip of the arm at a target.

- :mod:`.analytic`: closed form for two revolute joints on parallel axes (:func:`ik_2r`), both
  elbows, with the reason a target fails.
- :mod:`.numeric`: damped least squares for any serial chain, within the joint limits
  (:func:`solve_chain`); :func:`solve_ik` (:mod:`.solve`) picks the solver.
- :mod:`.chain`: the chain to the tip (:func:`serial_chain`), :func:`jacobian`, :func:`tip_positions`.
- :mod:`.reaching`: the move to a solution within the velocity limits (:func:`reach_motion`).
- :mod:`.workspace`: where the tip can go (:func:`workspace_points`, :func:`workspace_figure`).

The tip is a point fixed in a link, by default that of :func:`bras_kit.kinematics.tip.tool_tip`.
"""

from ._inputs import Vector
from ._limits import TWO_PI
from .analytic import (
    PLANE_TOLERANCE,
    SINGULAR_TOLERANCE,
    PlanarTwoLink,
    ik_2r,
    ik_2r_batch,
    planar_two_link,
)
from .chain import SerialChain, jacobian, resolve_tip, serial_chain, tip_positions
from .numeric import ACCEPT, MAX_ITERATIONS, SAME_MINIMUM, SEEDS, solve_chain
from .reaching import QUINTIC_PEAK, ReachMotion, minimum_duration, motion_violations, reach_motion
from .results import ElbowSolution, IKResult, LimitExcess
from .solve import solve_ik
from .workspace import WorkspaceSummary, workspace_figure, workspace_points

__all__ = [
    "ACCEPT",
    "MAX_ITERATIONS",
    "PLANE_TOLERANCE",
    "QUINTIC_PEAK",
    "SAME_MINIMUM",
    "SEEDS",
    "SINGULAR_TOLERANCE",
    "TWO_PI",
    "ElbowSolution",
    "IKResult",
    "LimitExcess",
    "PlanarTwoLink",
    "ReachMotion",
    "SerialChain",
    "Vector",
    "WorkspaceSummary",
    "ik_2r",
    "ik_2r_batch",
    "jacobian",
    "minimum_duration",
    "motion_violations",
    "planar_two_link",
    "reach_motion",
    "resolve_tip",
    "serial_chain",
    "solve_chain",
    "solve_ik",
    "tip_positions",
    "workspace_figure",
    "workspace_points",
]
