"""What breaks physics, and the per-joint report of a run (messages worded in the ``physics`` catalog).

The checks reuse the validator's findings (missing inertials BK505, bad masses and inertias
BK500-BK502, mesh files BK402-BK404) and add what only matters to a simulator: links weighed
by MuJoCo from their shapes, parent and child shapes overlapping at a joint, meshes found
through ``package://`` by bras-kit or converted from DAE.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass

from ..core import backends
from ..core.errors import ModelError
from ..core.i18n import say
from ..core.message import M, Message, Mn
from ..model.robot import Robot
from .mjcf import WATER_DENSITY, MjcfModel

VALIDATOR_CODES = ("BK402", "BK403", "BK404", "BK500", "BK501", "BK502")
MAX_VERDICTS = 5  # joints explained in full sentences; the others are named in one line


@dataclass(frozen=True)
class Note:
    """One diagnostic: ``level`` is ``error``, ``warning`` or ``info``; ``message`` is worded where shown."""

    level: str
    code: str
    message: Message | str

    def worded(self, lang: str | None = None) -> str:
        return say(self.message, lang)


LEVELS = {"error": M("error"), "warning": M("warning"), "info": M("info")}


def check_physics_ready(robot: Robot, lang: str | None = None) -> None:
    """Raise a clear :class:`ModelError` when a moving link has neither ``<inertial>`` nor ``<collision>``.

    The links come from the validator's BK505 (inertial-missing); those with ``<collision>``
    shapes are left to :func:`physics_notes` (MuJoCo weighs them as water).
    """
    from ..validate import validate

    found = validate(robot, select=("BK505",))
    named = {str(name) for f in found for name in f.data.get("links", [])}
    missing = [link.name or "?" for link in robot.links if link.name in named and not link.collisions]
    if missing:
        first = robot.link(missing[0])
        raise ModelError(
            Mn("link {links} moves but has no <inertial>: MuJoCo cannot simulate a body with no mass",
               "{n} links move but have no <inertial>: {links}; MuJoCo cannot simulate a body with no mass",
               len(missing), links=missing),
            path=robot.path, line=first.line if first is not None else None, element="link",
            hint=M("built-in arm: pass --inertials; your own file: give each moving link an <inertial> "
                   "(mass, centre of mass, inertia) — bras-kit validate shows the values for simple shapes"))


def physics_notes(robot: Robot, built: MjcfModel, lang: str | None = None,
                  package_paths: Sequence[str] = ()) -> list[Note]:
    """The validator's findings that matter to physics, then what the MJCF builder had to decide."""
    from ..validate import validate

    frames = _frame_only_links(robot)
    notes = [Note(f.severity, f.code, f"{f.code} {f.text(lang)}")
             for f in validate(robot, package_paths=package_paths,
                               select=VALIDATOR_CODES)
             if not (f.code in ("BK500", "BK501") and f.name in frames)]
    if built.density_links:
        model = built.compile()
        mujoco = backends.mujoco()

        for link in built.density_links:
            body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link)
            notes.append(Note("warning", "density", M(
                "link '{link}' has no <inertial>: MuJoCo weighs it from its <collision> shapes as if they were "
                "water ({density} kg/m³), so it gets {mass:.3g} kg without a word; give it a real <inertial>",
                link=link, density=WATER_DENSITY, mass=float(model.body_mass[body]))))
    if not any(link.collisions for link in robot.links):
        notes.append(Note("info", "no-collision", M("no <collision> shapes: the arm passes through the floor and "
                                                    "itself (built-in arm: --collisions or --inertials)")))
    for parent, child, joint in built.excluded[:MAX_VERDICTS]:
        if joint:
            words = M("'{parent}' and '{child}' touch or overlap at joint '{joint}': they would lock each other, "
                      "so bras-kit excludes contacts between them", parent=parent, child=child, joint=joint)
        else:
            words = M("'{parent}' and '{child}' already overlap at the zero pose: they would push each other "
                      "apart for ever, so bras-kit excludes contacts between them", parent=parent, child=child)
        notes.append(Note("info", "overlap", words))
    if len(built.excluded) > MAX_VERDICTS:
        rest = [f"{parent} / {child}" for parent, child, _ in built.excluded[MAX_VERDICTS:]]
        notes.append(Note("info", "overlap", Mn(
            "{n} more pair touches or overlaps, contacts excluded: {pairs}",
            "{n} more pairs touch or overlap, contacts excluded: {pairs}", len(rest), pairs=rest)))
    shapes = [g for link in robot.links for g in [*(v.geometry for v in link.visuals),
                                                  *(c.geometry for c in link.collisions)]]
    packaged = {g.filename for g in shapes if g is not None and (g.filename or "").startswith("package://")}
    if packaged:
        notes.append(Note("info", "package", Mn(
            "{n} mesh named package://… was found by bras-kit (MuJoCo knows nothing of ROS packages)",
            "{n} meshes named package://… were found by bras-kit (MuJoCo knows nothing of ROS packages)",
            len(packaged))))
    if built.converted:
        names = [os.path.basename(path) for path in built.converted]
        notes.append(Note("info", "converted", Mn(
            "{n} mesh in a format MuJoCo cannot read (DAE) converted to STL through trimesh: {names}",
            "{n} meshes in a format MuJoCo cannot read (DAE) converted to STL through trimesh: {names}",
            len(names), names=names)))
    for actuated in built.actuated:
        if not math.isfinite(actuated.effort):
            notes.append(Note("warning", "no-effort", M(
                "joint '{joint}' has no <limit effort>: its motor has no torque limit here", joint=actuated.joint)))
    return notes


