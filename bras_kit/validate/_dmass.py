"""libsdformat's arithmetic for merging a fixed link's inertial into its parent, ported line by line,
and ignition-math's test of the result: Gazebo refuses a model whose merged inertia fails it.

Sources: ``src/parser_urdf.cc`` of gazebosim/sdformat, tag ``sdformat12_12.3.0`` (the ODE mass
helpers ``dMassSetParameters``, ``dRFromEulerAngles``, ``dMassRotate``, ``dMassTranslate``,
``dMassAdd`` l. 456-722, and ``ReduceInertialToParent`` l. 760); urdfdom_headers 1.1
(``Rotation::setFromRPY``/``getRPY``); ``MassMatrix3::IsValid`` of ignition-math 6.10 (Debian 12).
The port keeps the original's quirks (the inverse rotation applied as three separate Euler
steps; 0 kg merged into 0 kg gives a NaN centre of mass): the point is to predict what Gazebo
does, not what physics would.
"""

from __future__ import annotations

import functools
import math
import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..model.robot import Inertial, Origin

EPSILON = sys.float_info.epsilon  # np.finfo(float).eps, without importing numpy
TOLERANCE = 10.0  # IGN_MASSMATRIX3_DEFAULT_TOLERANCE


@dataclass
class UrdfInertial:
    """urdf::Inertial as libsdformat holds it: mass, the origin (position and quaternion x y z w), I."""

    mass: float
    position: np.ndarray
    quaternion: tuple[float, float, float, float]
    inertia: np.ndarray  # 3x3, symmetric

    @classmethod
    def read(cls, inertial: Inertial) -> UrdfInertial:
        i = {k: (v if v is not None else 0.0) for k, v in inertial.inertia.items()}
        matrix = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]],
                           [i["ixz"], i["iyz"], i["izz"]]], dtype=float)
        return cls(float(inertial.mass or 0.0), np.array(inertial.origin.xyz, dtype=float),
                   quaternion_from_rpy(*inertial.origin.rpy), matrix)

    @classmethod
    def empty(cls) -> UrdfInertial:
        return cls(0.0, np.zeros(3), (0.0, 0.0, 0.0, 1.0), np.zeros((3, 3)))


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    """urdf::Rotation::setFromRPY (normalised)."""
    if roll == pitch == yaw == 0.0 and math.copysign(1.0, roll) + math.copysign(1.0, pitch) \
            + math.copysign(1.0, yaw) == 3.0:
        return (0.0, 0.0, 0.0, 1.0)  # what the formula gives for +0 angles, most inertials' rpy
    phi, the, psi = roll / 2.0, pitch / 2.0, yaw / 2.0
    x = math.sin(phi) * math.cos(the) * math.cos(psi) - math.cos(phi) * math.sin(the) * math.sin(psi)
    y = math.cos(phi) * math.sin(the) * math.cos(psi) + math.sin(phi) * math.cos(the) * math.sin(psi)
    z = math.cos(phi) * math.cos(the) * math.sin(psi) - math.sin(phi) * math.sin(the) * math.cos(psi)
    w = math.cos(phi) * math.cos(the) * math.cos(psi) + math.sin(phi) * math.sin(the) * math.sin(psi)
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    if norm == 0:
        return (0.0, 0.0, 0.0, 1.0)
    return (x / norm, y / norm, z / norm, w / norm)


def rpy_from_quaternion(q: tuple[float, float, float, float]) -> tuple[float, float, float]:
    """urdf::Rotation::getRPY."""
    x, y, z, w = q
    sarg = -2 * (x * z - w * y)
    if sarg <= -0.99999:
        return 0.0, -math.pi / 2, 2 * math.atan2(x, -y)
    if sarg >= 0.99999:
        return 0.0, math.pi / 2, 2 * math.atan2(-x, y)
    return (math.atan2(2 * (y * z + w * x), w * w - x * x - y * y + z * z), math.asin(sarg),
            math.atan2(2 * (x * y + w * z), w * w + x * x - y * y - z * z))


def euler_matrix(phi: float, theta: float, psi: float) -> np.ndarray:
    """dRFromEulerAngles."""
    sphi, cphi, sthe, cthe, spsi, cpsi = (math.sin(phi), math.cos(phi), math.sin(theta), math.cos(theta),
                                          math.sin(psi), math.cos(psi))
    return np.array([
        [cpsi * cthe, spsi * cthe, -sthe],
        [cpsi * sthe * sphi - spsi * cphi, spsi * sthe * sphi + cpsi * cphi, cthe * sphi],
        [cpsi * sthe * cphi + spsi * sphi, spsi * sthe * cphi - cpsi * sphi, cthe * cphi],
    ])


@dataclass
class DMass:
    """ODE's dMass: a mass, its centre and its inertia about that centre."""

    mass: float
    c: np.ndarray
    inertia: np.ndarray

    def rotate(self, r: np.ndarray) -> None:
        """dMassRotate: I = R I R', c = R c."""
        inertia = r @ (self.inertia @ r.T)
        inertia[1, 0], inertia[2, 0], inertia[2, 1] = inertia[0, 1], inertia[0, 2], inertia[1, 2]
        self.inertia = inertia
        self.c = r @ self.c

    def translate(self, offset: np.ndarray) -> None:
        """dMassTranslate: I += mass (chat^2 - ahat^2), a = c + offset; c += offset."""
        a = self.c + offset
        chat, ahat = _cross(self.c), _cross(a)
        inertia = self.inertia + self.mass * (chat @ chat - ahat @ ahat)
        inertia[1, 0], inertia[2, 0], inertia[2, 1] = inertia[0, 1], inertia[0, 2], inertia[1, 2]
        self.inertia = inertia
        self.c = self.c + offset

    def add(self, other: DMass) -> None:
        """dMassAdd: the centre of mass weighted by mass, divided by the sum (0/0 is NaN in C)."""
        total = self.mass + other.mass
        weighted = self.c * self.mass + other.c * other.mass
        with np.errstate(divide="ignore", invalid="ignore"):
            self.c = weighted * (np.float64(1.0) / np.float64(total)) if total != 0 else weighted * np.inf
        self.mass = total
        self.inertia = self.inertia + other.inertia


