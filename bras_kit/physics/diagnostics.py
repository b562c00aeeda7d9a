"""What breaks physics, said in French or English, and the per-joint report of a run.

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

from ..errors import ModelError
from ..model import Robot
from .mjcf import WATER_DENSITY, MjcfModel

VALIDATOR_CODES = ("BK402", "BK403", "BK404", "BK500", "BK501", "BK502")

_TEXT = {
    "en": {
        "massless": "link '{link}' moves but has no <inertial>: MuJoCo cannot simulate a body with no mass",
        "massless_hint": "built-in arm: pass --inertials; your own file: give each moving link an <inertial> "
                         "(mass, centre of mass, inertia) — bras-kit validate shows the values for simple shapes",
        "density": "link '{link}' has no <inertial>: MuJoCo weighs it from its <collision> shapes as if they were "
                   "water ({density:g} kg/m³), so it gets {mass:.3g} kg without a word; give it a real <inertial>",
        "overlap": "'{parent}' and '{child}' touch or overlap at joint '{joint}': they would lock each other, "
                   "so bras-kit excludes contacts between them",
        "overlap_start": "'{parent}' and '{child}' already overlap at the zero pose: they would push each other "
                         "apart for ever, so bras-kit excludes contacts between them",
        "package": "{count} mesh(es) named package://… were found by bras-kit (MuJoCo knows nothing of ROS packages)",
        "converted": "{count} mesh(es) in a format MuJoCo cannot read (DAE) converted to STL through trimesh: {names}",
        "no_effort": "joint '{joint}' has no <limit effort>: its motor has no torque limit here",
        "no_collision": "no <collision> shapes: the arm passes through the floor and itself "
                        "(built-in arm: --collisions or --inertials)",
        "finding": "{code} {message}",
        "header": ("joint", "err.mean", "err.max", "peak torque", "effort", "at limit", "needed", "verdict"),
        "ok": "ok",
        "weak": "too weak",
        "none_header": ("joint", "rest position", "lower", "upper", "past range", "where"),
        "on_lower": "on its lower limit",
        "on_upper": "on its upper limit",
        "between": "between its limits",
        "touching": "at the end, touching: {pairs}",
        "weak_verdict": "{joint}: the motor is too weak. Following this motion needs up to {needed:.3g} {unit} "
                        "(gravity and acceleration), but <limit effort> allows {effort:g} {unit}; it spent "
                        "{share:.0%} of the time at that limit and fell behind by up to {error:.2f} {pos}. "
                        "Raise effort, slow the motion down, or lighten the arm.",
        "all_ok": "every motor kept up: no joint needed more than its effort",
        "fell": "motors off: the arm fell under gravity from its start pose",
        "run": "{control} control, {duration:g} s simulated ({integrator}, time step {timestep:g} s, motors updated "
               "at {rate:g} Hz)",
        "unit_rot": "N·m", "unit_lin": "N", "pos_rot": "rad", "pos_lin": "m",
    },
    "fr": {
        "massless": "le link '{link}' bouge mais n'a pas d'<inertial> : MuJoCo ne peut pas simuler un corps sans masse",
        "massless_hint": "bras intégré : ajoutez --inertials ; votre fichier : donnez un <inertial> (masse, centre de "
                         "masse, inertie) à chaque link mobile — bras-kit validate donne les valeurs des formes simples",
        "density": "le link '{link}' n'a pas d'<inertial> : MuJoCo le pèse d'après ses formes <collision> comme si "
                   "c'était de l'eau ({density:g} kg/m³), il reçoit donc {mass:.3g} kg sans rien dire ; "
                   "donnez-lui un vrai <inertial>",
        "overlap": "'{parent}' et '{child}' se touchent ou se chevauchent au joint '{joint}' : ils se bloqueraient, "
                   "bras-kit exclut donc les contacts entre eux",
        "overlap_start": "'{parent}' et '{child}' se chevauchent déjà à la pose zéro : ils se repousseraient sans "
                         "fin, bras-kit exclut donc les contacts entre eux",
        "package": "{count} maillage(s) nommé(s) package://… trouvé(s) par bras-kit (MuJoCo ignore tout des paquets ROS)",
        "converted": "{count} maillage(s) dans un format que MuJoCo ne lit pas (DAE) converti(s) en STL avec trimesh : "
                     "{names}",
        "no_effort": "le joint '{joint}' n'a pas de <limit effort> : son moteur n'a ici aucune limite de couple",
        "no_collision": "aucune forme <collision> : le bras traverse le sol et lui-même "
                        "(bras intégré : --collisions ou --inertials)",
        "finding": "{code} {message}",
        "header": ("joint", "err.moy", "err.max", "couple max", "effort", "en butée", "requis", "verdict"),
        "ok": "ok",
        "weak": "trop faible",
        "none_header": ("joint", "position finale", "min", "max", "hors plage", "où"),
        "on_lower": "sur sa limite basse",
        "on_upper": "sur sa limite haute",
        "between": "entre ses limites",
        "touching": "à la fin, en contact : {pairs}",
        "weak_verdict": "{joint} : le moteur est trop faible. Suivre ce mouvement demande jusqu'à {needed:.3g} {unit} "
                        "(pesanteur et accélération), mais <limit effort> n'autorise que {effort:g} {unit} ; il est "
                        "resté {share:.0%} du temps à cette limite et a pris jusqu'à {error:.2f} {pos} de retard. "
                        "Augmentez effort, ralentissez le mouvement ou allégez le bras.",
        "all_ok": "tous les moteurs ont suivi : aucun joint n'a demandé plus que son effort",
        "fell": "moteurs coupés : le bras est tombé sous son poids depuis sa pose de départ",
        "run": "commande {control}, {duration:g} s simulées ({integrator}, pas de temps {timestep:g} s, moteurs mis à "
               "jour à {rate:g} Hz)",
        "unit_rot": "N·m", "unit_lin": "N", "pos_rot": "rad", "pos_lin": "m",
    },
}


@dataclass(frozen=True)
class Note:
    """One diagnostic: ``level`` is ``error``, ``warning`` or ``info``."""

    level: str
    code: str
    text: str


def text(lang: str) -> dict:  # type: ignore[type-arg]
    return _TEXT["fr" if lang == "fr" else "en"]


def check_physics_ready(robot: Robot, lang: str = "en") -> None:
    """Raise a clear :class:`ModelError` when a moving link has neither ``<inertial>`` nor ``<collision>``.

    The links come from the validator's BK505 (inertial-missing); those with ``<collision>``
    shapes are left to :func:`physics_notes` (MuJoCo weighs them as water).
    """
    from ..validate import validate

    found = validate(robot, select=("BK505",))
    named = {str(name) for f in found for name in f.data.get("links", [])}
    missing = [link for link in robot.links if link.name in named and not link.collisions]
    if missing:
        words = text(lang)
        names = ", ".join(link.name or "?" for link in missing)
        message = words["massless"].format(link=missing[0].name)
        if len(missing) > 1:
            message += f" ({names})"
        raise ModelError(message, path=robot.path, line=missing[0].line, element="link",
                         hint=words["massless_hint"])


def physics_notes(robot: Robot, built: MjcfModel, lang: str = "en", package_paths: Sequence[str] = ()) -> list[Note]:
    """The validator's findings that matter to physics, then what the MJCF builder had to decide."""
    from ..validate import validate

    words = text(lang)
    frames = _frame_only_links(robot)
    notes = [Note(f.severity, f.code, words["finding"].format(code=f.code, message=f.text(lang)))
             for f in validate(robot, lang=lang, package_paths=package_paths, select=VALIDATOR_CODES)
             if not (f.code in ("BK500", "BK501") and f.name in frames)]
    if built.density_links:
        model = built.compile()
        import mujoco

        for link in built.density_links:
            body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link)
            notes.append(Note("warning", "density", words["density"].format(
                link=link, density=WATER_DENSITY, mass=float(model.body_mass[body]))))
    if not any(link.collisions for link in robot.links):
        notes.append(Note("info", "no-collision", words["no_collision"]))
    for parent, child, joint in built.excluded:
        key = "overlap" if joint else "overlap_start"
        notes.append(Note("info", "overlap", words[key].format(parent=parent, child=child, joint=joint)))
    shapes = [g for link in robot.links for g in [*(v.geometry for v in link.visuals),
                                                  *(c.geometry for c in link.collisions)]]
    packaged = {g.filename for g in shapes if g is not None and (g.filename or "").startswith("package://")}
    if packaged:
        notes.append(Note("info", "package", words["package"].format(count=len(packaged))))
    if built.converted:
        names = [os.path.basename(path) for path in built.converted]
        notes.append(Note("info", "converted", words["converted"].format(
            count=len(names), names=", ".join(names[:6]) + (", …" if len(names) > 6 else ""))))
    for actuated in built.actuated:
        if not math.isfinite(actuated.effort):
            notes.append(Note("warning", "no-effort", words["no_effort"].format(joint=actuated.joint)))
    return notes


