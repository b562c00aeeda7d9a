"""Physics with MuJoCo: the MJCF built from the model, simulation runs, motors, diagnostics.

Modules import one way: controllers <- mjcf <- diagnostics <- run; plot reads the states.
"""

from __future__ import annotations

from .controllers import CONTROLS
from .mjcf import (
    DEFAULT_INTEGRATOR,
    DEFAULT_KD,
    DEFAULT_KP,
    DEFAULT_TIMESTEP,
    MjcfModel,
    build_mjcf,
)
from .run import JointReport, SimulatedStates, simulate

__all__ = [
    "CONTROLS",
    "DEFAULT_INTEGRATOR",
    "DEFAULT_KD",
    "DEFAULT_KP",
    "DEFAULT_TIMESTEP",
    "JointReport",
    "MjcfModel",
    "SimulatedStates",
    "build_mjcf",
    "simulate",
]