def _frame_only_links(robot: Robot) -> set[str]:
    """Links held by a fixed joint whose <inertial> is all zeros: frames (tool0, ee_link), not bodies."""
    fixed = {j.child for j in robot.joints if j.type == "fixed"} | {link.name for link in robot.links
                                                                  if link.name not in {j.child for j in robot.joints}}
    return {link.name or "" for link in robot.links if link.name in fixed and link.inertial is not None
            and not link.inertial.mass and not any(v for v in link.inertial.inertia.values())}


def _linear(robot: Robot, joint: str) -> bool:
    j = robot.joint(joint)
    return j is not None and j.type == "prismatic"


def _table(rows: list[tuple[str, ...]]) -> list[str]:
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    return ["  ".join(cell.ljust(w) if i in (0, len(row) - 1) else cell.rjust(w)
                      for i, (cell, w) in enumerate(zip(row, widths))).rstrip() for row in rows]


def _header(lang: str | None, *words: Message) -> tuple[str, ...]:
    return tuple(say(word, lang) for word in words)


def dynamics_summary(built: MjcfModel | None) -> Message | None:
    """Where the joints' damping and friction came from, in one sentence."""
    if built is None or not built.dynamics:
        return None
    damped = {joint: value for joint, value in built.dynamics.items() if value[0]}
    rubbing = {joint: value for joint, value in built.dynamics.items() if value[1]}
    if built.damping_given:
        value = next(iter(built.dynamics.values()))[0]
        return M("joint damping {value} N·m·s/rad on every joint (--damping), friction from <dynamics>",
                 value=value)
    if not damped and not rubbing:
        return M("no joint declares <dynamics>: joints without damping or friction, as in Gazebo")
    return M("damping and friction from <dynamics>: {joints}; the other joints have none",
             joints=[M("{joint} (damping {damping}, friction {friction})", joint=joint, damping=value[0],
                       friction=value[1]) for joint, value in built.dynamics.items() if any(value)])