def _frame_only_links(robot: Robot) -> set[str]:
    """Links held by a fixed joint whose <inertial> is all zeros: frames (tool0, ee_link), not bodies."""
    fixed = {j.child for j in robot.joints if j.type == "fixed"} | {link.name for link in robot.links
                                                                  if link.name not in {j.child for j in robot.joints}}
    return {link.name or "" for link in robot.links if link.name in fixed and link.inertial is not None
            and not link.inertial.mass and not any(v for v in link.inertial.inertia.values())}


def _units(robot: Robot, joint: str, words: dict) -> tuple[str, str]:  # type: ignore[type-arg]
    j = robot.joint(joint)
    linear = j is not None and j.type == "prismatic"
    return (words["unit_lin"], words["pos_lin"]) if linear else (words["unit_rot"], words["pos_rot"])


def _table(rows: list[tuple[str, ...]]) -> list[str]:
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    return ["  ".join(cell.ljust(w) if i in (0, len(row) - 1) else cell.rjust(w)
                      for i, (cell, w) in enumerate(zip(row, widths))).rstrip() for row in rows]


def report_text(robot: Robot, states, lang: str = "en") -> str:  # type: ignore[no-untyped-def]
    """The per-joint table of a run and, in plain words, which motors are too weak."""
    words = text(lang)
    duration = float(states.times[-1]) if len(states) else 0.0
    lines = [words["run"].format(control=states.control, duration=duration, integrator=states.integrator,
                                 timestep=states.timestep, rate=states.control_rate)]
    if states.control == "none":
        rows = [words["none_header"]]
        for r in states.report:
            tol = 0.02 * max(1.0, abs(r.upper - r.lower)) if math.isfinite(r.upper - r.lower) else 0.0
            where = words["on_lower"] if r.final_position <= r.lower + tol else \
                words["on_upper"] if r.final_position >= r.upper - tol else words["between"]
            rows.append((r.joint, f"{r.final_position:.3f}", f"{r.lower:g}", f"{r.upper:g}", f"{r.overshoot:.4f}", where))
        touching = [words["touching"].format(pairs=", ".join(f"{a} / {b}" for a, b in states.contacts))] \
            if states.contacts else []
        return "\n".join([words["fell"], *lines, *_table(rows), *touching])
    rows = [words["header"]]
    for r in states.report:
        unit, _ = _units(robot, r.joint, words)
        effort = f"{r.effort:g} {unit}" if math.isfinite(r.effort) else "-"
        rows.append((r.joint, f"{r.error_mean:.4f}", f"{r.error_max:.4f}", f"{r.peak_torque:.3g} {unit}", effort,
                     f"{r.share_at_limit:.0%}", f"{r.needed_peak:.3g} {unit}", words["weak"] if r.weak else words["ok"]))
    lines += _table(rows)
    weak = [r for r in states.report if r.weak]
    for r in weak:
        unit, pos = _units(robot, r.joint, words)
        lines.append(words["weak_verdict"].format(joint=r.joint, needed=r.needed_peak, unit=unit, effort=r.effort,
                                                  share=r.share_at_limit, error=r.error_max, pos=pos))
    if not weak:
        lines.append(words["all_ok"])
    return "\n".join(lines)
