"""The three ways the motors can behave: off, PD servo, PD servo with gravity compensation.

The PD law runs inside MuJoCo (a ``general`` actuator with ``gain = kp`` and
``bias = -kp q - kd qdot``), so it is applied at every physics step with no Python in the loop.
Python only moves the set point: feeding ``ctrl = q_ref + (kd / kp) qdot_ref`` makes the motor
force ``kp (q_ref - q) + kd (qdot_ref - qdot)``, the textbook PD tracking law.

Gravity compensation is MuJoCo's own: with ``gravcomp="1"`` on every body and
``actuatorgravcomp`` on every joint, the torque that cancels gravity (the gravity part of
``qfrc_bias``) is added to the motor force, and the total is clipped at ``<limit effort>`` like a
real drive would clip it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M

CONTROLS = ("none", "pd", "pd+gravity")


def check_control(control: str) -> str:
    if control not in CONTROLS:
        raise ParameterError(M("unknown control '{name}'", name=control),
                             hint=M("use none (motors off), pd (track the motion) or pd+gravity (and cancel gravity)"))
    return control


def gain_vector(value: float | Mapping[str, float], joints: Sequence[str], default: float, what: str) -> np.ndarray:
    """One gain per joint from a number or a {joint: gain} mapping; gains must be positive numbers."""
    if isinstance(value, Mapping):
        unknown = sorted(set(value) - set(joints))
        if unknown:
            raise ParameterError(M("{what} for unknown joint '{joint}'", what=what, joint=unknown[0]),
                                 hint=M("the joints are {names}", names=list(joints)))
        gains = np.array([float(value.get(j, default)) for j in joints])
    else:
        gains = np.full(len(joints), float(value))
    if not np.all(np.isfinite(gains)) or np.any(gains <= 0):
        raise ParameterError(M("{what} must be positive numbers, got {values}", what=what, values=list(gains)),
                             hint=M("e.g. --{what} {value}", what=what, value=default))
    return gains


def servo_setpoints(q_ref: np.ndarray, qd_ref: np.ndarray, kp: np.ndarray, kd: np.ndarray) -> np.ndarray:
    """The ``ctrl`` values that make MuJoCo's servo apply ``kp (q_ref - q) + kd (qd_ref - qd)``."""
    return q_ref + (kd / kp) * qd_ref