def _cross(a: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _unrotate(mass: DMass, quaternion: tuple[float, float, float, float]) -> None:
    phi, theta, psi = rpy_from_quaternion(quaternion)
    mass.rotate(euler_matrix(-phi, 0, 0))
    mass.rotate(euler_matrix(0, -theta, 0))
    mass.rotate(euler_matrix(0, 0, -psi))


def merge_into_parent(parent: UrdfInertial | None, child: UrdfInertial, joint: Origin) -> UrdfInertial:
    """ReduceInertialToParent: the parent's inertial once the child (on a fixed joint at ``joint``)
    is merged into it (a parent without one gets an empty one first)."""
    parent = parent if parent is not None else UrdfInertial.empty()
    with np.errstate(invalid="ignore", over="ignore"):
        parent_mass = DMass(parent.mass, np.zeros(3), parent.inertia.copy())
        _unrotate(parent_mass, parent.quaternion)
        parent_mass.translate(parent.position)
        link_mass = DMass(child.mass, np.zeros(3), child.inertia.copy())
        _unrotate(link_mass, child.quaternion)
        link_mass.translate(child.position)
        _unrotate(link_mass, quaternion_from_rpy(*joint.rpy))
        link_mass.translate(np.array(joint.xyz, dtype=float))
        parent_mass.add(link_mass)
        position = parent_mass.c.copy()
        parent_mass.translate(-position)
        phi, theta, psi = rpy_from_quaternion(parent.quaternion)
        parent_mass.rotate(euler_matrix(phi, theta, psi))
    return UrdfInertial(parent_mass.mass, position, parent.quaternion, parent_mass.inertia)


def _printed(value: float) -> float:
    """A value as CreateInertial writes it (16 significant digits) and the SDF reader reads it back."""
    return float(f"{value:.16g}") if math.isfinite(value) else value


def principal_moments(inertia: np.ndarray) -> tuple[float, float, float]:
    """MassMatrix3::PrincipalMoments (Kronenburg's closed form; the diagonal when products are ~0)."""
    d = [inertia[0, 0], inertia[1, 1], inertia[2, 2]]
    p_ = [inertia[0, 1], inertia[0, 2], inertia[1, 2]]
    tol = 1e-6 * max(d)
    if all(abs(v) <= tol for v in p_):
        return (d[0], d[1], d[2])
    b = sum(d)
    c = d[0] * d[1] - p_[0] ** 2 + d[0] * d[2] - p_[1] ** 2 + d[1] * d[2] - p_[2] ** 2
    dd = d[0] * p_[2] ** 2 + d[1] * p_[1] ** 2 + d[2] * p_[0] ** 2 - d[0] * d[1] * d[2] - 2 * p_[0] * p_[1] * p_[2]
    p = b * b - 3 * c
    if p < tol * tol:
        return (b / 3.0, b / 3.0, b / 3.0)
    q = 2 * b ** 3 - 9 * b * c - 27 * dd
    delta = math.acos(min(max(0.5 * q / p ** 1.5, -1.0), 1.0))
    moments = sorted([(b + 2 * math.sqrt(p) * math.cos(delta / 3.0)) / 3.0,
                      (b + 2 * math.sqrt(p) * math.cos((delta + 2 * math.pi) / 3.0)) / 3.0,
                      (b + 2 * math.sqrt(p) * math.cos((delta - 2 * math.pi) / 3.0)) / 3.0])
    return (moments[0], moments[1], moments[2])


def _epsilon(moments: tuple[float, float, float]) -> float:
    return TOLERANCE * float(EPSILON) * 0.5 * abs(sum(moments))


def valid_mass_matrix(inertial: UrdfInertial) -> bool:
    """MassMatrix3::IsValid: IsNearPositive and ValidMoments(PrincipalMoments())."""
    return _valid(float(inertial.mass), tuple(inertial.inertia.ravel().tolist()))


# a generated robot repeats one inertial on thousands of links: each distinct one is judged once
@functools.lru_cache(maxsize=4096)
def _valid(raw_mass: float, inertia: tuple[float, ...]) -> bool:
    mass = _printed(raw_mass)
    m = np.array([_printed(v) for v in inertia]).reshape(3, 3)
    if not (math.isfinite(mass) and np.isfinite(m).all()):
        return False
    with np.errstate(over="ignore", invalid="ignore"):  # gz-math's doubles overflow to inf silently
        eps = _epsilon((m[0, 0], m[1, 1], m[2, 2]))
        near_positive = (mass >= 0 and m[0, 0] + eps >= 0 and m[0, 0] * m[1, 1] - m[0, 1] ** 2 + eps >= 0
                         and float(np.linalg.det(m)) + eps >= 0)
        if not near_positive:
            return False
        a, b, c = principal_moments(m)
    eps = _epsilon((a, b, c))
    return (a + eps >= 0 and b + eps >= 0 and c + eps >= 0 and a + b + eps >= c and b + c + eps >= a
            and c + a + eps >= b)


def finite_pose(inertial: UrdfInertial) -> bool:
    return all(math.isfinite(v) for v in inertial.position.tolist())  # numpy's isfinite costs more on 3 values