def report_text(robot: Robot, states, lang: str | None = None) -> str:
    """The per-joint table of a run and, in plain words, which motors are too weak."""
    duration = float(states.times[-1]) if len(states) else 0.0
    lines = [say(M("{control} control, {duration} s simulated ({integrator}, time step {timestep} s, motors "
                   "updated at {rate} Hz)", control=states.control, duration=duration,
                   integrator=states.integrator, timestep=states.timestep, rate=states.control_rate), lang)]
    summary = dynamics_summary(states.model)
    if summary is not None:
        lines.append(say(summary, lang))
    if states.control == "none":
        rows = [_header(lang, M("joint"), M("rest position"), M("lower limit"), M("upper limit"),
                        M("beyond the limit"), M("where"))]
        for r in states.report:
            tol = 0.02 * max(1.0, abs(r.upper - r.lower)) if math.isfinite(r.upper - r.lower) else 0.0
            where = M("not a number") if math.isnan(r.final_position) else \
                M("on its lower limit") if r.final_position <= r.lower + tol else \
                M("on its upper limit") if r.final_position >= r.upper - tol else M("between its limits")
            rows.append((r.joint, f"{r.final_position:.3f}", f"{r.lower:g}", f"{r.upper:g}", f"{r.overshoot:.4f}",
                         say(where, lang)))
        touching = [say(M("at the end, touching: {pairs}", pairs=[f"{a} / {b}" for a, b in states.contacts]),
                        lang)] if states.contacts else []
        fell = say(M("motors off: the arm fell under gravity from its start pose"), lang)
        return "\n".join([fell, *lines, *_table(rows), *touching])
    # the headers in words a learner reads without a legend (the errors are in rad, m for a prismatic joint)
    rows = [_header(lang, M("joint"), M("mean error"), M("largest error"), M("peak torque"), M("effort limit"),
                    M("time at limit"), M("torque needed"), M("verdict"))]
    unjudged = False
    for r in states.report:
        unit = "N" if _linear(robot, r.joint) else "N·m"
        effort = f"{r.effort:g} {unit}" if math.isfinite(r.effort) else "-"
        numbers = (r.error_mean, r.error_max, r.peak_torque, r.needed_peak, r.share_at_limit)
        if any(math.isnan(v) for v in numbers):  # never "ok" beside a value that is not a number
            verdict = M("not a number")
            unjudged = True
        elif states.diverged is not None:  # rows computed up to a divergence judge nothing
            verdict = M("no verdict: the simulation diverged")
        else:
            verdict = M("too weak") if r.weak else M("saturates") if r.saturated else M("ok")
        rows.append((r.joint, f"{r.error_mean:.4f}", f"{r.error_max:.4f}", f"{r.peak_torque:.3g} {unit}", effort,
                     f"{r.share_at_limit:.0%}", f"{r.needed_peak:.3g} {unit}", say(verdict, lang)))
    lines += _table(rows)
    weak = [r for r in states.report if r.weak]
    for r in weak[:MAX_VERDICTS]:
        lines.append(say(M("{joint}: the motor is too weak. Following this motion needs up to {needed:.3g} {unit} "
                           "(gravity and acceleration), but <limit effort> allows {effort} {unit}; it spent "
                           "{share:.0%} of the time at that limit and fell behind by up to {error:.2f} {pos}. "
                           "Raise effort, slow the motion down, or lighten the arm.",
                           joint=r.joint, needed=r.needed_peak, effort=r.effort, share=r.share_at_limit,
                           error=r.error_max, unit="N" if _linear(robot, r.joint) else "N·m",
                           pos="m" if _linear(robot, r.joint) else "rad"), lang))
    if len(weak) > MAX_VERDICTS:
        lines.append(say(Mn("{n} more joint is too weak: {joints}", "{n} more joints are too weak: {joints}",
                            len(weak) - MAX_VERDICTS, joints=[r.joint for r in weak[MAX_VERDICTS:]]), lang))
    saturated = [r.joint for r in states.report if r.saturated]
    if saturated:
        lines.append(say(Mn("{joints} sat at its torque limit and fell behind although the motion needs less than "
                            "its effort: the gains (--kp, --kd) or the time step make the motor overshoot; lower "
                            "them or use --integrator implicitfast",
                            "{joints} sat at their torque limits and fell behind although the motion needs less "
                            "than their effort: the gains (--kp, --kd) or the time step make the motors overshoot; "
                            "lower them or use --integrator implicitfast", len(saturated), joints=saturated), lang))
    if not weak and not saturated and states.diverged is None and not unjudged:
        lines.append(say(M("every motor kept up: no joint needed more than its effort"), lang))
    return "\n".join(lines)


def divergence_message(states) -> Message | None:
    """The simulation became unstable: when and on which joint (None when it did not)."""
    if states.diverged is None:
        return None
    return M("the simulation diverged at t = {time:.4f} s: joint '{joint}' became not a number (NaN) or huge",
             time=states.diverged.time, joint=states.diverged.joint)


DIVERGENCE_HINT = M("lower --timestep, use --integrator implicitfast, lower --kp/--kd, or check the masses and "
                    "inertias (bras-kit validate): tiny inertias make a stiff system")
